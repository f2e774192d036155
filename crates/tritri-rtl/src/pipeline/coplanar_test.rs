//! The exact closed 2D triangle test of the coplanar case: do the two
//! (closed) triangles meet in the projection that drops `axis`?
//!
//! Software model: `hulls_intersect_2d` (with `segments_intersect_2d`,
//! `on_segment_2d` and `point_in_triangle_2d`) in devillers_guigue.rs, as
//! called by `coplanar_triangles` (axis: T1's dominant normal axis) and by
//! `segment_triangle` when the segment lies in the triangle's plane (axis:
//! the triangle's; the degenerate triangle's three collinear vertices stand
//! for the segment, since their three edges cover it). The thesis leaves
//! this case to software; here it is hardware, so every pair gets the exact
//! answer.
//!
//! Nine edge-against-edge tests plus two point-in-triangle tests share
//! eighteen orient2d values: `[A_e, A_e+1, B_v]` for each edge `e` of A
//! (T1) and vertex `v` of B (T2), and `[B_f, B_f+1, A_u]`, computed here as
//! `-(B_f+1 - B_f) × (B_f - A_u)` so that one offset `B_v - A_u` serves
//! both. The orientation of each projected triangle is the sign of its
//! normal's `axis` component. Collinear touching is resolved by comparing
//! projected coordinates.
//!
//! Stages: inputs (1: registered beside the unit, so that the dominant
//! axis, which selects every projected coordinate, fans out from a
//! register of its own and not from the base polygon's, 145 MHz at W = 8
//! on ECP5), projection (1), differences and comparisons (1), orient2d (4),
//! signs (1), decision (2: the eleven terms of `hulls_intersect_2d`, then
//! their OR; in one stage, eighteen signs fanned into one register through
//! five LUT levels, 129 MHz on ECP5).

use super::rare_decisions::{CoplanarContacts, CoplanarDecision, COPLANAR_DECISION_LATENCY};
use crate::arith::compare::{CoordinateCompare, COMPARE_LATENCY};
use crate::arith::cross_product::{CrossProduct2d, CROSS_PRODUCT_LATENCY};
use crate::arith::delay_line::DelayLine;
use crate::arith::sign::{SignOf, SIGN_LATENCY};
use crate::arith::subtractor::{Subtractor, SUBTRACTOR_LATENCY};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from inputs to `hit`.
pub const COPLANAR_TEST_LATENCY: usize =
    INPUT_STAGES + 1 + SUBTRACTOR_LATENCY + CROSS_PRODUCT_LATENCY + SIGN_LATENCY + DECISION_STAGES;
/// The inputs' register stage.
const INPUT_STAGES: usize = 1;
/// The decision's stages: the terms, then their OR.
const DECISION_STAGES: usize = COPLANAR_DECISION_LATENCY;
const ON_EDGE_DELAY: usize = CROSS_PRODUCT_LATENCY + SIGN_LATENCY;
/// The orientations are read where the terms are formed.
const ORIENTATION_DELAY: usize = COPLANAR_TEST_LATENCY - DECISION_STAGES - INPUT_STAGES;
const _: () = assert!(COMPARE_LATENCY == SUBTRACTOR_LATENCY);

