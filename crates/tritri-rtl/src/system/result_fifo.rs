//! The result FIFO: one word per cycle in which at least one of the `P`
//! pipelines reported a pair (a hit, or a verdict without a certificate,
//! which the host decides again). A word is the `P`-bit mask of those
//! pairs, their `out_hit` and `out_certain` bits as two more masks, the
//! streamed triangle's id (the same for every pipeline, since B is
//! broadcast) and the `P` base ids, so `P` pairs in one cycle cost one
//! write and nothing has to be dropped or serialized on the pipelines'
//! side.
//!
//! Columns are [`SimpleDualPortRam`]s in block RAM with their output
//! registers, sharing the pointers. A word moves from the memory into the
//! RAM's read register (stage 1) and on into its output register (the
//! head, stage 2) as a first-word-fall-through queue: `head_valid` with the
//! head word on `head_*`, removed by `pop`. Both stages move together
//! (`read_enable`, the block RAM's `CEB` and `OCEB`): they shift when the
//! head is popped or empty, and a shift fetches the next stored word into
//! stage 1 if there is one. So the serializer reads the head from the block
//! RAM's output register: without it the DP16KD takes 5.8 ns from clock to
//! data, and the serializer's register loads after it held the system at
//! 121.9 MHz post-route (ECP5, W = 16, P = 1). A word written in cycle `t`
//! is the head from cycle `t + 3` when the queue was empty; while the head
//! waits for its pop, stage 1 cannot take a word behind it, so a queue that
//! ran dry costs a pop one gap, and a full one none.
//!
//! `room` (fewer than `depth - reserve` words stored, the two stages
//! included) is a register, decided a clock ahead from the next count. The
//! system's read side advances on it (and on the shared pipelines' `hold`):
//! computed in the same clock from the count and the pipelines' verdicts,
//! it was one combinational net to every clock enable of the read side,
//! 12.9 ns of routing and 51 MHz post-route (ECP5, W = 8, P = 1). After
//! `room` falls, at most `reserve` more words may be written before pops
//! make room again.
//!
//! The pipelines themselves never stop for the FIFO (an enable to all
//! their registers crossed the chip: 9.7 ns of routing, 88.9 MHz), so the
//! `reserve` words above the `room` mark take the pairs still in flight
//! when the read side stops: with the pipeline latency `L` as the reserve,
//! a write in the last clock with `room` and the `L` verdicts after it fit,
//! and a write finds the FIFO full only if the caller broke that rule.
//!
//! The read address is the fetch pointer, a register, and whether a stored
//! word waits to be fetched is a register too (`available_q`), so a pop
//! reaches the block RAMs only through their clock enables.

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
    /// The address of the next word to fetch into stage 1.
    fetch_pointer: DFF<Bits<FIFO_POINTER_BITS>>,
    /// Words stored, in the memory or in the two stages.
    count: DFF<Bits<FIFO_POINTER_BITS>>,
    /// Words in the memory, written at an earlier edge, not yet fetched.
    available: DFF<Bits<FIFO_POINTER_BITS>>,
    /// `available != 0`, registered.
    available_q: DFF<Bit>,
    /// Stage 1 holds a word; the head (stage 2) holds one.
    stage_valid: DFF<Bit>,
    head_valid_q: DFF<Bit>,
    /// `count < depth - reserve`, registered.
    room_q: DFF<Bit>,
    do_write: Signal<Local, Bit>,
    do_pop: Signal<Local, Bit>,
    /// The two stages move: the head is popped or empty.
    shift: Signal<Local, Bit>,
    /// A shift that brings a stored word into stage 1.
    fetch: Signal<Local, Bit>,
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
            fetch_pointer,
            count,
            available,
            available_q,
            stage_valid,
            head_valid_q,
            room_q
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
            mask_column: column(depth),
            hit_column: column(depth),
            certain_column: column(depth),
            stream_id_column: column(depth),
            base_id_columns: (0..pipelines).map(|_| column(depth)).collect(),
            write_pointer: Default::default(),
            fetch_pointer: Default::default(),
            count: Default::default(),
            available: Default::default(),
            available_q: Default::default(),
            stage_valid: Default::default(),
            head_valid_q: Default::default(),
            room_q: Default::default(),
            do_write: Default::default(),
            do_pop: Default::default(),
            shift: Default::default(),
            fetch: Default::default(),
        }
    }
}

/// A column: block RAM with its output register.
fn column<T: Synth>(depth: usize) -> SimpleDualPortRam<T, FIFO_POINTER_BITS> {
    SimpleDualPortRam::with_output_register(depth).in_block_ram()
}

