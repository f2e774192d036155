//! The result FIFO: one word per cycle in which at least one of the `P`
//! pipelines reported a pair (a hit, or a verdict without a certificate,
//! which the host decides again). A word is the `P`-bit mask of those
//! pairs, their `out_hit` and `out_certain` bits as two more masks, the
//! streamed triangle's id (the same for every pipeline, since B is
//! broadcast) and the `P` base ids, so `P` pairs in one cycle cost one
//! write and nothing has to be dropped or serialized on the pipelines'
//! side.
//!
//! Columns are [`SimpleDualPortRam`]s sharing the pointers, in block RAM
//! (see below). The head is shown first-word-fall-through: `head_valid` with the head word on
//! `head_*`, removed by `pop`. Because the memory reads one cycle late, a
//! word becomes readable two cycles after its write (`readable` counts the
//! words written at least one edge before the read), while `room` counts
//! every stored word: after `room` falls, at most `reserve` more words may
//! be written before pops make room again.
//!
//! `room` (fewer than `depth - reserve` words stored) is a register,
//! decided a clock ahead from the next count. The system's read side
//! advances on it (and on the shared pipelines' `hold`): computed in the
//! same clock from the count and the pipelines' verdicts, it was one
//! combinational net to every clock enable of the read side, 12.9 ns of
//! routing and 51 MHz post-route (ECP5, W = 8, P = 1).
//!
//! The pipelines themselves never stop for the FIFO (an enable to all
//! their registers crossed the chip: 9.7 ns of routing, 88.9 MHz), so the
//! `reserve` words above the `room` mark take the pairs still in flight
//! when the read side stops: with the pipeline latency `L` as the reserve,
//! a write in the last clock with `room` and the `L` verdicts after it fit,
//! and a write finds the FIFO full only if the caller broke that rule.
//!
//! The read address is the next head, so `pop` reaches the memories'
//! address through as little logic as possible: `head_valid` is a register
//! (`readable != 0` of the next count) and the successor of the read
//! pointer is kept ready in `read_pointer_next`. Deriving both from the
//! counters in the same cycle put ten levels of logic before the
//! distributed RAM, 88 MHz on ECP5; in distributed RAM, the read address
//! fanned out to 56 LUT RAMs and their multiplexers (103 MHz), in block
//! RAM to four.

use super::dual_port_ram::SimpleDualPortRam;
use super::{FIFO_POINTER_BITS, ID_BITS, MAX_PIPELINES};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

#[derive(LogicBlock)]
pub struct ResultFifo {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub write: Signal<In, Bit>,
    pub write_mask: Signal<In, Bits<MAX_PIPELINES>>,
    /// Of the word's pairs, those with `out_hit` and with `out_certain`.
    pub write_hit_mask: Signal<In, Bits<MAX_PIPELINES>>,
    pub write_certain_mask: Signal<In, Bits<MAX_PIPELINES>>,
    pub write_stream_id: Signal<In, Bits<ID_BITS>>,
    pub write_base_ids: Vec<Signal<In, Bits<ID_BITS>>>,
    /// Fewer than `depth - reserve` words are stored; a register.
    pub room: Signal<Out, Bit>,
    /// No word stored (readable or not).
    pub empty: Signal<Out, Bit>,
    pub pop: Signal<In, Bit>,
    pub head_valid: Signal<Out, Bit>,
    pub head_mask: Signal<Out, Bits<MAX_PIPELINES>>,
    pub head_hit_mask: Signal<Out, Bits<MAX_PIPELINES>>,
    pub head_certain_mask: Signal<Out, Bits<MAX_PIPELINES>>,
    pub head_stream_id: Signal<Out, Bits<ID_BITS>>,
    pub head_base_ids: Vec<Signal<Out, Bits<ID_BITS>>>,
    last_address: Constant<Bits<FIFO_POINTER_BITS>>,
    /// `depth - reserve`: the count from which `room` is low.
    room_mark: Constant<Bits<FIFO_POINTER_BITS>>,
    /// `depth - reserve - 1`: a write without a pop at this count ends `room`.
    last_room_count: Constant<Bits<FIFO_POINTER_BITS>>,
    mask_column: SimpleDualPortRam<Bits<MAX_PIPELINES>, FIFO_POINTER_BITS>,
    hit_column: SimpleDualPortRam<Bits<MAX_PIPELINES>, FIFO_POINTER_BITS>,
    certain_column: SimpleDualPortRam<Bits<MAX_PIPELINES>, FIFO_POINTER_BITS>,
    stream_id_column: SimpleDualPortRam<Bits<ID_BITS>, FIFO_POINTER_BITS>,
    base_id_columns: Vec<SimpleDualPortRam<Bits<ID_BITS>, FIFO_POINTER_BITS>>,
    write_pointer: DFF<Bits<FIFO_POINTER_BITS>>,
    read_pointer: DFF<Bits<FIFO_POINTER_BITS>>,
    count: DFF<Bits<FIFO_POINTER_BITS>>,
    readable: DFF<Bits<FIFO_POINTER_BITS>>,
    /// `readable != 0`, registered.
    head_valid_q: DFF<Bit>,
    /// `count < depth - reserve`, registered.
    room_q: DFF<Bit>,
    /// The read pointer's successor (wrapping at the depth), registered.
    read_pointer_next: DFF<Bits<FIFO_POINTER_BITS>>,
    wrote: DFF<Bit>,
    do_write: Signal<Local, Bit>,
    do_pop: Signal<Local, Bit>,
    next_read_pointer: Signal<Local, Bits<FIFO_POINTER_BITS>>,
}

