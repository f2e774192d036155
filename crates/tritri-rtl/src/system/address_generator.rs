//! The address generator (thesis, chapter 4, figures 4.10–4.12): the write
//! state machine that fills the memories' write bank from the host stream,
//! and the read state machine that walks the other bank in the nested loop
//! of the all-pairs test, from each array's start address over its count
//! (the boundary).
//!
//! # Write side (never stalls)
//!
//! `in_ready` is high while the write bank is free. A transfer
//! (`in_valid & in_ready`) is either a triangle of object A
//! (`in_object = 0`) or B (`in_object = 1`), written at that array's write
//! pointer, or, with `in_end = 1`, the end-of-batch word: the arrays'
//! counts are recorded for that bank, the bank is marked full (handed to
//! the read side) and writing moves to the other bank. Bank `k` starts at address `k · depth`. A triangle beyond `depth`
//! in one array is not written and sets the sticky `overflow` flag.
//!
//! # Read side (holds while `advance` is low)
//!
//! ```text
//! Idle ──(read bank full, both arrays non-empty)──► LoadBases
//!  ▲  └─(read bank full, an array empty: release the bank)─┘ (stays Idle)
//!  │   LoadBases: read A[a], bset to pipeline `lane`, a += 1, lane += 1;
//!  │              after P bases or the last A ─► StreamB (b = start of B)
//!  │   StreamB:   read B[b] for every loaded pipeline, b += 1;
//!  │              after the last B ─► LoadBases (next group of bases)
//!  └───────────── or, after the last A's group, release the bank ─► Idle
//! ```
//!
//! One memory read per cycle in LoadBases and StreamB, so a batch of `N1`
//! A-triangles and `N2` B-triangles issues `N1 + ceil(N1 / P) · N2` reads
//! after one Idle cycle (the thesis's `N1 + N1 · N2` for `P = 1`). The
//! memories answer [`MEMORY_READ_LATENCY`] cycles later; `bset` and
//! `lane_valid` pass through as many registers, so that they arrive with
//! the data. `done` is high when no bank is full, the read side is idle and
//! the last streamed pair has left the pipelines (`L` plus the read latency
//! in advancing cycles after its read).
//!
//! The read side counts down what is left of each array (`a_left`,
//! `b_left`) beside the address pointers, and keeps its end tests on them
//! (one left, none left) in registers, set as the counts change, so that
//! its next state waits on no comparison: testing `pointer + 1 == end` put
//! an adder and a 16-bit comparison before the next state (110 MHz on
//! ECP5), and comparing the counts there, with `advance`, still held the
//! W = 16 system at 128.9 MHz. The write side does the same for a full
//! array (`a_write_full`): comparing the write pointer with the bank's end
//! put an adder and four levels of logic between the host's `in_valid` and
//! the block RAMs' write enables, the system's critical path at 128.9 MHz.

use super::{ADDRESS_BITS, LANE_BITS, MAX_TRIANGLES_PER_BANK, MEMORY_READ_LATENCY};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// The read state machine's states.
#[derive(Copy, Clone, PartialEq, Eq, Debug, LogicState)]
pub enum ReadState {
    Idle,
    LoadBases,
    StreamB,
}

/// `bset` and `lane_valid` are registered twice below (`*_read`, `*_q`),
/// once per clock of the memories' read.
const _: () = assert!(MEMORY_READ_LATENCY == 2);

/// Width of the in-flight countdown (read latency + pipeline latency + the
/// counters' < 256).
pub const FLIGHT_BITS: usize = 8;

