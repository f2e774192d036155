//! Step (6): align T2 (already re-oriented by step (5)): rotate it so that
//! its lone vertex comes first, and swap T1's last two vertices instead of
//! flipping signs.
//!
//! Thesis, figures 3.7 and 3.17 (the T2 vertex-alignment unit). Software
//! model: `align_t2` in devillers_guigue.rs; its sign table is the same as
//! step (5)'s, [`AlignmentTable`]. The rotation and swap of step (5) pass
//! through so that step (7) sees all four.

use super::align_t1::AlignmentTable;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from step (5)'s outputs to step (6)'s.
pub const ALIGN_T2_LATENCY: usize = 1;

#[derive(LogicBlock, Default)]
pub struct AlignT2 {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub t1_rotation_in: Signal<In, Bits<2>>,
    pub t2_swap_in: Signal<In, Bit>,
    /// T2's signs after step (5).
    pub t2_aligned_negative: [Signal<In, Bit>; 3],
    pub t2_aligned_zero: [Signal<In, Bit>; 3],
    pub t1_rotation: Signal<Out, Bits<2>>,
    pub t2_swap: Signal<Out, Bit>,
    /// T2 (after step (5)) becomes `[t2_k, t2_k+1, t2_k+2]`.
    pub t2_rotation: Signal<Out, Bits<2>>,
    /// T1's (rotated) q1 and r1 trade places.
    pub t1_swap: Signal<Out, Bit>,
    sign_table: AlignmentTable,
    t1_rotation_q: DFF<Bits<2>>,
    t2_swap_q: DFF<Bit>,
    t2_rotation_q: DFF<Bits<2>>,
    t1_swap_q: DFF<Bit>,
}

impl crate::unit::Unit for AlignT2 {
    const LATENCY: Option<usize> = Some(ALIGN_T2_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            sign_table,
            t1_rotation_q,
            t2_swap_q,
            t2_rotation_q,
            t1_swap_q
        );
    }
}

impl Logic for AlignT2 {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..3 {
            self.sign_table.negative[i].next = self.t2_aligned_negative[i].val();
            self.sign_table.zero[i].next = self.t2_aligned_zero[i].val();
        }
        dff_setup!(
            self,
            clock,
            t1_rotation_q,
            t2_swap_q,
            t2_rotation_q,
            t1_swap_q
        );
        if self.advance.val() {
            self.t1_rotation_q.d.next = self.t1_rotation_in.val();
            self.t2_swap_q.d.next = self.t2_swap_in.val();
            self.t2_rotation_q.d.next = self.sign_table.rotation.val();
            self.t1_swap_q.d.next = self.sign_table.swap.val();
        }
        self.t1_rotation.next = self.t1_rotation_q.q.val();
        self.t2_swap.next = self.t2_swap_q.q.val();
        self.t2_rotation.next = self.t2_rotation_q.q.val();
        self.t1_swap.next = self.t1_swap_q.q.val();
    }
}
