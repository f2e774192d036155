//! The octree engine's set-operation unit (`octree_engine.txt`, function
//! 1): two voxel models streamed from memory a word at a time, the result
//! out a word per clock. A word is 64 voxels along x, in the voxel
//! memory's order (`tritri_geom::octree::voxels::VoxelGrid`), so the
//! operation is bitwise: union `a | b`, intersection `a & b`, difference
//! `a & !b`. One register stage, valid/ready on both sides; the input is
//! taken whenever the output register is empty or being read.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Voxels per word.
pub const WORD_BITS: usize = 64;

/// The operation codes of `op`.
pub const OP_UNION: u64 = 0;
pub const OP_INTERSECTION: u64 = 1;
pub const OP_DIFFERENCE: u64 = 2;

#[derive(LogicBlock, Default)]
pub struct SetOperationUnit {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    /// 0 union, 1 intersection, 2 difference (a \ b); 3 is a \ b too.
    pub op: Signal<In, Bits<2>>,
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_a: Signal<In, Bits<64>>,
    pub in_b: Signal<In, Bits<64>>,
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_word: Signal<Out, Bits<64>>,
    valid_q: DFF<Bit>,
    word_q: DFF<Bits<64>>,
}

impl crate::unit::Unit for SetOperationUnit {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, valid_q, word_q);
    }
}

impl Logic for SetOperationUnit {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, valid_q, word_q);
        self.in_ready.next = !self.valid_q.q.val() | self.out_ready.val();
        self.out_valid.next = self.valid_q.q.val();
        self.out_word.next = self.word_q.q.val();
        if self.in_ready.val() {
            self.valid_q.d.next = self.in_valid.val();
            if self.op.val() == 0 {
                self.word_q.d.next = self.in_a.val() | self.in_b.val();
            } else if self.op.val() == 1 {
                self.word_q.d.next = self.in_a.val() & self.in_b.val();
            } else {
                self.word_q.d.next = self.in_a.val() & !self.in_b.val();
            }
        }
        if self.reset.val() {
            self.valid_q.d.next = false;
        }
    }
}
