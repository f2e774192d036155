//! The operands of the three shared `orient3d` units, chosen by the pair's
//! case, then fetched from the six vertices (T1: indices 0..2, T2: 3..5).
//!
//! * both triangles proper: the two determinants of step (7),
//!   `interval_overlap` in devillers_guigue.rs;
//! * one triangle degenerate, spanning the segment `[a, b]` (its
//!   lexicographic ends): `[a, b, v_i, v_i+1]` for the three edges of the
//!   other triangle, `segment_triangle` in devillers_guigue.rs;
//! * both degenerate: `[a, b, c, d]` of the two segments,
//!   `degenerate_pair` in devillers_guigue.rs.
//!
//! Stages: index selection, then the vertex multiplexers.

use crate::arith::delay_line::DelayLine;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from the case and the indices to the operand points.
pub const ORIENT3D_OPERANDS_LATENCY: usize = 2;

#[derive(LogicBlock)]
pub struct Orient3dOperands<const W: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
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
    pub operands: [Signal<Out, Bits<W>>; 36],
    index_q: [DFF<Bits<3>>; 12],
    t1_delay: [DelayLine<Bits<W>, 1>; 9],
    t2_delay: [DelayLine<Bits<W>, 1>; 9],
    operands_q: [DFF<Bits<W>>; 36],
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
            index_q: Default::default(),
            t1_delay: Default::default(),
            t2_delay: Default::default(),
            operands_q: std::array::from_fn(|_| Default::default()),
        }
    }
}

impl<const W: usize> Logic for Orient3dOperands<W> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..12 {
            self.index_q[i].clock.next = self.clock.val();
            self.index_q[i].d.next = self.index_q[i].q.val();
        }
        if self.advance.val() {
            if !self.t1_degenerate.val() && !self.t2_degenerate.val() {
                for i in 0..4 {
                    self.index_q[i].d.next = self.overlap_first[i].val();
                    self.index_q[4 + i].d.next = self.overlap_second[i].val();
                    self.index_q[8 + i].d.next = 0.into();
                }
            } else if self.t1_degenerate.val() && !self.t2_degenerate.val() {
                // Segment of T1 against the edges of T2.
                for u in 0..3 {
                    self.index_q[4 * u].d.next = bit_cast::<3, 2>(self.t1_segment_low.val());
                    self.index_q[4 * u + 1].d.next = bit_cast::<3, 2>(self.t1_segment_high.val());
                }
                self.index_q[2].d.next = 3.into();
                self.index_q[3].d.next = 4.into();
                self.index_q[6].d.next = 4.into();
                self.index_q[7].d.next = 5.into();
                self.index_q[10].d.next = 5.into();
                self.index_q[11].d.next = 3.into();
            } else if !self.t1_degenerate.val() && self.t2_degenerate.val() {
                // Segment of T2 against the edges of T1.
                for u in 0..3 {
                    self.index_q[4 * u].d.next = bit_cast::<3, 2>(self.t2_segment_low.val()) + 3;
                    self.index_q[4 * u + 1].d.next = bit_cast::<3, 2>(self.t2_segment_high.val()) + 3;
                }
                self.index_q[2].d.next = 0.into();
                self.index_q[3].d.next = 1.into();
                self.index_q[6].d.next = 1.into();
                self.index_q[7].d.next = 2.into();
                self.index_q[10].d.next = 2.into();
                self.index_q[11].d.next = 0.into();
            } else {
                // Two segments: [a, b, c, d].
                self.index_q[0].d.next = bit_cast::<3, 2>(self.t1_segment_low.val());
                self.index_q[1].d.next = bit_cast::<3, 2>(self.t1_segment_high.val());
                self.index_q[2].d.next = bit_cast::<3, 2>(self.t2_segment_low.val()) + 3;
                self.index_q[3].d.next = bit_cast::<3, 2>(self.t2_segment_high.val()) + 3;
                for i in 4..12 {
                    self.index_q[i].d.next = 0.into();
                }
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
        for s in 0..12 {
            for k in 0..3 {
                self.operands_q[3 * s + k].clock.next = self.clock.val();
                self.operands_q[3 * s + k].d.next = self.operands_q[3 * s + k].q.val();
                if self.advance.val() {
                    if self.index_q[s].q.val() == 0 {
                        self.operands_q[3 * s + k].d.next = self.t1_delay[k].q.val();
                    } else if self.index_q[s].q.val() == 1 {
                        self.operands_q[3 * s + k].d.next = self.t1_delay[3 + k].q.val();
                    } else if self.index_q[s].q.val() == 2 {
                        self.operands_q[3 * s + k].d.next = self.t1_delay[6 + k].q.val();
                    } else if self.index_q[s].q.val() == 3 {
                        self.operands_q[3 * s + k].d.next = self.t2_delay[k].q.val();
                    } else if self.index_q[s].q.val() == 4 {
                        self.operands_q[3 * s + k].d.next = self.t2_delay[3 + k].q.val();
                    } else {
                        self.operands_q[3 * s + k].d.next = self.t2_delay[6 + k].q.val();
                    }
                }
                self.operands[3 * s + k].next = self.operands_q[3 * s + k].q.val();
            }
        }
    }
}
