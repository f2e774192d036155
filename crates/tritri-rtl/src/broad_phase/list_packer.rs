//! One of the binning unit's list writers: it appends the indices of one
//! object's triangles that meet one child octant to that octant's list
//! memory, two indices to a word, in the order the two lanes deliver them
//! (lane 0 first). A half word waits for the next index, or for `flush` at
//! the end of the pass, so each list starts on a word and no lane ever
//! waits.
//!
//! Word layout: the earlier index in bits `[INDEX_BITS-1:0]`, the later in
//! `[2 INDEX_BITS-1:INDEX_BITS]` (zero after a flush of a half word).

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Bits of a triangle index (per object).
pub const INDEX_BITS: usize = 18;
/// Bits of a list memory word: two indices.
pub const LIST_WORD_BITS: usize = 2 * INDEX_BITS;
/// Bits of a list memory address (words).
pub const LIST_ADDRESS_BITS: usize = 20;

// The kernel shifts by the literal 18 (a constant's name would reach the Verilog).
const _: () = assert!(INDEX_BITS == 18);

#[derive(LogicBlock, Default)]
pub struct ListPacker {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: the memory is empty.
    pub reset: Signal<In, Bit>,
    /// A pass begins: the new list starts at the next free word, count 0.
    pub new_list: Signal<In, Bit>,
    /// The pass is over: write a waiting half word.
    pub flush: Signal<In, Bit>,
    pub in0_valid: Signal<In, Bit>,
    pub in0_index: Signal<In, Bits<INDEX_BITS>>,
    pub in1_valid: Signal<In, Bit>,
    pub in1_index: Signal<In, Bits<INDEX_BITS>>,
    pub write_enable: Signal<Out, Bit>,
    pub write_address: Signal<Out, Bits<LIST_ADDRESS_BITS>>,
    pub write_data: Signal<Out, Bits<LIST_WORD_BITS>>,
    /// The list of this pass: its first word and its entries so far.
    pub start: Signal<Out, Bits<LIST_ADDRESS_BITS>>,
    pub count: Signal<Out, Bits<20>>,
    /// Words written since reset (the next free address): a register, so
    /// that a reader may test it in a block that also drives this packer's
    /// inputs (Icarus loops on a combinational path back into such a block).
    pub used: Signal<Out, Bits<LIST_ADDRESS_BITS>>,
    free: DFF<Bits<LIST_ADDRESS_BITS>>,
    start_q: DFF<Bits<LIST_ADDRESS_BITS>>,
    count_q: DFF<Bits<20>>,
    waiting: DFF<Bit>,
    waiting_index: DFF<Bits<INDEX_BITS>>,
    first: Signal<Local, Bits<INDEX_BITS>>,
}

impl crate::unit::Unit for ListPacker {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, free, start_q, count_q, waiting, waiting_index);
    }
}

impl Logic for ListPacker {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, free, start_q, count_q, waiting, waiting_index);
        self.start.next = self.start_q.q.val();
        self.count.next = self.count_q.q.val();
        self.used.next = self.free.q.val();
        self.write_address.next = self.free.q.val();
        self.write_enable.next = false;
        self.write_data.next = 0.into();
        self.first.next = self.in1_index.val();
        if self.in0_valid.val() {
            self.first.next = self.in0_index.val();
        }
        if self.flush.val() {
            if self.waiting.q.val() {
                self.write_enable.next = true;
                self.write_data.next =
                    bit_cast::<LIST_WORD_BITS, INDEX_BITS>(self.waiting_index.q.val());
                self.waiting.d.next = false;
            }
        } else if self.waiting.q.val() {
            if self.in0_valid.val() | self.in1_valid.val() {
                // The waiting index and the first new one make a word.
                self.write_enable.next = true;
                self.write_data.next =
                    bit_cast::<LIST_WORD_BITS, INDEX_BITS>(self.waiting_index.q.val())
                        | (bit_cast::<LIST_WORD_BITS, INDEX_BITS>(self.first.val()) << 18);
                if self.in0_valid.val() & self.in1_valid.val() {
                    self.waiting_index.d.next = self.in1_index.val();
                } else {
                    self.waiting.d.next = false;
                }
            }
        } else if self.in0_valid.val() & self.in1_valid.val() {
            self.write_enable.next = true;
            self.write_data.next = bit_cast::<LIST_WORD_BITS, INDEX_BITS>(self.in0_index.val())
                | (bit_cast::<LIST_WORD_BITS, INDEX_BITS>(self.in1_index.val()) << 18);
        } else if self.in0_valid.val() | self.in1_valid.val() {
            self.waiting.d.next = true;
            self.waiting_index.d.next = self.first.val();
        }
        if self.write_enable.val() {
            self.free.d.next = self.free.q.val() + 1;
        }
        if self.in0_valid.val() & self.in1_valid.val() {
            self.count_q.d.next = self.count_q.q.val() + 2;
        } else if self.in0_valid.val() | self.in1_valid.val() {
            self.count_q.d.next = self.count_q.q.val() + 1;
        }
        if self.new_list.val() {
            self.start_q.d.next = self.free.q.val();
            self.count_q.d.next = 0.into();
        }
        if self.reset.val() {
            self.free.d.next = 0.into();
            self.count_q.d.next = 0.into();
            self.waiting.d.next = false;
        }
    }
}
