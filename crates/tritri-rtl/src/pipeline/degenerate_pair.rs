//! Two degenerate triangles: do the segments `[a, b]` (T1's lexicographic
//! ends) and `[c, d]` (T2's) meet? Either may be a point.
//!
//! Software model: `degenerate_pair` in devillers_guigue.rs. They meet iff
//! the four ends are coplanar (`orient3d(a, b, c, d) == 0`, computed by the
//! shared orient3d unit 0 and checked in `decision`) and the 2D segment
//! test holds in all three axis projections (each is necessary, and at
//! least one is one-to-one on a plane through all four points). This unit
//! computes the three 2D tests. The orient2d values of all three
//! projections are the components of four cross products:
//! `[a, b, c] = (b - a) × (c - a)`, `[a, b, d]`, `[c, d, a]`, `[c, d, b]`.
//!
//! Stages: end selection (1), differences and comparisons (1), cross
//! products (4), signs (1), decision (1).

use super::rare_decisions::{SegmentContacts, SegmentsDecision, SEGMENTS_DECISION_LATENCY};
use crate::arith::compare::{CoordinateCompare, COMPARE_LATENCY};
use crate::arith::cross_product::{CrossProduct, CROSS_PRODUCT_LATENCY};
use crate::arith::delay_line::DelayLine;
use crate::arith::sign::{SignOf, SIGN_LATENCY};
use crate::arith::subtractor::{VectorSubtractor, SUBTRACTOR_LATENCY};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from inputs to `hit`.
pub const DEGENERATE_PAIR_LATENCY: usize =
    1 + SUBTRACTOR_LATENCY + CROSS_PRODUCT_LATENCY + SIGN_LATENCY + SEGMENTS_DECISION_LATENCY;
const ON_SEGMENT_DELAY: usize = CROSS_PRODUCT_LATENCY + SIGN_LATENCY;
const _: () = assert!(COMPARE_LATENCY == SUBTRACTOR_LATENCY);

#[derive(LogicBlock, Default)]
pub struct DegeneratePair<const W: usize, const D: usize, const C: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub t1_vertices: [Signal<In, Bits<W>>; 9],
    pub t2_vertices: [Signal<In, Bits<W>>; 9],
    pub t1_segment_low: Signal<In, Bits<2>>,
    pub t1_segment_high: Signal<In, Bits<2>>,
    pub t2_segment_low: Signal<In, Bits<2>>,
    pub t2_segment_high: Signal<In, Bits<2>>,
    /// The projections of `[a, b]` and `[c, d]` meet along all three axes,
    /// `DEGENERATE_PAIR_LATENCY` edges later.
    pub hit: Signal<Out, Bit>,
    /// `a, b, c, d`: coordinate `k` of end `j` at `3 j + k`.
    ends_q: [DFF<Bits<W>>; 12],
    edge_ab: VectorSubtractor<W, D>,
    offset_ac: VectorSubtractor<W, D>,
    offset_ad: VectorSubtractor<W, D>,
    edge_cd: VectorSubtractor<W, D>,
    offset_ca: VectorSubtractor<W, D>,
    offset_cb: VectorSubtractor<W, D>,
    /// `[a, b, c]`, `[a, b, d]`, `[c, d, a]`, `[c, d, b]` for all axes.
    orient_abc: CrossProduct<D, C>,
    orient_abd: CrossProduct<D, C>,
    orient_cda: CrossProduct<D, C>,
    orient_cdb: CrossProduct<D, C>,
    /// Sign of component `k` of cross product `i` at `3 i + k`.
    sign: [SignOf<C>; 12],
    /// Coordinate `k` of the pairs (a, c), (a, d), (b, c), (b, d) at `3 pair + k`.
    compare: [CoordinateCompare<W>; 12],
    /// Along coordinate `m` (`3 i + m`): c within [a, b], d within [a, b],
    /// a within [c, d], b within [c, d].
    within_segment: [DelayLine<Bit, ON_SEGMENT_DELAY>; 12],
    contacts: SegmentContacts,
    decision: SegmentsDecision,
}