#[derive(LogicBlock, Default)]
pub struct CoplanarTest<const W: usize, const D: usize, const C: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub t1_vertices: [Signal<In, Bits<W>>; 9],
    pub t2_vertices: [Signal<In, Bits<W>>; 9],
    /// The axis the projection drops (0, 1 or 2).
    pub axis: Signal<In, Bits<2>>,
    pub t1_normal_negative: [Signal<In, Bit>; 3],
    pub t1_normal_zero: [Signal<In, Bit>; 3],
    pub t2_normal_negative: [Signal<In, Bit>; 3],
    pub t2_normal_zero: [Signal<In, Bit>; 3],
    /// The closed projected hulls meet, `COPLANAR_TEST_LATENCY` edges later.
    pub hit: Signal<Out, Bit>,
    /// Stage 0: the inputs.
    axis_q: DFF<Bits<2>>,
    t1_q: [DFF<Bits<W>>; 9],
    t2_q: [DFF<Bits<W>>; 9],
    /// T1's normal's negative and zero flags (`k`, `3 + k`), then T2's.
    normal_q: [DFF<Bit>; 12],
    /// Projected coordinates `2 v + c` of vertex `v` (T1: 0..2, T2: 3..5).
    projection_q: [DFF<Bits<W>>; 12],
    /// Edge `e` of A (`2 e + c`) and of B.
    edge_a: [Subtractor<W, D>; 6],
    edge_b: [Subtractor<W, D>; 6],
    /// `B_v - A_u` at `2 (3 u + v) + c`.
    offset: [Subtractor<W, D>; 18],
    /// Coordinate `c` of `A_u` against `B_v` at `9 c + 3 u + v`.
    compare: [CoordinateCompare<W>; 18],
    /// `B_v` on the projected edge `e` of A (`3 e + v`), when collinear.
    on_edge_a: [DelayLine<Bit, ON_EDGE_DELAY>; 9],
    /// `A_u` on the projected edge `f` of B (`3 f + u`), when collinear.
    on_edge_b: [DelayLine<Bit, ON_EDGE_DELAY>; 9],
    /// Orientation of A (negative, zero) and of B in the projection.
    orientation: [DelayLine<Bit, ORIENTATION_DELAY>; 4],
    /// `[A_e, A_e+1, B_v]` at `3 e + v`; `-[B_f, B_f+1, A_u]` at `9 + 3 f + u`.
    orient: [CrossProduct2d<D, C>; 18],
    sign: [SignOf<C>; 18],
    contacts: CoplanarContacts,
    decision: CoplanarDecision,
}

impl<const W: usize, const D: usize, const C: usize> crate::unit::Unit for CoplanarTest<W, D, C> {
    const LATENCY: Option<usize> = Some(COPLANAR_TEST_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            axis_q,
            t1_q,
            t2_q,
            normal_q,
            projection_q,
            edge_a,
            edge_b,
            offset,
            compare,
            on_edge_a,
            on_edge_b,
            orientation,
            orient,
            sign,
            contacts,
            decision
        );
    }
}