#[derive(LogicBlock)]
pub struct AddressGenerator {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    /// Clock enable of the read side (low while the result FIFO is above its mark).
    pub advance: Signal<In, Bit>,
    // Host triangle stream (the data fields go straight to the memories).
    pub in_valid: Signal<In, Bit>,
    pub in_end: Signal<In, Bit>,
    pub in_object: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    // Memory write ports.
    pub a_write_enable: Signal<Out, Bit>,
    pub a_write_address: Signal<Out, Bits<ADDRESS_BITS>>,
    pub b_write_enable: Signal<Out, Bit>,
    pub b_write_address: Signal<Out, Bits<ADDRESS_BITS>>,
    // Memory read addresses (the read enable is `advance`).
    pub a_read_address: Signal<Out, Bits<ADDRESS_BITS>>,
    pub b_read_address: Signal<Out, Bits<ADDRESS_BITS>>,
    /// The triangle on the memories' read data is a base (from A) rather
    /// than a streamed one (from B); aligned with the read data.
    pub bset: Signal<Out, Bit>,
    /// Per pipeline: the triangle on the bus is for it; aligned with the
    /// read data.
    pub lane_valid: Vec<Signal<Out, Bit>>,
    pub done: Signal<Out, Bit>,
    pub overflow: Signal<Out, Bit>,
    // Generator parameters.
    bank_size: Constant<Bits<ADDRESS_BITS>>,
    /// `bank_size - 1`: a write at this count fills the array.
    last_index: Constant<Bits<ADDRESS_BITS>>,
    last_lane: Constant<Bits<LANE_BITS>>,
    flight_cycles: Constant<Bits<FLIGHT_BITS>>,
    // Write side.
    write_bank: DFF<Bit>,
    a_write_pointer: DFF<Bits<ADDRESS_BITS>>,
    b_write_pointer: DFF<Bits<ADDRESS_BITS>>,
    overflow_q: DFF<Bit>,
    /// Triangles written to each array of the write bank.
    a_write_count: DFF<Bits<ADDRESS_BITS>>,
    b_write_count: DFF<Bits<ADDRESS_BITS>>,
    /// Each array of the write bank holds `triangles_per_bank` triangles
    /// (its count equals the depth), decided as the count reaches it.
    a_write_full: DFF<Bit>,
    b_write_full: DFF<Bit>,
    // Shared: per bank, full flag, counts and empty flag.
    bank_full: [DFF<Bit>; 2],
    /// Per bank: triangles written to each array, and whether one of the
    /// two is empty (the bank has no pairs).
    a_bank_count: [DFF<Bits<ADDRESS_BITS>>; 2],
    b_bank_count: [DFF<Bits<ADDRESS_BITS>>; 2],
    bank_empty: [DFF<Bit>; 2],
    // Read side.
    read_state: DFF<ReadState>,
    read_bank: DFF<Bit>,
    a_read_pointer: DFF<Bits<ADDRESS_BITS>>,
    /// A triangles not yet loaded as bases, and whether that is one, or none.
    a_left: DFF<Bits<ADDRESS_BITS>>,
    a_left_one: DFF<Bit>,
    a_left_none: DFF<Bit>,
    b_read_pointer: DFF<Bits<ADDRESS_BITS>>,
    /// B triangles in the read bank, and those not yet streamed this pass.
    b_count: DFF<Bits<ADDRESS_BITS>>,
    b_left: DFF<Bits<ADDRESS_BITS>>,
    /// `b_left == 1`.
    b_left_one: DFF<Bit>,
    lane: DFF<Bits<LANE_BITS>>,
    lane_active: Vec<DFF<Bit>>,
    /// `lane_valid` and `bset` aligned with the block RAMs' read data, then
    /// with the memories' output registers (the ports).
    lane_valid_read: Vec<DFF<Bit>>,
    lane_valid_q: Vec<DFF<Bit>>,
    bset_read: DFF<Bit>,
    bset_q: DFF<Bit>,
    flight: DFF<Bits<FLIGHT_BITS>>,
    // Combinational.
    transfer: Signal<Local, Bit>,
    other_bank_start: Signal<Local, Bits<ADDRESS_BITS>>,
    read_bank_start: Signal<Local, Bits<ADDRESS_BITS>>,
    read_bank_full: Signal<Local, Bit>,
    read_bank_a_count: Signal<Local, Bits<ADDRESS_BITS>>,
    read_bank_b_count: Signal<Local, Bits<ADDRESS_BITS>>,
    read_bank_empty: Signal<Local, Bit>,
    load_issue: Signal<Local, Bit>,
    stream_issue: Signal<Local, Bit>,
    release_bank: Signal<Local, Bit>,
}

impl crate::unit::Unit for AddressGenerator {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            write_bank,
            a_write_pointer,
            b_write_pointer,
            overflow_q,
            a_write_count,
            b_write_count,
            a_write_full,
            b_write_full,
            bank_full,
            a_bank_count,
            b_bank_count,
            bank_empty,
            read_state,
            read_bank,
            a_read_pointer,
            a_left,
            a_left_one,
            a_left_none,
            b_read_pointer,
            b_count,
            b_left,
            b_left_one,
            lane,
            lane_active,
            lane_valid_read,
            lane_valid_q,
            bset_read,
            bset_q,
            flight
        );
    }
}