impl<const W: usize, const D: usize, const C: usize> crate::unit::Unit for DegeneratePair<W, D, C> {
    const LATENCY: Option<usize> = Some(DEGENERATE_PAIR_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            ends_q,
            edge_ab,
            offset_ac,
            offset_ad,
            edge_cd,
            offset_ca,
            offset_cb,
            orient_abc,
            orient_abd,
            orient_cda,
            orient_cdb,
            sign,
            compare,
            within_segment,
            contacts,
            decision
        );
    }
}

impl<const W: usize, const D: usize, const C: usize> Logic for DegeneratePair<W, D, C> {
    #[hdl_gen]
    fn update(&mut self) {
        // Stage 1: fetch the ends.
        for i in 0..12 {
            self.ends_q[i].clock.next = self.clock.val();
            self.ends_q[i].d.next = self.ends_q[i].q.val();
        }
        if self.advance.val() {
            for k in 0..3 {
                if self.t1_segment_low.val() == 0 {
                    self.ends_q[k].d.next = self.t1_vertices[k].val();
                } else if self.t1_segment_low.val() == 1 {
                    self.ends_q[k].d.next = self.t1_vertices[3 + k].val();
                } else {
                    self.ends_q[k].d.next = self.t1_vertices[6 + k].val();
                }
                if self.t1_segment_high.val() == 0 {
                    self.ends_q[3 + k].d.next = self.t1_vertices[k].val();
                } else if self.t1_segment_high.val() == 1 {
                    self.ends_q[3 + k].d.next = self.t1_vertices[3 + k].val();
                } else {
                    self.ends_q[3 + k].d.next = self.t1_vertices[6 + k].val();
                }
                if self.t2_segment_low.val() == 0 {
                    self.ends_q[6 + k].d.next = self.t2_vertices[k].val();
                } else if self.t2_segment_low.val() == 1 {
                    self.ends_q[6 + k].d.next = self.t2_vertices[3 + k].val();
                } else {
                    self.ends_q[6 + k].d.next = self.t2_vertices[6 + k].val();
                }
                if self.t2_segment_high.val() == 0 {
                    self.ends_q[9 + k].d.next = self.t2_vertices[k].val();
                } else if self.t2_segment_high.val() == 1 {
                    self.ends_q[9 + k].d.next = self.t2_vertices[3 + k].val();
                } else {
                    self.ends_q[9 + k].d.next = self.t2_vertices[6 + k].val();
                }
            }
        }
        // Stage 2: differences and comparisons.
        clock!(
            self, clock, edge_ab, offset_ac, offset_ad, edge_cd, offset_ca, offset_cb, orient_abc,
            orient_abd, orient_cda, orient_cdb
        );
        self.edge_ab.advance.next = self.advance.val();
        self.offset_ac.advance.next = self.advance.val();
        self.offset_ad.advance.next = self.advance.val();
        self.edge_cd.advance.next = self.advance.val();
        self.offset_ca.advance.next = self.advance.val();
        self.offset_cb.advance.next = self.advance.val();
        self.orient_abc.advance.next = self.advance.val();
        self.orient_abd.advance.next = self.advance.val();
        self.orient_cda.advance.next = self.advance.val();
        self.orient_cdb.advance.next = self.advance.val();
        for k in 0..3 {
            // a = ends 0..2, b = 3..5, c = 6..8, d = 9..11.
            self.edge_ab.a[k].next = self.ends_q[3 + k].q.val();
            self.edge_ab.b[k].next = self.ends_q[k].q.val();
            self.offset_ac.a[k].next = self.ends_q[6 + k].q.val();
            self.offset_ac.b[k].next = self.ends_q[k].q.val();
            self.offset_ad.a[k].next = self.ends_q[9 + k].q.val();
            self.offset_ad.b[k].next = self.ends_q[k].q.val();
            self.edge_cd.a[k].next = self.ends_q[9 + k].q.val();
            self.edge_cd.b[k].next = self.ends_q[6 + k].q.val();
            self.offset_ca.a[k].next = self.ends_q[k].q.val();
            self.offset_ca.b[k].next = self.ends_q[6 + k].q.val();
            self.offset_cb.a[k].next = self.ends_q[3 + k].q.val();
            self.offset_cb.b[k].next = self.ends_q[6 + k].q.val();
            // Stages 3-6: the four cross products.
            self.orient_abc.u[k].next = self.edge_ab.difference[k].val();
            self.orient_abc.v[k].next = self.offset_ac.difference[k].val();
            self.orient_abd.u[k].next = self.edge_ab.difference[k].val();
            self.orient_abd.v[k].next = self.offset_ad.difference[k].val();
            self.orient_cda.u[k].next = self.edge_cd.difference[k].val();
            self.orient_cda.v[k].next = self.offset_ca.difference[k].val();
            self.orient_cdb.u[k].next = self.edge_cd.difference[k].val();
            self.orient_cdb.v[k].next = self.offset_cb.difference[k].val();
            self.sign[k].value.next = self.orient_abc.product[k].val();
            self.sign[3 + k].value.next = self.orient_abd.product[k].val();
            self.sign[6 + k].value.next = self.orient_cda.product[k].val();
            self.sign[9 + k].value.next = self.orient_cdb.product[k].val();
            // Comparisons: pairs (a, c), (a, d), (b, c), (b, d).
            self.compare[k].a.next = self.ends_q[k].q.val();
            self.compare[k].b.next = self.ends_q[6 + k].q.val();
            self.compare[3 + k].a.next = self.ends_q[k].q.val();
            self.compare[3 + k].b.next = self.ends_q[9 + k].q.val();
            self.compare[6 + k].a.next = self.ends_q[3 + k].q.val();
            self.compare[6 + k].b.next = self.ends_q[6 + k].q.val();
            self.compare[9 + k].a.next = self.ends_q[3 + k].q.val();
            self.compare[9 + k].b.next = self.ends_q[9 + k].q.val();
        }
        for i in 0..12 {
            self.compare[i].clock.next = self.clock.val();
            self.compare[i].advance.next = self.advance.val();
            self.sign[i].clock.next = self.clock.val();
            self.sign[i].advance.next = self.advance.val();
            self.within_segment[i].clock.next = self.clock.val();
            self.within_segment[i].advance.next = self.advance.val();
            self.within_segment[i].d.next = self.contacts.within[i].val();
            self.contacts.less[i].next = self.compare[i].less.val();
            self.contacts.equal[i].next = self.compare[i].equal.val();
            self.decision.negative[i].next = self.sign[i].negative.val();
            self.decision.zero[i].next = self.sign[i].zero.val();
            self.decision.within[i].next = self.within_segment[i].q.val();
        }
        // Stage 8: the 2D test in each projection.
        self.decision.clock.next = self.clock.val();
        self.decision.advance.next = self.advance.val();
        self.hit.next = self.decision.hit.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::pipeline::degenerate_pair::{DegeneratePair, DEGENERATE_PAIR_LATENCY};
    use crate::pipeline::unit_vectors::{
        degenerate_pairs, lexicographic_ends, segments_meet, set_vertices,
    };
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;

    /// Two degenerate triangles: their segments (lexicographic ends) meet in all
    /// three axis projections (`degenerate_pair` without its orient3d, which
    /// the shared orient3d unit computes).
    #[test]
    fn degenerate_pair_is_the_three_projection_segment_test() {
        let vectors = degenerate_pairs();
        let model = segments_meet;
        let hits = vectors.iter().filter(|v| model(v)).count();
        assert!(
            hits > 20 && hits < vectors.len() - 20,
            "{hits} hits of {}",
            vectors.len()
        );
        let mut uut = DegeneratePair::<24, 25, 49>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &vectors,
            DEGENERATE_PAIR_LATENCY,
            |u, (t1, t2)| {
                set_vertices(&mut u.t1_vertices, t1);
                set_vertices(&mut u.t2_vertices, t2);
                let ((a, b), (c, d)) = (lexicographic_ends(t1), lexicographic_ends(t2));
                u.t1_segment_low.next = (a as u64).into();
                u.t1_segment_high.next = (b as u64).into();
                u.t2_segment_low.next = (c as u64).into();
                u.t2_segment_high.next = (d as u64).into();
            },
            |u| u.hit.val(),
            model,
        );
    }
}
