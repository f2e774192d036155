//! The two ends of a degenerate triangle: the lexicographic (x, y, z)
//! minimum and maximum of its three vertices, as vertex indices.
//!
//! Software model: `shape` in devillers_guigue.rs (`lo`, `hi`, with the
//! same tie rule: a later vertex replaces the current end only when it is
//! strictly smaller / larger). On three collinear vertices these are the
//! ends of the segment they span (a point when all are equal). Computed for
//! every triangle; only degenerate ones use it.
//!
//! Stages: per-axis comparisons of the vertex pairs (0,1), (0,2), (1,2);
//! then the lexicographic order and the indices.

use crate::arith::compare::{CoordinateCompare, COMPARE_LATENCY};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from vertices to end indices.
pub const SEGMENT_ENDS_LATENCY: usize = COMPARE_LATENCY + 1;

#[derive(LogicBlock, Default)]
pub struct SegmentEnds<const W: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub vertices: [Signal<In, Bits<W>>; 9],
    /// Index (0..2) of the lexicographically smallest vertex.
    pub low: Signal<Out, Bits<2>>,
    /// Index (0..2) of the lexicographically largest vertex.
    pub high: Signal<Out, Bits<2>>,
    /// Comparisons `3 * pair + axis` of the pairs (0,1), (0,2), (1,2):
    /// `vertex i` against `vertex j`.
    compare: [CoordinateCompare<W>; 9],
    /// Local: lexicographic orders (pair (i,j) as above): `i < j` and `j < i`.
    first_less: [Signal<Local, Bit>; 3],
    second_less: [Signal<Local, Bit>; 3],
    low_q: DFF<Bits<2>>,
    high_q: DFF<Bits<2>>,
}

impl<const W: usize> crate::unit::Unit for SegmentEnds<W> {
    const LATENCY: Option<usize> = Some(SEGMENT_ENDS_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, compare, low_q, high_q);
    }
}

impl<const W: usize> Logic for SegmentEnds<W> {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..3 {
            // pair 0: vertices 0, 1; pair 1: vertices 0, 2; pair 2: vertices 1, 2.
            self.compare[k].a.next = self.vertices[k].val();
            self.compare[k].b.next = self.vertices[3 + k].val();
            self.compare[3 + k].a.next = self.vertices[k].val();
            self.compare[3 + k].b.next = self.vertices[6 + k].val();
            self.compare[6 + k].a.next = self.vertices[3 + k].val();
            self.compare[6 + k].b.next = self.vertices[6 + k].val();
        }
        for i in 0..9 {
            self.compare[i].clock.next = self.clock.val();
            self.compare[i].advance.next = self.advance.val();
        }
        for p in 0..3 {
            // i < j: x less, or x equal and (y less, or y equal and z less).
            self.first_less[p].next = self.compare[3 * p].less.val()
                || (self.compare[3 * p].equal.val()
                    && (self.compare[3 * p + 1].less.val()
                        || (self.compare[3 * p + 1].equal.val()
                            && self.compare[3 * p + 2].less.val())));
            // j < i: the same with "greater" = neither less nor equal.
            self.second_less[p].next = (!self.compare[3 * p].less.val()
                && !self.compare[3 * p].equal.val())
                || (self.compare[3 * p].equal.val()
                    && ((!self.compare[3 * p + 1].less.val()
                        && !self.compare[3 * p + 1].equal.val())
                        || (self.compare[3 * p + 1].equal.val()
                            && !self.compare[3 * p + 2].less.val()
                            && !self.compare[3 * p + 2].equal.val())));
        }
        dff_setup!(self, clock, low_q, high_q);
        if self.advance.val() {
            // low: v1 < v0 ? 1 : 0, then v2 < low ? 2.
            if self.second_less[0].val() {
                if self.second_less[2].val() {
                    self.low_q.d.next = 2.into();
                } else {
                    self.low_q.d.next = 1.into();
                }
            } else if self.second_less[1].val() {
                self.low_q.d.next = 2.into();
            } else {
                self.low_q.d.next = 0.into();
            }
            // high: v1 > v0 ? 1 : 0, then v2 > high ? 2.
            if self.first_less[0].val() {
                if self.first_less[2].val() {
                    self.high_q.d.next = 2.into();
                } else {
                    self.high_q.d.next = 1.into();
                }
            } else if self.first_less[1].val() {
                self.high_q.d.next = 2.into();
            } else {
                self.high_q.d.next = 0.into();
            }
        }
        self.low.next = self.low_q.q.val();
        self.high.next = self.high_q.q.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::pipeline::segment_ends::{SegmentEnds, SEGMENT_ENDS_LATENCY};
    use crate::pipeline::unit_vectors::{lexicographic_ends, set_vertices, VECTORS};
    use crate::sim_drive::assert_stream_matches;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rust_hdl::prelude::*;
    use tritri_geom::fixed_point::FixedTriangle;

    #[test]
    fn segment_ends_are_the_lexicographic_extremes_first_index_on_ties() {
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        // Small coordinates: many equal coordinates and equal vertices.
        let vectors: Vec<FixedTriangle> = (0..VECTORS)
            .map(|_| std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-1..2))))
            .collect();
        let mut uut = SegmentEnds::<24>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &vectors,
            SEGMENT_ENDS_LATENCY,
            |u, t| set_vertices(&mut u.vertices, t),
            |u| {
                (
                    u.low.val().to_u64() as usize,
                    u.high.val().to_u64() as usize,
                )
            },
            lexicographic_ends,
        );
    }
}
