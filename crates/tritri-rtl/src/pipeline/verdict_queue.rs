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
//!
//! The head comes from registers: the slot the read pointer will point at
//! is chosen a clock ahead (`head_q`, with this clock's push and pop), and
//! so is whether the queue will be empty (`empty_q`); only the bypass of
//! an empty queue is left between them and the decision. (ECP5, W = 16,
//! the whole shared pipeline with nextpnr's `static` placer: the read
//! pointer through the 32-way choice, 3.8 ns across the chip, into the
//! decision's verdict was the critical path, 106.5 MHz.)
//!
//! The pointers are one-hot, one bit per slot, and step by rotating: a
//! slot is then chosen by an AND-OR of the slots with the pointer, and
//! neither a step nor a comparison needs a carry. (With five-bit pointers
//! the step, the 32-way choice and the comparisons with the write pointer
//! were nine levels of logic into `head_q`, the critical path of the whole
//! W = 16 shared pipeline at 131.6 MHz, router1.)

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Slots: one bit of each one-hot pointer per slot (the update's
/// `Bits<32>` and its rotations' literal 31 follow it).
pub const VERDICT_QUEUE_DEPTH: usize = 32;

#[derive(LogicBlock, Default)]
pub struct VerdictQueue {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: empties the queue. The queue needs it
    /// before its first use: the pointers power up with no bit set.
    pub reset: Signal<In, Bit>,
    /// Write `push_hit` at the tail.
    pub push: Signal<In, Bit>,
    pub push_hit: Signal<In, Bit>,
    /// Remove the head.
    pub pop: Signal<In, Bit>,
    pub head: Signal<Out, Bit>,
    slots: DFF<Bits<32>>,
    /// One-hot: the slot the next push writes, and the head's slot.
    write_q: DFF<Bits<32>>,
    read_q: DFF<Bits<32>>,
    /// The slot at the read pointer, and whether the queue is empty, as
    /// they will be after this clock's push and pop.
    head_q: DFF<Bit>,
    empty_q: DFF<Bit>,
    /// The slot the read pointer stays at, and the one it steps to, with
    /// this clock's push written into either.
    stay_hit: Signal<Local, Bit>,
    step_hit: Signal<Local, Bit>,
    /// The read pointer rotated one slot on, and the write pointer.
    read_step: Signal<Local, Bits<32>>,
    write_step: Signal<Local, Bits<32>>,
    /// The tail is the slot after the head: the queue holds one verdict.
    holds_one: Signal<Local, Bit>,
}

impl crate::unit::Unit for VerdictQueue {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, slots, write_q, read_q, head_q, empty_q);
    }
}

impl Logic for VerdictQueue {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, slots, write_q, read_q, head_q, empty_q);
        self.read_step.next = (self.read_q.q.val() << 1) | (self.read_q.q.val() >> 31);
        self.write_step.next = (self.write_q.q.val() << 1) | (self.write_q.q.val() >> 31);
        if self.push.val() {
            if self.push_hit.val() {
                self.slots.d.next = self.slots.q.val() | self.write_q.q.val();
            } else {
                self.slots.d.next = self.slots.q.val() & !self.write_q.q.val();
            }
            self.write_q.d.next = self.write_step.val();
        }
        if self.pop.val() {
            self.read_q.d.next = self.read_step.val();
        }
        self.holds_one.next = (self.write_q.q.val() & self.read_step.val()).any();
        // The pointers meet only when the queue is empty: it never fills.
        self.stay_hit.next = (self.slots.q.val() & self.read_q.q.val()).any();
        if self.push.val() && self.empty_q.q.val() {
            self.stay_hit.next = self.push_hit.val();
        }
        self.step_hit.next = (self.slots.q.val() & self.read_step.val()).any();
        if self.push.val() && self.holds_one.val() {
            self.step_hit.next = self.push_hit.val();
        }
        if self.pop.val() {
            self.head_q.d.next = self.step_hit.val();
        } else {
            self.head_q.d.next = self.stay_hit.val();
        }
        // A push alone leaves a verdict; a pop alone of the only one
        // leaves none; both, or neither, keep the count.
        if self.push.val() && !self.pop.val() {
            self.empty_q.d.next = false;
        }
        if self.pop.val() && !self.push.val() {
            self.empty_q.d.next = self.holds_one.val();
        }
        if self.reset.val() {
            self.write_q.d.next = 1.into();
            self.read_q.d.next = 1.into();
            self.empty_q.d.next = true;
        }
        self.head.next = self.head_q.q.val();
        // Empty: the verdict on its way in.
        if self.push.val() && self.empty_q.q.val() {
            self.head.next = self.push_hit.val();
        }
    }
}

const _: () = assert!(VERDICT_QUEUE_DEPTH == 32);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim_drive::{clock_cycle, settle};
    use std::collections::VecDeque;

    /// Random pushes and pops against a queue of the model's: the head is
    /// the oldest verdict, or the one being pushed into an empty queue, in
    /// every clock it is read, across the pointers' wrap and a reset.
    #[test]
    fn head_is_the_oldest_verdict_or_the_one_pushed_into_an_empty_queue() {
        let mut queue = VerdictQueue::default();
        queue.connect_all();
        let mut model: VecDeque<bool> = VecDeque::new();
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut random = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        queue.reset.next = true;
        clock_cycle(&mut queue, |q| &mut q.clock);
        let (mut reads, mut deepest) = (0, 0);
        for clock in 0..20_000 {
            let r = random();
            let reset = clock % 5_000 == 4_999;
            let push = r & 3 != 0 && model.len() < VERDICT_QUEUE_DEPTH - 1;
            let push_hit = r & 4 != 0;
            // A pop reads the head: of a queue with a verdict, or of an
            // empty one being pushed into. Pops are frequent in even
            // thousands of clocks and rare in odd ones, where the queue
            // fills to the pipeline's bound.
            let often = (clock / 1_000) % 2 == 0;
            let pop =
                (if often { r & 24 != 0 } else { r & 24 == 24 }) && (!model.is_empty() || push);
            queue.reset.next = reset;
            queue.push.next = push;
            queue.push_hit.next = push_hit;
            queue.pop.next = pop;
            settle(&mut queue);
            if pop {
                let expected = *model.front().unwrap_or(&push_hit);
                assert_eq!(queue.head.val(), expected, "clock {clock}");
                reads += 1;
            }
            clock_cycle(&mut queue, |q| &mut q.clock);
            if push {
                model.push_back(push_hit);
            }
            deepest = deepest.max(model.len());
            if pop {
                model.pop_front();
            }
            if reset {
                model.clear();
            }
        }
        assert!(reads > 10_000, "{reads} reads");
        assert_eq!(deepest, VERDICT_QUEUE_DEPTH - 1);
    }
}