impl<const W: usize, const D: usize, const C: usize> Logic for CoplanarTest<W, D, C> {
    #[hdl_gen]
    fn update(&mut self) {
        // Stage 0: the inputs.
        dff_setup!(self, clock, axis_q);
        for i in 0..9 {
            self.t1_q[i].clock.next = self.clock.val();
            self.t1_q[i].d.next = self.t1_q[i].q.val();
            self.t2_q[i].clock.next = self.clock.val();
            self.t2_q[i].d.next = self.t2_q[i].q.val();
        }
        for i in 0..12 {
            self.normal_q[i].clock.next = self.clock.val();
            self.normal_q[i].d.next = self.normal_q[i].q.val();
        }
        if self.advance.val() {
            self.axis_q.d.next = self.axis.val();
            for i in 0..9 {
                self.t1_q[i].d.next = self.t1_vertices[i].val();
                self.t2_q[i].d.next = self.t2_vertices[i].val();
            }
            for k in 0..3 {
                self.normal_q[k].d.next = self.t1_normal_negative[k].val();
                self.normal_q[3 + k].d.next = self.t1_normal_zero[k].val();
                self.normal_q[6 + k].d.next = self.t2_normal_negative[k].val();
                self.normal_q[9 + k].d.next = self.t2_normal_zero[k].val();
            }
        }
        // Stage 1: project, and pick the orientations.
        for i in 0..12 {
            self.projection_q[i].clock.next = self.clock.val();
            self.projection_q[i].d.next = self.projection_q[i].q.val();
        }
        if self.advance.val() {
            for v in 0..3 {
                if self.axis_q.q.val() == 0 {
                    self.projection_q[2 * v].d.next = self.t1_q[3 * v + 1].q.val();
                    self.projection_q[2 * v + 1].d.next = self.t1_q[3 * v + 2].q.val();
                    self.projection_q[6 + 2 * v].d.next = self.t2_q[3 * v + 1].q.val();
                    self.projection_q[7 + 2 * v].d.next = self.t2_q[3 * v + 2].q.val();
                } else if self.axis_q.q.val() == 1 {
                    self.projection_q[2 * v].d.next = self.t1_q[3 * v + 2].q.val();
                    self.projection_q[2 * v + 1].d.next = self.t1_q[3 * v].q.val();
                    self.projection_q[6 + 2 * v].d.next = self.t2_q[3 * v + 2].q.val();
                    self.projection_q[7 + 2 * v].d.next = self.t2_q[3 * v].q.val();
                } else {
                    self.projection_q[2 * v].d.next = self.t1_q[3 * v].q.val();
                    self.projection_q[2 * v + 1].d.next = self.t1_q[3 * v + 1].q.val();
                    self.projection_q[6 + 2 * v].d.next = self.t2_q[3 * v].q.val();
                    self.projection_q[7 + 2 * v].d.next = self.t2_q[3 * v + 1].q.val();
                }
            }
        }
        for i in 0..4 {
            self.orientation[i].clock.next = self.clock.val();
            self.orientation[i].advance.next = self.advance.val();
        }
        if self.axis_q.q.val() == 0 {
            self.orientation[0].d.next = self.normal_q[0].q.val();
            self.orientation[1].d.next = self.normal_q[3].q.val();
            self.orientation[2].d.next = self.normal_q[6].q.val();
            self.orientation[3].d.next = self.normal_q[9].q.val();
        } else if self.axis_q.q.val() == 1 {
            self.orientation[0].d.next = self.normal_q[1].q.val();
            self.orientation[1].d.next = self.normal_q[4].q.val();
            self.orientation[2].d.next = self.normal_q[7].q.val();
            self.orientation[3].d.next = self.normal_q[10].q.val();
        } else {
            self.orientation[0].d.next = self.normal_q[2].q.val();
            self.orientation[1].d.next = self.normal_q[5].q.val();
            self.orientation[2].d.next = self.normal_q[8].q.val();
            self.orientation[3].d.next = self.normal_q[11].q.val();
        }
        // Stage 2: edge vectors, offsets, coordinate comparisons.
        for i in 0..6 {
            self.edge_a[i].clock.next = self.clock.val();
            self.edge_a[i].advance.next = self.advance.val();
            self.edge_b[i].clock.next = self.clock.val();
            self.edge_b[i].advance.next = self.advance.val();
        }
        for i in 0..18 {
            self.offset[i].clock.next = self.clock.val();
            self.offset[i].advance.next = self.advance.val();
            self.compare[i].clock.next = self.clock.val();
            self.compare[i].advance.next = self.advance.val();
            self.orient[i].clock.next = self.clock.val();
            self.orient[i].advance.next = self.advance.val();
            self.sign[i].clock.next = self.clock.val();
            self.sign[i].advance.next = self.advance.val();
            self.sign[i].value.next = self.orient[i].product.val();
            self.contacts.less[i].next = self.compare[i].less.val();
            self.contacts.equal[i].next = self.compare[i].equal.val();
            self.decision.negative[i].next = self.sign[i].negative.val();
            self.decision.zero[i].next = self.sign[i].zero.val();
        }
        for e in 0..3 {
            for c in 0..2 {
                self.edge_a[2 * e + c].a.next = self.projection_q[2 * ((e + 1) % 3) + c].q.val();
                self.edge_a[2 * e + c].b.next = self.projection_q[2 * e + c].q.val();
                self.edge_b[2 * e + c].a.next =
                    self.projection_q[6 + 2 * ((e + 1) % 3) + c].q.val();
                self.edge_b[2 * e + c].b.next = self.projection_q[6 + 2 * e + c].q.val();
            }
        }
        for u in 0..3 {
            for v in 0..3 {
                for c in 0..2 {
                    self.offset[2 * (3 * u + v) + c].a.next =
                        self.projection_q[6 + 2 * v + c].q.val();
                    self.offset[2 * (3 * u + v) + c].b.next = self.projection_q[2 * u + c].q.val();
                    self.compare[9 * c + 3 * u + v].a.next = self.projection_q[2 * u + c].q.val();
                    self.compare[9 * c + 3 * u + v].b.next =
                        self.projection_q[6 + 2 * v + c].q.val();
                }
            }
        }
        // Stages 3-6: orient2d values.
        for e in 0..3 {
            for v in 0..3 {
                self.orient[3 * e + v].u_x.next = self.edge_a[2 * e].difference.val();
                self.orient[3 * e + v].u_y.next = self.edge_a[2 * e + 1].difference.val();
                self.orient[3 * e + v].w_x.next = self.offset[2 * (3 * e + v)].difference.val();
                self.orient[3 * e + v].w_y.next = self.offset[2 * (3 * e + v) + 1].difference.val();
                // f = e, u = v: (B_f+1 - B_f) × (B_f - A_u).
                self.orient[9 + 3 * e + v].u_x.next = self.edge_b[2 * e].difference.val();
                self.orient[9 + 3 * e + v].u_y.next = self.edge_b[2 * e + 1].difference.val();
                self.orient[9 + 3 * e + v].w_x.next = self.offset[2 * (3 * v + e)].difference.val();
                self.orient[9 + 3 * e + v].w_y.next =
                    self.offset[2 * (3 * v + e) + 1].difference.val();
            }
        }
        // Collinear touching (on_segment_2d): within the edge's bounding box
        // on both projected coordinates. A_u <= B_v is less || equal.
        for i in 0..9 {
            self.on_edge_a[i].clock.next = self.clock.val();
            self.on_edge_a[i].advance.next = self.advance.val();
            self.on_edge_b[i].clock.next = self.clock.val();
            self.on_edge_b[i].advance.next = self.advance.val();
        }
        for i in 0..9 {
            self.on_edge_a[i].d.next = self.contacts.on_edge_a[i].val();
            self.on_edge_b[i].d.next = self.contacts.on_edge_b[i].val();
        }
        // Stages 8-9: the terms of hulls_intersect_2d, then their OR.
        self.decision.clock.next = self.clock.val();
        self.decision.advance.next = self.advance.val();
        for i in 0..9 {
            self.decision.on_edge_a[i].next = self.on_edge_a[i].q.val();
            self.decision.on_edge_b[i].next = self.on_edge_b[i].q.val();
        }
        for i in 0..4 {
            self.decision.orientation[i].next = self.orientation[i].q.val();
        }
        self.hit.next = self.decision.hit.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::pipeline::coplanar_test::{CoplanarTest, COPLANAR_TEST_LATENCY};
    use crate::pipeline::unit_vectors::{coplanar_pairs, normal, set_vertices};
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;
    use tritri_geom::devillers_guigue::coplanar_triangles;
    use tritri_geom::fixed_point::{dominant_axis, FixedPoint, FixedTriangle};

    /// Coplanar triangles (T1 proper) on T1's dominant projection:
    /// `coplanar_triangles`.
    #[test]
    fn coplanar_test_is_the_closed_2d_test() {
        let vectors: Vec<(FixedTriangle, FixedTriangle)> = coplanar_pairs(8)
            .into_iter()
            .filter(|(t1, _)| normal(t1) != [0, 0, 0])
            .collect();
        let hits = vectors
            .iter()
            .filter(|(t1, t2)| coplanar_triangles::<FixedPoint>(*t1, *t2))
            .count();
        assert!(
            hits > vectors.len() / 5 && hits < vectors.len() * 4 / 5,
            "{hits} hits of {}",
            vectors.len()
        );
        let mut uut = CoplanarTest::<24, 25, 49>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &vectors,
            COPLANAR_TEST_LATENCY,
            |u, (t1, t2)| {
                set_vertices(&mut u.t1_vertices, t1);
                set_vertices(&mut u.t2_vertices, t2);
                let (n1, n2) = (normal(t1), normal(t2));
                u.axis.next = (dominant_axis(n1.map(|c| c.unsigned_abs())) as u64).into();
                for k in 0..3 {
                    u.t1_normal_negative[k].next = n1[k] < 0;
                    u.t1_normal_zero[k].next = n1[k] == 0;
                    u.t2_normal_negative[k].next = n2[k] < 0;
                    u.t2_normal_zero[k].next = n2[k] == 0;
                }
            },
            |u| u.hit.val(),
            |(t1, t2)| coplanar_triangles::<FixedPoint>(*t1, *t2),
        );
    }
}