impl AddressGenerator {
    /// `pipelines` pipelines, memories of `triangles_per_bank` triangles
    /// per array per bank, and `done` rising `flight_cycles + 1` clocks
    /// after the last streamed read
    /// ([`SystemConfig::read_to_counted_cycles`](super::SystemConfig::read_to_counted_cycles)).
    pub fn new(pipelines: usize, triangles_per_bank: usize, flight_cycles: usize) -> Self {
        assert!(pipelines >= 1 && pipelines <= 1 << LANE_BITS);
        assert!((1..=MAX_TRIANGLES_PER_BANK).contains(&triangles_per_bank));
        assert!(flight_cycles < 1 << FLIGHT_BITS);
        AddressGenerator {
            clock: Default::default(),
            reset: Default::default(),
            advance: Default::default(),
            in_valid: Default::default(),
            in_end: Default::default(),
            in_object: Default::default(),
            in_ready: Default::default(),
            a_write_enable: Default::default(),
            a_write_address: Default::default(),
            b_write_enable: Default::default(),
            b_write_address: Default::default(),
            a_read_address: Default::default(),
            b_read_address: Default::default(),
            bset: Default::default(),
            lane_valid: (0..pipelines).map(|_| Default::default()).collect(),
            done: Default::default(),
            overflow: Default::default(),
            bank_size: Constant::new((triangles_per_bank as u64).to_bits()),
            last_index: Constant::new(((triangles_per_bank - 1) as u64).to_bits()),
            last_lane: Constant::new(((pipelines - 1) as u64).to_bits()),
            flight_cycles: Constant::new((flight_cycles as u64).to_bits()),
            write_bank: Default::default(),
            a_write_pointer: Default::default(),
            b_write_pointer: Default::default(),
            overflow_q: Default::default(),
            bank_full: Default::default(),
            a_bank_count: Default::default(),
            b_bank_count: Default::default(),
            bank_empty: Default::default(),
            a_write_count: Default::default(),
            b_write_count: Default::default(),
            a_write_full: Default::default(),
            b_write_full: Default::default(),
            read_state: Default::default(),
            read_bank: Default::default(),
            a_read_pointer: Default::default(),
            a_left: Default::default(),
            a_left_one: Default::default(),
            a_left_none: Default::default(),
            b_read_pointer: Default::default(),
            b_count: Default::default(),
            b_left: Default::default(),
            b_left_one: Default::default(),
            lane: Default::default(),
            lane_active: (0..pipelines).map(|_| Default::default()).collect(),
            lane_valid_read: (0..pipelines).map(|_| Default::default()).collect(),
            lane_valid_q: (0..pipelines).map(|_| Default::default()).collect(),
            bset_read: Default::default(),
            bset_q: Default::default(),
            flight: Default::default(),
            transfer: Default::default(),
            other_bank_start: Default::default(),
            read_bank_start: Default::default(),
            read_bank_full: Default::default(),
            read_bank_a_count: Default::default(),
            read_bank_b_count: Default::default(),
            read_bank_empty: Default::default(),
            load_issue: Default::default(),
            stream_issue: Default::default(),
            release_bank: Default::default(),
        }
    }
}

