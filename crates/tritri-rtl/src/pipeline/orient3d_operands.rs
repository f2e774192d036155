//! The operands of the two shared `orient3d` units, chosen by the pair's
//! case, then fetched from the six vertices (T1: indices 0..2, T2: 3..5).
//!
//! * both triangles proper: the two determinants of step (7),
//!   `interval_overlap` in devillers_guigue.rs;
//! * one triangle degenerate, spanning the segment `[a, b]` (its
//!   lexicographic ends): `[a, b, v_i, v_i+1]` for the first two edges of
//!   the other triangle, `segment_triangle` in devillers_guigue.rs (the
//!   third edge's follows from these two, `super::third_determinant`);
//! * both degenerate: `[a, b, c, d]` of the two segments,
//!   `degenerate_pair` in devillers_guigue.rs.
//!
//! Stages: the index of each operand (0..2 a vertex of T1, 3..5 of T2),
//! registered as its vertex number and its triangle; the vertex within
//! each triangle (two 3:1 multiplexers per operand coordinate); the
//! triangle (a 2:1 multiplexer). One 6:1 multiplexer stage, as before,
//! limited the W = 16 pipeline to 92 MHz on ECP5: its select registers
//! fanned out to 48 multiplexers of two LUT levels each, and routing took
//! nine tenths of the path.
//!
//! The degenerate flags and segment ends come a clock before the overlap
//! indices: the degenerate cases' indices and the case are registered
//! then, so the first stage only picks step (7)'s indices or those. Decided
//! with the indices, the case's four-way choice was the W = 8 pipeline's
//! critical path on ECP5 with the certificates (143.1 MHz, five LUT
//! levels).

use crate::arith::delay_line::DelayLine;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from the case and the indices to the operand points.
pub const ORIENT3D_OPERANDS_LATENCY: usize = 3;

#[derive(LogicBlock)]
pub struct Orient3dOperands<const W: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// The case and the segment ends: a clock before the overlap indices.
    pub t1_degenerate: Signal<In, Bit>,
    pub t2_degenerate: Signal<In, Bit>,
    pub t1_segment_low: Signal<In, Bits<2>>,
    pub t1_segment_high: Signal<In, Bits<2>>,
    pub t2_segment_low: Signal<In, Bits<2>>,
    pub t2_segment_high: Signal<In, Bits<2>>,
    /// Step (7)'s operand indices, from `interval_overlap`.
    pub overlap_first: [Signal<In, Bits<3>>; 4],
    pub overlap_second: [Signal<In, Bits<3>>; 4],
    pub t1_vertices: [Signal<In, Bits<W>>; 9],
    pub t2_vertices: [Signal<In, Bits<W>>; 9],
    /// Unit `u`, operand `j` (a, b, c, d), coordinate `k` at `12 u + 3 j + k`.
    pub operands: [Signal<Out, Bits<W>>; 24],
    /// Operand `s`'s index in a degenerate case (from the flags and
    /// segment ends), registered with whether both triangles are proper.
    degenerate_index: [Signal<Local, Bits<3>>; 8],
    degenerate_index_q: [DFF<Bits<3>>; 8],
    proper_q: DFF<Bit>,
    /// Operand `s`'s index this clock (0..2: T1's vertices, 3..5: T2's).
    index: [Signal<Local, Bits<3>>; 8],
    /// Stage 1: the index as a vertex number (0..2) and a triangle.
    vertex_q: [DFF<Bits<2>>; 8],
    from_t2_q: [DFF<Bit>; 8],
    t1_delay: [DelayLine<Bits<W>, 1>; 9],
    t2_delay: [DelayLine<Bits<W>, 1>; 9],
    /// Stage 2: that vertex's coordinate in each triangle, and the triangle.
    t1_pick_q: [DFF<Bits<W>>; 24],
    t2_pick_q: [DFF<Bits<W>>; 24],
    from_t2_2q: [DFF<Bit>; 8],
    /// Stage 3: the operand.
    operands_q: [DFF<Bits<W>>; 24],
}

impl<const W: usize> crate::unit::Unit for Orient3dOperands<W> {
    const LATENCY: Option<usize> = Some(ORIENT3D_OPERANDS_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            degenerate_index_q,
            proper_q,
            vertex_q,
            from_t2_q,
            t1_delay,
            t2_delay,
            t1_pick_q,
            t2_pick_q,
            from_t2_2q,
            operands_q
        );
    }
}

impl<const W: usize> Default for Orient3dOperands<W> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            advance: Default::default(),
            t1_degenerate: Default::default(),
            t2_degenerate: Default::default(),
            t1_segment_low: Default::default(),
            t1_segment_high: Default::default(),
            t2_segment_low: Default::default(),
            t2_segment_high: Default::default(),
            overlap_first: Default::default(),
            overlap_second: Default::default(),
            t1_vertices: Default::default(),
            t2_vertices: Default::default(),
            operands: std::array::from_fn(|_| Default::default()),
            degenerate_index: Default::default(),
            degenerate_index_q: Default::default(),
            proper_q: Default::default(),
            index: Default::default(),
            vertex_q: Default::default(),
            from_t2_q: Default::default(),
            t1_delay: Default::default(),
            t2_delay: Default::default(),
            t1_pick_q: std::array::from_fn(|_| Default::default()),
            t2_pick_q: std::array::from_fn(|_| Default::default()),
            from_t2_2q: Default::default(),
            operands_q: std::array::from_fn(|_| Default::default()),
        }
    }
}

