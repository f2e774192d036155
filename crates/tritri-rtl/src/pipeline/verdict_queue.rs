//! The shared rare-case unit's verdicts, waiting for their pairs: a queue of
//! single bits, written when the unit is done with a job and read when
//! that job's pair reaches the decision. Both happen in the pairs' order,
//! so a circular buffer with two pointers is the whole queue.
//!
//! The pipeline bounds what it holds: a verdict is written at most
//! [`VERDICT_QUEUE_DEPTH`] - 1 rare pairs before it is read, since every
//! pair between the unit's input and the decision occupies a stage of the
//! general path (`super::shared_rare_pipeline` asserts that there are
//! fewer stages than slots). The head is the slot at the read pointer, a
//! verdict written at least one edge earlier; or, when the queue is empty,
//! the verdict being pushed, so that a pair meets its verdict in the
//! clock the unit gives it.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Slots (the pointers' `2^5`; the update's literals follow it).
pub const VERDICT_QUEUE_DEPTH: usize = 32;

#[derive(LogicBlock, Default)]
pub struct VerdictQueue {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: empties the queue.
    pub reset: Signal<In, Bit>,
    /// Write `push_hit` at the tail.
    pub push: Signal<In, Bit>,
    pub push_hit: Signal<In, Bit>,
    /// Remove the head.
    pub pop: Signal<In, Bit>,
    pub head: Signal<Out, Bit>,
    slots: DFF<Bits<32>>,
    write_q: DFF<Bits<5>>,
    read_q: DFF<Bits<5>>,
}

impl crate::unit::Unit for VerdictQueue {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, slots, write_q, read_q);
    }
}

impl Logic for VerdictQueue {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, slots, write_q, read_q);
        if self.push.val() {
            self.slots.d.next = self
                .slots
                .q
                .val()
                .replace_bit(self.write_q.q.val().index(), self.push_hit.val());
            self.write_q.d.next = self.write_q.q.val() + 1;
        }
        if self.pop.val() {
            self.read_q.d.next = self.read_q.q.val() + 1;
        }
        if self.reset.val() {
            self.write_q.d.next = 0.into();
            self.read_q.d.next = 0.into();
        }
        self.head.next = self.slots.q.val().get_bit(self.read_q.q.val().index());
        // Empty: the verdict on its way in.
        if self.push.val() && self.read_q.q.val() == self.write_q.q.val() {
            self.head.next = self.push_hit.val();
        }
    }
}

const _: () = assert!(VERDICT_QUEUE_DEPTH == 1 << 5);