impl Logic for AddressGenerator {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            write_bank,
            a_write_pointer,
            b_write_pointer,
            overflow_q,
            a_write_count,
            b_write_count,
            a_write_full,
            b_write_full,
            read_state,
            read_bank,
            a_read_pointer,
            a_left,
            a_left_one,
            a_left_none,
            b_read_pointer,
            b_count,
            b_left,
            b_left_one,
            lane,
            bset_read,
            bset_q,
            flight
        );
        for k in 0..2 {
            self.bank_full[k].clock.next = self.clock.val();
            self.bank_full[k].d.next = self.bank_full[k].q.val();
            self.a_bank_count[k].clock.next = self.clock.val();
            self.a_bank_count[k].d.next = self.a_bank_count[k].q.val();
            self.b_bank_count[k].clock.next = self.clock.val();
            self.b_bank_count[k].d.next = self.b_bank_count[k].q.val();
            self.bank_empty[k].clock.next = self.clock.val();
            self.bank_empty[k].d.next = self.bank_empty[k].q.val();
        }
        for i in 0..self.lane_valid.len() {
            self.lane_active[i].clock.next = self.clock.val();
            self.lane_active[i].d.next = self.lane_active[i].q.val();
            self.lane_valid_read[i].clock.next = self.clock.val();
            self.lane_valid_read[i].d.next = self.lane_valid_read[i].q.val();
            self.lane_valid_q[i].clock.next = self.clock.val();
            self.lane_valid_q[i].d.next = self.lane_valid_q[i].q.val();
            self.lane_valid[i].next = self.lane_valid_q[i].q.val();
        }

        // ---- Write side: host stream into the write bank.
        self.other_bank_start.next = self.bank_size.val();
        self.in_ready.next = !self.bank_full[0].q.val();
        if self.write_bank.q.val() {
            self.other_bank_start.next = 0.into();
            self.in_ready.next = !self.bank_full[1].q.val();
        }
        self.transfer.next = self.in_valid.val() & self.in_ready.val();
        self.a_write_address.next = self.a_write_pointer.q.val();
        self.b_write_address.next = self.b_write_pointer.q.val();
        self.a_write_enable.next = false;
        self.b_write_enable.next = false;
        if self.transfer.val() & !self.in_end.val() {
            if self.in_object.val() {
                if self.b_write_full.q.val() {
                    self.overflow_q.d.next = true;
                } else {
                    self.b_write_enable.next = true;
                    self.b_write_pointer.d.next = self.b_write_pointer.q.val() + 1;
                    self.b_write_count.d.next = self.b_write_count.q.val() + 1;
                    self.b_write_full.d.next = self.b_write_count.q.val() == self.last_index.val();
                }
            } else {
                if self.a_write_full.q.val() {
                    self.overflow_q.d.next = true;
                } else {
                    self.a_write_enable.next = true;
                    self.a_write_pointer.d.next = self.a_write_pointer.q.val() + 1;
                    self.a_write_count.d.next = self.a_write_count.q.val() + 1;
                    self.a_write_full.d.next = self.a_write_count.q.val() == self.last_index.val();
                }
            }
        }
        if self.transfer.val() & self.in_end.val() {
            // End of batch: record the arrays' counts, hand the bank over.
            if self.write_bank.q.val() {
                self.bank_full[1].d.next = true;
                self.a_bank_count[1].d.next = self.a_write_count.q.val();
                self.b_bank_count[1].d.next = self.b_write_count.q.val();
                self.bank_empty[1].d.next =
                    (self.a_write_count.q.val() == 0) | (self.b_write_count.q.val() == 0);
            } else {
                self.bank_full[0].d.next = true;
                self.a_bank_count[0].d.next = self.a_write_count.q.val();
                self.b_bank_count[0].d.next = self.b_write_count.q.val();
                self.bank_empty[0].d.next =
                    (self.a_write_count.q.val() == 0) | (self.b_write_count.q.val() == 0);
            }
            self.write_bank.d.next = !self.write_bank.q.val();
            self.a_write_pointer.d.next = self.other_bank_start.val();
            self.b_write_pointer.d.next = self.other_bank_start.val();
            self.a_write_count.d.next = 0.into();
            self.b_write_count.d.next = 0.into();
            self.a_write_full.d.next = false;
            self.b_write_full.d.next = false;
        }

        // ---- Read side: the nested loop over the read bank.
        self.read_bank_start.next = 0.into();
        self.read_bank_full.next = self.bank_full[0].q.val();
        self.read_bank_a_count.next = self.a_bank_count[0].q.val();
        self.read_bank_b_count.next = self.b_bank_count[0].q.val();
        self.read_bank_empty.next = self.bank_empty[0].q.val();
        if self.read_bank.q.val() {
            self.read_bank_start.next = self.bank_size.val();
            self.read_bank_full.next = self.bank_full[1].q.val();
            self.read_bank_a_count.next = self.a_bank_count[1].q.val();
            self.read_bank_b_count.next = self.b_bank_count[1].q.val();
            self.read_bank_empty.next = self.bank_empty[1].q.val();
        }
        self.a_read_address.next = self.a_read_pointer.q.val();
        self.b_read_address.next = self.b_read_pointer.q.val();
        self.load_issue.next = false;
        self.stream_issue.next = false;
        self.release_bank.next = false;
        if self.advance.val() {
            match self.read_state.q.val() {
                ReadState::Idle => {
                    if self.read_bank_full.val() {
                        self.a_read_pointer.d.next = self.read_bank_start.val();
                        self.b_read_pointer.d.next = self.read_bank_start.val();
                        self.a_left.d.next = self.read_bank_a_count.val();
                        self.a_left_one.d.next = self.read_bank_a_count.val() == 1;
                        self.a_left_none.d.next = self.read_bank_a_count.val() == 0;
                        self.b_count.d.next = self.read_bank_b_count.val();
                        self.lane.d.next = 0.into();
                        if self.read_bank_empty.val() {
                            self.release_bank.next = true;
                        } else {
                            self.read_state.d.next = ReadState::LoadBases;
                        }
                    }
                }
                ReadState::LoadBases => {
                    self.load_issue.next = true;
                    self.a_read_pointer.d.next = self.a_read_pointer.q.val() + 1;
                    self.a_left.d.next = self.a_left.q.val() - 1;
                    self.a_left_one.d.next = self.a_left.q.val() == 2;
                    self.a_left_none.d.next = self.a_left_one.q.val();
                    self.lane.d.next = self.lane.q.val() + 1;
                    if (self.lane.q.val() == self.last_lane.val()) | self.a_left_one.q.val() {
                        self.read_state.d.next = ReadState::StreamB;
                        self.b_read_pointer.d.next = self.read_bank_start.val();
                        self.b_left.d.next = self.b_count.q.val();
                        self.b_left_one.d.next = self.b_count.q.val() == 1;
                    }
                }
                ReadState::StreamB => {
                    self.stream_issue.next = true;
                    self.b_read_pointer.d.next = self.b_read_pointer.q.val() + 1;
                    self.b_left.d.next = self.b_left.q.val() - 1;
                    self.b_left_one.d.next = self.b_left.q.val() == 2;
                    if self.b_left_one.q.val() {
                        if self.a_left_none.q.val() {
                            self.release_bank.next = true;
                            self.read_state.d.next = ReadState::Idle;
                        } else {
                            self.read_state.d.next = ReadState::LoadBases;
                            self.lane.d.next = 0.into();
                        }
                    }
                }
            }
            // Registered with the block RAMs' read data, then with the
            // memories' output registers.
            self.bset_read.d.next = self.load_issue.val();
            self.bset_q.d.next = self.bset_read.q.val();
            for i in 0..self.lane_valid.len() {
                self.lane_valid_q[i].d.next = self.lane_valid_read[i].q.val();
                self.lane_valid_read[i].d.next =
                    self.stream_issue.val() & self.lane_active[i].q.val();
                if self.load_issue.val() {
                    if self.lane.q.val().index() == i {
                        self.lane_valid_read[i].d.next = true;
                        self.lane_active[i].d.next = true;
                    } else {
                        self.lane_valid_read[i].d.next = false;
                        if self.lane.q.val() == 0 {
                            self.lane_active[i].d.next = false;
                        }
                    }
                }
            }
            // Pairs in flight: the last streamed read's verdicts are
            // counted `flight_cycles` advancing cycles later.
            if self.stream_issue.val() {
                self.flight.d.next = self.flight_cycles.val();
            } else if self.flight.q.val() != 0 {
                self.flight.d.next = self.flight.q.val() - 1;
            }
            if self.release_bank.val() {
                if self.read_bank.q.val() {
                    self.bank_full[1].d.next = false;
                } else {
                    self.bank_full[0].d.next = false;
                }
                self.read_bank.d.next = !self.read_bank.q.val();
            }
        }
        self.bset.next = self.bset_q.q.val();
        self.overflow.next = self.overflow_q.q.val();
        self.done.next = !self.bank_full[0].q.val()
            & !self.bank_full[1].q.val()
            & (self.read_state.q.val() == ReadState::Idle)
            & (self.flight.q.val() == 0);

        // Synchronous reset of all control state.
        if self.reset.val() {
            self.write_bank.d.next = false;
            self.a_write_pointer.d.next = 0.into();
            self.b_write_pointer.d.next = 0.into();
            self.a_write_count.d.next = 0.into();
            self.b_write_count.d.next = 0.into();
            self.a_write_full.d.next = false;
            self.b_write_full.d.next = false;
            self.overflow_q.d.next = false;
            self.read_state.d.next = ReadState::Idle;
            self.read_bank.d.next = false;
            self.lane.d.next = 0.into();
            self.bset_read.d.next = false;
            self.bset_q.d.next = false;
            self.flight.d.next = 0.into();
            for k in 0..2 {
                self.bank_full[k].d.next = false;
            }
            for i in 0..self.lane_valid.len() {
                self.lane_active[i].d.next = false;
                self.lane_valid_read[i].d.next = false;
                self.lane_valid_q[i].d.next = false;
            }
        }
    }
}