impl crate::unit::Unit for ResultFifo {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            mask_column,
            hit_column,
            certain_column,
            stream_id_column,
            base_id_columns,
            write_pointer,
            read_pointer,
            count,
            readable,
            head_valid_q,
            room_q,
            read_pointer_next,
            wrote
        );
    }
}

impl ResultFifo {
    /// `depth` words of `pipelines` lanes each, `room` low from
    /// `depth - reserve` words on.
    pub fn new(pipelines: usize, depth: usize, reserve: usize) -> Self {
        assert!((1..=MAX_PIPELINES).contains(&pipelines));
        assert!((2..1 << (FIFO_POINTER_BITS - 1)).contains(&depth));
        assert!(
            reserve < depth,
            "a FIFO of {depth} words cannot keep {reserve} in reserve"
        );
        ResultFifo {
            clock: Default::default(),
            reset: Default::default(),
            write: Default::default(),
            write_mask: Default::default(),
            write_hit_mask: Default::default(),
            write_certain_mask: Default::default(),
            write_stream_id: Default::default(),
            write_base_ids: (0..pipelines).map(|_| Default::default()).collect(),
            room: Default::default(),
            empty: Default::default(),
            pop: Default::default(),
            head_valid: Default::default(),
            head_mask: Default::default(),
            head_hit_mask: Default::default(),
            head_certain_mask: Default::default(),
            head_stream_id: Default::default(),
            head_base_ids: (0..pipelines).map(|_| Default::default()).collect(),
            last_address: Constant::new(((depth - 1) as u64).to_bits()),
            room_mark: Constant::new(((depth - reserve) as u64).to_bits()),
            last_room_count: Constant::new(((depth - reserve - 1) as u64).to_bits()),
            mask_column: SimpleDualPortRam::new_block_ram(depth),
            hit_column: SimpleDualPortRam::new_block_ram(depth),
            certain_column: SimpleDualPortRam::new_block_ram(depth),
            stream_id_column: SimpleDualPortRam::new_block_ram(depth),
            base_id_columns: (0..pipelines)
                .map(|_| SimpleDualPortRam::new_block_ram(depth))
                .collect(),
            write_pointer: Default::default(),
            read_pointer: Default::default(),
            count: Default::default(),
            readable: Default::default(),
            head_valid_q: Default::default(),
            room_q: Default::default(),
            read_pointer_next: Default::default(),
            wrote: Default::default(),
            do_write: Default::default(),
            do_pop: Default::default(),
            next_read_pointer: Default::default(),
        }
    }
}

