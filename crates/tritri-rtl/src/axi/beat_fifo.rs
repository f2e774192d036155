//! A first-word-fall-through queue of beats: a RAM of `2^A` words (block
//! RAM, or LUTs with [`BeatFifo::in_distributed_ram`]), its read register (the *stage*) and a head register, so the reader of
//! the queue sees a registered word and a pop reaches the RAM only through
//! its read enable.
//!
//! * A word pushed at edge `t` is in the RAM after `t`; it is fetched into
//!   the stage at `t + 1` and moves to the head at `t + 2`, so an empty
//!   queue shows it (`out_valid`) from the clock after edge `t + 2`.
//! * The stage and the head move together: the head takes the stage when
//!   it is empty or popped, and the stage fetches when it is empty or
//!   moves, so a full queue delivers a word every clock.
//! * `count` (words held: RAM, stage and head) is a register. It holds at
//!   most `2^A + 2`; the caller does not push into a full queue (the
//!   reader's credits and the writer's `in_ready` see to it).

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
    held: DFF<Bits<COUNT_BITS>>,
    head_free: Signal<Local, Bit>,
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
            held: Default::default(),
            head_free: Default::default(),
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
            held
        );
        clock!(self, clock, memory);
        self.out_valid.next = self.head_valid.q.val();
        self.out_data.next = self.head.q.val();
        self.count.next = self.held.q.val();
        self.popped.next = self.pop.val() & self.head_valid.q.val();
        self.head_free.next = !self.head_valid.q.val() | self.popped.val();
        // The head takes the stage's word, or empties when popped.
        if self.head_free.val() {
            self.head_valid.d.next = self.stage_valid.q.val();
            self.head.d.next = self.memory.read_data.val();
        }
        // The stage fetches when it is empty or its word moves on.
        self.fetch.next =
            (!self.stage_valid.q.val() | self.head_free.val()) & (self.stored.q.val() != 0);
        self.memory.read_enable.next = self.fetch.val();
        self.memory.read_address.next = self.read_pointer.q.val();
        if self.fetch.val() {
            self.read_pointer.d.next = self.read_pointer.q.val() + 1;
            self.stage_valid.d.next = true;
        } else if self.head_free.val() {
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
            self.held.d.next = 0.into();
        }
    }
}
