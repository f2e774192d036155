//! A first-word-fall-through queue of beats: a RAM of `2^A` words (block
//! RAM, or LUTs with [`BeatFifo::in_distributed_ram`]), its read register
//! (the *stage*), a head register and a spare behind it, so the reader of
//! the queue sees a registered word and the RAM's read enable depends on
//! registers only.
//!
//! * A word pushed at edge `t` is in the RAM after `t`; it is fetched into
//!   the stage at `t + 1` and moves to the head at `t + 2`, so an empty
//!   queue shows it (`out_valid`) from the clock after edge `t + 2`.
//! * The stage fetches while the stage, the head and the spare are not all
//!   full. The stage's word moves on every clock it can: to the head when
//!   the head is free (empty or popped) and the spare is empty, else to
//!   the spare, which hands its word to the head first. A full queue so
//!   delivers a word every clock, at the same clocks as a queue whose
//!   stage fetched whenever the head was popped, but a pop reaches only
//!   the head's and the spare's registers: in a 257-bit queue of block
//!   RAMs, a pop that drove the RAMs' clock enables was the list pass's
//!   critical path (23.3 ns, most of it routing across the die).
//! * `count` (words held: RAM, stage, head and spare) is a register. It
//!   holds at most `2^A + 2`; the caller does not push into a full queue
//!   (the reader's credits and the writer's `in_ready` see to it).

use crate::system::dual_port_ram::SimpleDualPortRam;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Bits of the queue's word count.
pub const COUNT_BITS: usize = 16;

#[derive(LogicBlock)]
pub struct BeatFifo<const DW: usize, const A: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: empty.
    pub reset: Signal<In, Bit>,
    pub push: Signal<In, Bit>,
    pub push_data: Signal<In, Bits<DW>>,
    /// Take the head (only with `out_valid`).
    pub pop: Signal<In, Bit>,
    pub out_valid: Signal<Out, Bit>,
    pub out_data: Signal<Out, Bits<DW>>,
    pub count: Signal<Out, Bits<COUNT_BITS>>,
    memory: SimpleDualPortRam<Bits<DW>, A>,
    write_pointer: DFF<Bits<A>>,
    read_pointer: DFF<Bits<A>>,
    /// Words in the RAM not yet fetched.
    stored: DFF<Bits<COUNT_BITS>>,
    stage_valid: DFF<Bit>,
    head_valid: DFF<Bit>,
    head: DFF<Bits<DW>>,
    /// The word after the head, when the stage's word could not go to the
    /// head (only while the head is full).
    spare_valid: DFF<Bit>,
    spare: DFF<Bits<DW>>,
    held: DFF<Bits<COUNT_BITS>>,
    head_free: Signal<Local, Bit>,
    /// The spare takes the stage's word this clock.
    spare_load: Signal<Local, Bit>,
    /// The stage's word leaves it this clock.
    stage_moves: Signal<Local, Bit>,
    fetch: Signal<Local, Bit>,
    popped: Signal<Local, Bit>,
}

impl<const DW: usize, const A: usize> crate::unit::Unit for BeatFifo<DW, A> {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            memory,
            write_pointer,
            read_pointer,
            stored,
            stage_valid,
            head_valid,
            head,
            spare_valid,
            spare,
            held
        );
    }
}

impl<const DW: usize, const A: usize> BeatFifo<DW, A> {
    /// Words the queue holds.
    pub const CAPACITY: usize = (1 << A) + 2;
}

impl<const DW: usize, const A: usize> Default for BeatFifo<DW, A> {
    fn default() -> Self {
        const { assert!(A >= 1 && A < COUNT_BITS - 1) };
        BeatFifo {
            clock: Default::default(),
            reset: Default::default(),
            push: Default::default(),
            push_data: Default::default(),
            pop: Default::default(),
            out_valid: Default::default(),
            out_data: Default::default(),
            count: Default::default(),
            memory: SimpleDualPortRam::new(1 << A).in_block_ram(),
            write_pointer: Default::default(),
            read_pointer: Default::default(),
            stored: Default::default(),
            stage_valid: Default::default(),
            head_valid: Default::default(),
            head: Default::default(),
            spare_valid: Default::default(),
            spare: Default::default(),
            held: Default::default(),
            head_free: Default::default(),
            spare_load: Default::default(),
            stage_moves: Default::default(),
            fetch: Default::default(),
            popped: Default::default(),
        }
    }
}