impl Logic for ResultFifo {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            write_pointer,
            fetch_pointer,
            count,
            available,
            available_q,
            stage_valid,
            head_valid_q,
            room_q
        );
        self.room.next = self.room_q.q.val();
        self.empty.next = self.count.q.val() == 0;
        self.head_valid.next = self.head_valid_q.q.val();
        self.do_write.next = self.write.val();
        self.do_pop.next = self.pop.val() & self.head_valid_q.q.val();
        self.shift.next = self.pop.val() | !self.head_valid_q.q.val();
        self.fetch.next = self.shift.val() & self.available_q.q.val();
        if self.shift.val() {
            self.head_valid_q.d.next = self.stage_valid.q.val();
            self.stage_valid.d.next = self.fetch.val();
        }
        if self.fetch.val() {
            if self.fetch_pointer.q.val() == self.last_address.val() {
                self.fetch_pointer.d.next = 0.into();
            } else {
                self.fetch_pointer.d.next = self.fetch_pointer.q.val() + 1;
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
        if self.do_write.val() & !self.fetch.val() {
            self.available.d.next = self.available.q.val() + 1;
        }
        if !self.do_write.val() & self.fetch.val() {
            self.available.d.next = self.available.q.val() - 1;
        }
        // The next available != 0, without waiting for its carry chain: one
        // more word, one fewer (then at least two were there), or as many.
        // A word written at this edge can be fetched at the next: the
        // memory reads first, and it is there by then.
        self.available_q.d.next = self.available.q.val() != 0;
        if self.do_write.val() & !self.fetch.val() {
            self.available_q.d.next = true;
        }
        if !self.do_write.val() & self.fetch.val() {
            self.available_q.d.next = self.available.q.val() != 1;
        }
        // The next count < depth - reserve, by the same cases as the count:
        // one more word may reach the mark, one fewer may leave it.
        if self.do_write.val() & !self.do_pop.val() {
            self.room_q.d.next =
                self.room_q.q.val() & (self.count.q.val() != self.last_room_count.val());
        }
        if !self.do_write.val() & self.do_pop.val() {
            self.room_q.d.next = self.room_q.q.val() | (self.count.q.val() == self.room_mark.val());
        }

        // The columns: written at the write pointer, fetched from the fetch
        // pointer as the stages shift.
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
        self.mask_column.read_enable.next = self.shift.val();
        self.mask_column.read_address.next = self.fetch_pointer.q.val();
        self.head_mask.next = self.mask_column.read_data.val();
        self.hit_column.write_enable.next = self.do_write.val();
        self.hit_column.write_address.next = self.write_pointer.q.val();
        self.hit_column.write_data.next = self.write_hit_mask.val();
        self.hit_column.read_enable.next = self.shift.val();
        self.hit_column.read_address.next = self.fetch_pointer.q.val();
        self.head_hit_mask.next = self.hit_column.read_data.val();
        self.certain_column.write_enable.next = self.do_write.val();
        self.certain_column.write_address.next = self.write_pointer.q.val();
        self.certain_column.write_data.next = self.write_certain_mask.val();
        self.certain_column.read_enable.next = self.shift.val();
        self.certain_column.read_address.next = self.fetch_pointer.q.val();
        self.head_certain_mask.next = self.certain_column.read_data.val();
        self.stream_id_column.write_enable.next = self.do_write.val();
        self.stream_id_column.write_address.next = self.write_pointer.q.val();
        self.stream_id_column.write_data.next = self.write_stream_id.val();
        self.stream_id_column.read_enable.next = self.shift.val();
        self.stream_id_column.read_address.next = self.fetch_pointer.q.val();
        self.head_stream_id.next = self.stream_id_column.read_data.val();
        for i in 0..self.base_id_columns.len() {
            self.base_id_columns[i].clock.next = self.clock.val();
            self.base_id_columns[i].write_enable.next = self.do_write.val();
            self.base_id_columns[i].write_address.next = self.write_pointer.q.val();
            self.base_id_columns[i].write_data.next = self.write_base_ids[i].val();
            self.base_id_columns[i].read_enable.next = self.shift.val();
            self.base_id_columns[i].read_address.next = self.fetch_pointer.q.val();
            self.head_base_ids[i].next = self.base_id_columns[i].read_data.val();
        }

        if self.reset.val() {
            self.write_pointer.d.next = 0.into();
            self.fetch_pointer.d.next = 0.into();
            self.count.d.next = 0.into();
            self.available.d.next = 0.into();
            self.available_q.d.next = false;
            self.stage_valid.d.next = false;
            self.head_valid_q.d.next = false;
            self.room_q.d.next = true;
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

    /// The stages keep up: a word written into an empty queue is the head
    /// three clocks later, and a burst of words shows a new head in every
    /// clock of a run of pops, in order. Only a head that waited alone
    /// while more words came costs its pop one gap (the module's docs).
    #[test]
    fn a_word_is_the_head_three_clocks_after_its_write_and_pops_run_back_to_back() {
        let mut fifo = ResultFifo::new(1, 16, 2);
        fifo.connect_all();
        fifo.reset.next = true;
        clock_cycle(&mut fifo, |f| &mut f.clock);
        fifo.reset.next = false;
        // Writes `ids` one per clock, then `idle` clocks without writes;
        // returns `head_valid` in each clock from the first write.
        let write = |fifo: &mut ResultFifo, ids: std::ops::Range<u64>, idle: usize| {
            let mut heads = vec![];
            for id in ids {
                heads.push(fifo.head_valid.val());
                fifo.write.next = true;
                fifo.write_stream_id.next = id.into();
                clock_cycle(fifo, |f| &mut f.clock);
            }
            fifo.write.next = false;
            for _ in 0..idle {
                heads.push(fifo.head_valid.val());
                clock_cycle(fifo, |f| &mut f.clock);
            }
            heads
        };
        // Pops every clock while anything is stored; the heads popped, and
        // the clocks that had no head to pop.
        let drain = |fifo: &mut ResultFifo| {
            let (mut popped, mut gaps) = (vec![], 0);
            fifo.pop.next = true;
            while !fifo.empty.val() {
                if fifo.head_valid.val() {
                    popped.push(fifo.head_stream_id.val().to_u64());
                } else {
                    gaps += 1;
                }
                clock_cycle(fifo, |f| &mut f.clock);
            }
            fifo.pop.next = false;
            (popped, gaps)
        };
        let heads = write(&mut fifo, 100..112, 4);
        assert_eq!(heads[..4], [false, false, false, true]);
        assert_eq!(drain(&mut fifo), ((100..112).collect(), 0));
        // A lone word becomes the head; two more come while it waits.
        write(&mut fifo, 200..201, 5);
        write(&mut fifo, 201..203, 5);
        assert_eq!(drain(&mut fifo), ((200..203).collect(), 1));
    }
}