impl Logic for ResultFifo {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            write_pointer,
            read_pointer,
            count,
            readable,
            head_valid_q,
            room_q,
            read_pointer_next,
            wrote
        );
        self.room.next = self.room_q.q.val();
        self.empty.next = self.count.q.val() == 0;
        self.head_valid.next = self.head_valid_q.q.val();
        self.do_write.next = self.write.val();
        self.do_pop.next = self.pop.val() & self.head_valid_q.q.val();
        self.next_read_pointer.next = self.read_pointer.q.val();
        if self.do_pop.val() {
            self.next_read_pointer.next = self.read_pointer_next.q.val();
        }
        self.read_pointer.d.next = self.next_read_pointer.val();
        // The successor of the pointer the next cycle starts with: the same
        // without a pop; with one, the successor's successor, computed from
        // the register beside the pop rather than after it.
        if self.do_pop.val() {
            if self.read_pointer_next.q.val() == self.last_address.val() {
                self.read_pointer_next.d.next = 0.into();
            } else {
                self.read_pointer_next.d.next = self.read_pointer_next.q.val() + 1;
            }
        }
        if self.do_write.val() {
            if self.write_pointer.q.val() == self.last_address.val() {
                self.write_pointer.d.next = 0.into();
            } else {
                self.write_pointer.d.next = self.write_pointer.q.val() + 1;
            }
        }
        if self.do_write.val() & !self.do_pop.val() {
            self.count.d.next = self.count.q.val() + 1;
        }
        if !self.do_write.val() & self.do_pop.val() {
            self.count.d.next = self.count.q.val() - 1;
        }
        if self.wrote.q.val() & !self.do_pop.val() {
            self.readable.d.next = self.readable.q.val() + 1;
        }
        if !self.wrote.q.val() & self.do_pop.val() {
            self.readable.d.next = self.readable.q.val() - 1;
        }
        // The next readable != 0, without waiting for its carry chain: one more
        // word, one fewer (then at least two were readable), or as many.
        self.head_valid_q.d.next = self.readable.q.val() != 0;
        if self.wrote.q.val() & !self.do_pop.val() {
            self.head_valid_q.d.next = true;
        }
        if !self.wrote.q.val() & self.do_pop.val() {
            self.head_valid_q.d.next = self.readable.q.val() != 1;
        }
        self.wrote.d.next = self.do_write.val();
        // The next count < depth - reserve, by the same cases as the count:
        // one more word may reach the mark, one fewer may leave it.
        if self.do_write.val() & !self.do_pop.val() {
            self.room_q.d.next =
                self.room_q.q.val() & (self.count.q.val() != self.last_room_count.val());
        }
        if !self.do_write.val() & self.do_pop.val() {
            self.room_q.d.next = self.room_q.q.val() | (self.count.q.val() == self.room_mark.val());
        }

        // The columns: written at the write pointer, read at the next head.
        clock!(
            self,
            clock,
            mask_column,
            hit_column,
            certain_column,
            stream_id_column
        );
        self.mask_column.write_enable.next = self.do_write.val();
        self.mask_column.write_address.next = self.write_pointer.q.val();
        self.mask_column.write_data.next = self.write_mask.val();
        self.mask_column.read_enable.next = true;
        self.mask_column.read_address.next = self.next_read_pointer.val();
        self.head_mask.next = self.mask_column.read_data.val();
        self.hit_column.write_enable.next = self.do_write.val();
        self.hit_column.write_address.next = self.write_pointer.q.val();
        self.hit_column.write_data.next = self.write_hit_mask.val();
        self.hit_column.read_enable.next = true;
        self.hit_column.read_address.next = self.next_read_pointer.val();
        self.head_hit_mask.next = self.hit_column.read_data.val();
        self.certain_column.write_enable.next = self.do_write.val();
        self.certain_column.write_address.next = self.write_pointer.q.val();
        self.certain_column.write_data.next = self.write_certain_mask.val();
        self.certain_column.read_enable.next = true;
        self.certain_column.read_address.next = self.next_read_pointer.val();
        self.head_certain_mask.next = self.certain_column.read_data.val();
        self.stream_id_column.write_enable.next = self.do_write.val();
        self.stream_id_column.write_address.next = self.write_pointer.q.val();
        self.stream_id_column.write_data.next = self.write_stream_id.val();
        self.stream_id_column.read_enable.next = true;
        self.stream_id_column.read_address.next = self.next_read_pointer.val();
        self.head_stream_id.next = self.stream_id_column.read_data.val();
        for i in 0..self.base_id_columns.len() {
            self.base_id_columns[i].clock.next = self.clock.val();
            self.base_id_columns[i].write_enable.next = self.do_write.val();
            self.base_id_columns[i].write_address.next = self.write_pointer.q.val();
            self.base_id_columns[i].write_data.next = self.write_base_ids[i].val();
            self.base_id_columns[i].read_enable.next = true;
            self.base_id_columns[i].read_address.next = self.next_read_pointer.val();
            self.head_base_ids[i].next = self.base_id_columns[i].read_data.val();
        }

        if self.reset.val() {
            self.write_pointer.d.next = 0.into();
            self.read_pointer.d.next = 0.into();
            self.read_pointer_next.d.next = 1.into();
            self.count.d.next = 0.into();
            self.readable.d.next = 0.into();
            self.head_valid_q.d.next = false;
            self.room_q.d.next = true;
            self.wrote.d.next = false;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim_drive::clock_cycle;
    use rand::Rng;
    use rand_chacha::rand_core::SeedableRng;
    use std::collections::VecDeque;

    /// Random writes and pops against a queue: `room` is high exactly when
    /// fewer than `depth - reserve` words are stored, `empty` when none is,
    /// and the head shows the oldest word; a writer that keeps on writing
    /// past `room` (as the pipelines' pairs in flight do) loses nothing
    /// until the FIFO holds `depth` words.
    #[test]
    fn room_and_head_follow_a_queue() {
        let (depth, reserve) = (5, 2);
        let mut fifo = ResultFifo::new(2, depth, reserve);
        fifo.connect_all();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(14);
        let mut queue: VecDeque<(u64, u64, u64)> = VecDeque::new();
        fifo.reset.next = true;
        clock_cycle(&mut fifo, |f| &mut f.clock);
        fifo.reset.next = false;
        let (mut writes, mut pops, mut full_clocks) = (0, 0, 0);
        for clock in 0..4000 {
            assert_eq!(
                fifo.room.val(),
                queue.len() < depth - reserve,
                "clock {clock}"
            );
            assert_eq!(fifo.empty.val(), queue.is_empty(), "clock {clock}");
            full_clocks += usize::from(queue.len() == depth);
            let head_valid = fifo.head_valid.val();
            if head_valid {
                let shown = (
                    fifo.head_mask.val().to_u64(),
                    fifo.head_stream_id.val().to_u64(),
                    fifo.head_base_ids[1].val().to_u64(),
                );
                assert_eq!(Some(&shown), queue.front(), "clock {clock}");
            }
            // Bursts of writes, then of pops, so that it fills and drains.
            let write_bias = if (clock / 50) % 2 == 0 { 0.8 } else { 0.2 };
            let write = rng.gen_bool(write_bias) && queue.len() < depth;
            let pop = rng.gen_bool(1.0 - write_bias);
            let word = (
                rng.gen_range(1..4u64),
                rng.gen::<u32>() as u64,
                rng.gen::<u32>() as u64,
            );
            fifo.write.next = write;
            fifo.write_mask.next = word.0.into();
            fifo.write_stream_id.next = word.1.into();
            fifo.write_base_ids[1].next = word.2.into();
            fifo.pop.next = pop;
            clock_cycle(&mut fifo, |f| &mut f.clock);
            if pop && head_valid {
                queue.pop_front();
                pops += 1;
            }
            if write {
                queue.push_back(word);
                writes += 1;
            }
        }
        assert!(
            writes > 500 && pops > 500 && full_clocks > 100,
            "{writes} {pops} {full_clocks}"
        );
    }
}