impl<const DW: usize, const A: usize> BeatFifo<DW, A> {
    /// The queue with its words in distributed RAM (LUTs): for a few
    /// words, where a block RAM would be wasted.
    pub fn in_distributed_ram() -> Self {
        BeatFifo {
            memory: SimpleDualPortRam::new(1 << A),
            ..Default::default()
        }
    }
}

impl<const DW: usize, const A: usize> Logic for BeatFifo<DW, A> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            write_pointer,
            read_pointer,
            stored,
            stage_valid,
            head_valid,
            head,
            spare_valid,
            spare,
            held
        );
        clock!(self, clock, memory);
        self.out_valid.next = self.head_valid.q.val();
        self.out_data.next = self.head.q.val();
        self.count.next = self.held.q.val();
        self.popped.next = self.pop.val() & self.head_valid.q.val();
        self.head_free.next = !self.head_valid.q.val() | self.popped.val();
        // A free head takes the spare's word, else the stage's (or empties).
        if self.head_free.val() {
            self.head_valid.d.next = self.stage_valid.q.val();
            self.head.d.next = self.memory.read_data.val();
            if self.spare_valid.q.val() {
                self.head_valid.d.next = true;
                self.head.d.next = self.spare.q.val();
            }
        }
        // The spare takes the stage's word when its own goes to the head,
        // or when it is empty and the head is not free (the spare is only
        // ever full behind a full head).
        self.spare_load.next = self.head_free.val() == self.spare_valid.q.val();
        if self.spare_load.val() {
            self.spare_valid.d.next = self.stage_valid.q.val();
            self.spare.d.next = self.memory.read_data.val();
        }
        self.stage_moves.next =
            self.stage_valid.q.val() & (self.head_free.val() | !self.spare_valid.q.val());
        // The stage fetches unless it, the head and the spare are all full:
        // registers only, so a pop never reaches the RAM's clock enable.
        // When the stage is full and fetches, its word moves this clock.
        self.fetch.next =
            !(self.stage_valid.q.val() & self.head_valid.q.val() & self.spare_valid.q.val())
                & (self.stored.q.val() != 0);
        self.memory.read_enable.next = self.fetch.val();
        self.memory.read_address.next = self.read_pointer.q.val();
        if self.fetch.val() {
            self.read_pointer.d.next = self.read_pointer.q.val() + 1;
            self.stage_valid.d.next = true;
        } else if self.stage_moves.val() {
            self.stage_valid.d.next = false;
        }
        self.memory.write_enable.next = self.push.val();
        self.memory.write_address.next = self.write_pointer.q.val();
        self.memory.write_data.next = self.push_data.val();
        if self.push.val() {
            self.write_pointer.d.next = self.write_pointer.q.val() + 1;
        }
        if self.push.val() & !self.fetch.val() {
            self.stored.d.next = self.stored.q.val() + 1;
        } else if !self.push.val() & self.fetch.val() {
            self.stored.d.next = self.stored.q.val() - 1;
        }
        if self.push.val() & !self.popped.val() {
            self.held.d.next = self.held.q.val() + 1;
        } else if !self.push.val() & self.popped.val() {
            self.held.d.next = self.held.q.val() - 1;
        }
        if self.reset.val() {
            self.write_pointer.d.next = 0.into();
            self.read_pointer.d.next = 0.into();
            self.stored.d.next = 0.into();
            self.stage_valid.d.next = false;
            self.head_valid.d.next = false;
            self.spare_valid.d.next = false;
            self.held.d.next = 0.into();
        }
    }
}