impl<const W: usize> Logic for Orient3dOperands<W> {
    #[hdl_gen]
    fn update(&mut self) {
        // A clock early: the degenerate cases' indices and the case.
        for i in 0..8 {
            self.degenerate_index[i].next = 0.into();
        }
        if self.t1_degenerate.val() && !self.t2_degenerate.val() {
            // Segment of T1 against the first two edges of T2.
            for u in 0..2 {
                self.degenerate_index[4 * u].next = bit_cast::<3, 2>(self.t1_segment_low.val());
                self.degenerate_index[4 * u + 1].next =
                    bit_cast::<3, 2>(self.t1_segment_high.val());
            }
            self.degenerate_index[2].next = 3.into();
            self.degenerate_index[3].next = 4.into();
            self.degenerate_index[6].next = 4.into();
            self.degenerate_index[7].next = 5.into();
        } else if !self.t1_degenerate.val() && self.t2_degenerate.val() {
            // Segment of T2 against the first two edges of T1.
            for u in 0..2 {
                self.degenerate_index[4 * u].next = bit_cast::<3, 2>(self.t2_segment_low.val()) + 3;
                self.degenerate_index[4 * u + 1].next =
                    bit_cast::<3, 2>(self.t2_segment_high.val()) + 3;
            }
            self.degenerate_index[2].next = 0.into();
            self.degenerate_index[3].next = 1.into();
            self.degenerate_index[6].next = 1.into();
            self.degenerate_index[7].next = 2.into();
        } else if self.t1_degenerate.val() && self.t2_degenerate.val() {
            // Two segments: [a, b, c, d].
            self.degenerate_index[0].next = bit_cast::<3, 2>(self.t1_segment_low.val());
            self.degenerate_index[1].next = bit_cast::<3, 2>(self.t1_segment_high.val());
            self.degenerate_index[2].next = bit_cast::<3, 2>(self.t2_segment_low.val()) + 3;
            self.degenerate_index[3].next = bit_cast::<3, 2>(self.t2_segment_high.val()) + 3;
        }
        dff_setup!(self, clock, proper_q);
        if self.advance.val() {
            self.proper_q.d.next = !self.t1_degenerate.val() && !self.t2_degenerate.val();
        }
        for i in 0..8 {
            self.degenerate_index_q[i].clock.next = self.clock.val();
            self.degenerate_index_q[i].d.next = self.degenerate_index_q[i].q.val();
            if self.advance.val() {
                self.degenerate_index_q[i].d.next = self.degenerate_index[i].val();
            }
            self.index[i].next = self.degenerate_index_q[i].q.val();
        }
        if self.proper_q.q.val() {
            for i in 0..4 {
                self.index[i].next = self.overlap_first[i].val();
                self.index[4 + i].next = self.overlap_second[i].val();
            }
        }
        for s in 0..8 {
            self.vertex_q[s].clock.next = self.clock.val();
            self.vertex_q[s].d.next = self.vertex_q[s].q.val();
            self.from_t2_q[s].clock.next = self.clock.val();
            self.from_t2_q[s].d.next = self.from_t2_q[s].q.val();
            self.from_t2_2q[s].clock.next = self.clock.val();
            self.from_t2_2q[s].d.next = self.from_t2_2q[s].q.val();
            if self.advance.val() {
                if self.index[s].val() == 0 || self.index[s].val() == 3 {
                    self.vertex_q[s].d.next = 0.into();
                } else if self.index[s].val() == 1 || self.index[s].val() == 4 {
                    self.vertex_q[s].d.next = 1.into();
                } else {
                    self.vertex_q[s].d.next = 2.into();
                }
                self.from_t2_q[s].d.next = self.index[s].val() == 3
                    || self.index[s].val() == 4
                    || self.index[s].val() == 5;
                self.from_t2_2q[s].d.next = self.from_t2_q[s].q.val();
            }
        }
        for i in 0..9 {
            self.t1_delay[i].clock.next = self.clock.val();
            self.t1_delay[i].advance.next = self.advance.val();
            self.t1_delay[i].d.next = self.t1_vertices[i].val();
            self.t2_delay[i].clock.next = self.clock.val();
            self.t2_delay[i].advance.next = self.advance.val();
            self.t2_delay[i].d.next = self.t2_vertices[i].val();
        }
        for s in 0..8 {
            for k in 0..3 {
                self.t1_pick_q[3 * s + k].clock.next = self.clock.val();
                self.t1_pick_q[3 * s + k].d.next = self.t1_pick_q[3 * s + k].q.val();
                self.t2_pick_q[3 * s + k].clock.next = self.clock.val();
                self.t2_pick_q[3 * s + k].d.next = self.t2_pick_q[3 * s + k].q.val();
                self.operands_q[3 * s + k].clock.next = self.clock.val();
                self.operands_q[3 * s + k].d.next = self.operands_q[3 * s + k].q.val();
                if self.advance.val() {
                    if self.vertex_q[s].q.val() == 0 {
                        self.t1_pick_q[3 * s + k].d.next = self.t1_delay[k].q.val();
                        self.t2_pick_q[3 * s + k].d.next = self.t2_delay[k].q.val();
                    } else if self.vertex_q[s].q.val() == 1 {
                        self.t1_pick_q[3 * s + k].d.next = self.t1_delay[3 + k].q.val();
                        self.t2_pick_q[3 * s + k].d.next = self.t2_delay[3 + k].q.val();
                    } else {
                        self.t1_pick_q[3 * s + k].d.next = self.t1_delay[6 + k].q.val();
                        self.t2_pick_q[3 * s + k].d.next = self.t2_delay[6 + k].q.val();
                    }
                    if self.from_t2_2q[s].q.val() {
                        self.operands_q[3 * s + k].d.next = self.t2_pick_q[3 * s + k].q.val();
                    } else {
                        self.operands_q[3 * s + k].d.next = self.t1_pick_q[3 * s + k].q.val();
                    }
                }
                self.operands[3 * s + k].next = self.operands_q[3 * s + k].q.val();
            }
        }
    }
}
