//! The shared rare-case unit's verdicts, waiting for their pairs: a queue of
//! single bits, written when the unit is done with a job and read when
//! that job's pair reaches the decision. Both happen in the pairs' order,
//! so a first-in, first-out queue of bits is the whole of it.
//!
//! The pipeline bounds what it holds: a verdict is written at most
//! [`VERDICT_QUEUE_DEPTH`] - 1 rare pairs before it is read, since every
//! pair between the unit's input and the decision occupies a stage of the
//! general path (`super::shared_rare_pipeline` asserts that there are
//! fewer stages than slots). The head is the oldest verdict, written at
//! least one edge earlier: a pair reaches the decision a clock after its
//! verdict at the earliest, so a pop never finds the queue empty (the
//! pipeline asserts the margin).
//!
//! The queue shifts: slot 0 is always the head, a pop moves every slot
//! down one, and a push writes the slot after the last verdict, which a
//! one-hot count names. So the head is a register, and every slot's next
//! value depends only on itself, its neighbour and the count's two bits
//! beside it, all in the queue's own corner of the chip. (With a bypass
//! that handed an empty queue's incoming verdict straight on, the unit's
//! output register reached the decision's `hit_q` through it: the W = 16
//! shared system's critical path on ECP5, 148.3 MHz.)
//!
//! (History, ECP5, W = 16 shared pipeline. A circular buffer's head chosen
//! through a 32-way choice by the read pointer was the critical path:
//! 106.5 MHz with nextpnr's `static` placer, five-bit pointers. With
//! one-hot pointers and the next head chosen a clock ahead into a
//! register, the pointer through that choice was still five levels and
//! the worst path left, 7.29 ns at 137.2 MHz, router1.)

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Slots, and positions of the one-hot count (the update's `Bits<32>`).
pub const VERDICT_QUEUE_DEPTH: usize = 32;

#[derive(LogicBlock, Default)]
pub struct VerdictQueue {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: empties the queue. The queue needs it
    /// before its first use: the count powers up with no bit set.
    pub reset: Signal<In, Bit>,
    /// Write `push_hit` at the tail.
    pub push: Signal<In, Bit>,
    pub push_hit: Signal<In, Bit>,
    /// Remove the head.
    pub pop: Signal<In, Bit>,
    pub head: Signal<Out, Bit>,
    /// The verdicts, oldest in bit 0.
    slots: DFF<Bits<32>>,
    /// One-hot: bit `n` when the queue holds `n` verdicts, the slot a push
    /// writes when nothing is popped.
    count_q: DFF<Bits<32>>,
    /// The slots after this clock's pop, and the slot this clock's push
    /// writes among them.
    kept: Signal<Local, Bits<32>>,
    tail: Signal<Local, Bits<32>>,
}

impl crate::unit::Unit for VerdictQueue {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, slots, count_q);
    }
}

impl Logic for VerdictQueue {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, slots, count_q);
        // A pop always finds a verdict (module doc).
        if self.pop.val() {
            self.kept.next = self.slots.q.val() >> 1;
            self.tail.next = self.count_q.q.val() >> 1;
        } else {
            self.kept.next = self.slots.q.val();
            self.tail.next = self.count_q.q.val();
        }
        self.slots.d.next = self.kept.val();
        if self.push.val() {
            if self.push_hit.val() {
                self.slots.d.next = self.kept.val() | self.tail.val();
            } else {
                self.slots.d.next = self.kept.val() & !self.tail.val();
            }
        }
        // The queue never fills: the pipeline bounds it (module doc).
        if self.push.val() && !self.pop.val() {
            self.count_q.d.next = self.count_q.q.val() << 1;
        }
        if self.pop.val() && !self.push.val() {
            self.count_q.d.next = self.count_q.q.val() >> 1;
        }
        if self.reset.val() {
            self.count_q.d.next = 1.into();
        }
        self.head.next = self.slots.q.val().get_bit(0);
    }
}

const _: () = assert!(VERDICT_QUEUE_DEPTH == 32);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim_drive::{clock_cycle, settle};
    use std::collections::VecDeque;

    /// Random pushes and pops against a queue of the model's: the head is
    /// the oldest verdict in every clock it is read, across the pointers'
    /// wrap and a reset.
    #[test]
    fn head_is_the_oldest_verdict() {
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
            // A pop reads the head of a queue with a verdict. Pops are
            // frequent in even thousands of clocks and rare in odd ones,
            // where the queue fills to the pipeline's bound.
            let often = (clock / 1_000) % 2 == 0;
            let pop = (if often { r & 24 != 0 } else { r & 24 == 24 }) && !model.is_empty();
            queue.reset.next = reset;
            queue.push.next = push;
            queue.push_hit.next = push_hit;
            queue.pop.next = pop;
            settle(&mut queue);
            if pop {
                assert_eq!(queue.head.val(), model[0], "clock {clock}");
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
