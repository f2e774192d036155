//! A region of external memory read over AXI4 and streamed out a beat at
//! a time: `start` with a base address (aligned to the beat) and a number
//! of beats, and the unit issues INCR bursts ([`super::burst_beats`]: at
//! most `max_burst` beats, cut at 4 KB boundaries), at most `outstanding`
//! in flight, each only when its queue has room for all its beats, so
//! `rready` is always high and the memory never waits on the reader.
//!
//! Clocks: an AR request is issued (`arvalid` rises) the clock after the
//! unit decides it, and the next request is decided the clock after the
//! memory took it, so a request goes out at most every second clock. A
//! beat taken at edge `t` leaves the queue from the clock after edge
//! `t + 2` ([`super::beat_fifo`]). [`super::transfer_machine`] is the
//! clock-exact model.

use super::beat_fifo::{BeatFifo, COUNT_BITS};
use super::burst_rule::{BurstRule, RULE_BITS};
use super::{ADDRESS_BITS, MAX_OUTSTANDING};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Bits of a beat count.
pub const BEAT_BITS: usize = 32;
/// Bits of the count of bursts in flight.
pub const OUTSTANDING_BITS: usize = 4;
const _: () = assert!(MAX_OUTSTANDING < 1 << OUTSTANDING_BITS);
// The credits add the rule's burst to the queue's count.
const _: () = assert!(RULE_BITS == COUNT_BITS);

#[derive(LogicBlock)]
pub struct BurstReader<const DW: usize, const A: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high.
    pub reset: Signal<In, Bit>,
    /// One clock high while not busy: read `beats` beats from `base`.
    pub start: Signal<In, Bit>,
    pub base: Signal<In, Bits<ADDRESS_BITS>>,
    pub beats: Signal<In, Bits<BEAT_BITS>>,
    /// Always 0: one ID, so responses come in order.
    pub m_axi_arid: Signal<Out, Bit>,
    pub m_axi_araddr: Signal<Out, Bits<ADDRESS_BITS>>,
    pub m_axi_arlen: Signal<Out, Bits<8>>,
    pub m_axi_arsize: Signal<Out, Bits<3>>,
    pub m_axi_arburst: Signal<Out, Bits<2>>,
    pub m_axi_arcache: Signal<Out, Bits<4>>,
    pub m_axi_arprot: Signal<Out, Bits<3>>,
    pub m_axi_arvalid: Signal<Out, Bit>,
    pub m_axi_arready: Signal<In, Bit>,
    /// A beat with another ID than 0 is a fault (`error`).
    pub m_axi_rid: Signal<In, Bit>,
    pub m_axi_rdata: Signal<In, Bits<DW>>,
    pub m_axi_rresp: Signal<In, Bits<2>>,
    pub m_axi_rlast: Signal<In, Bit>,
    pub m_axi_rvalid: Signal<In, Bit>,
    pub m_axi_rready: Signal<Out, Bit>,
    /// The beats, in address order.
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_data: Signal<Out, Bits<DW>>,
    /// With the region's last beat.
    pub out_last: Signal<Out, Bit>,
    /// From the clock after `start` until the last beat has left.
    pub busy: Signal<Out, Bit>,
    /// A read response was not OKAY, or not for ID 0, since `start`
    /// (sticky).
    pub error: Signal<Out, Bit>,
    queue: BeatFifo<DW, A>,
    /// The next burst's beats.
    rule: BurstRule,
    /// The bursts in flight allowed, the beats the queue holds and
    /// `log2(DW / 8)`.
    outstanding: Constant<Bits<OUTSTANDING_BITS>>,
    capacity: Constant<Bits<COUNT_BITS>>,
    size: Constant<Bits<3>>,
    running: DFF<Bit>,
    failed: DFF<Bit>,
    next_address: DFF<Bits<ADDRESS_BITS>>,
    /// Beats not yet requested, and not yet delivered.
    to_request: DFF<Bits<BEAT_BITS>>,
    to_deliver: DFF<Bits<BEAT_BITS>>,
    in_flight: DFF<Bits<OUTSTANDING_BITS>>,
    /// Beats requested and not yet delivered: the queue's room they hold.
    committed: DFF<Bits<COUNT_BITS>>,
    ar_valid: DFF<Bit>,
    ar_address: DFF<Bits<ADDRESS_BITS>>,
    ar_length: DFF<Bits<8>>,
    /// The next burst's beats, a clock behind the registers it is computed
    /// from (the rule's minimum is too long a path to also decide the
    /// issue in the same clock), and whether it is up to date: not in the
    /// clock after a start or an issue, which change those registers.
    burst_q: DFF<Bits<COUNT_BITS>>,
    burst_ok: DFF<Bit>,
    issue: Signal<Local, Bit>,
    /// The queue's count, not needed here (the credits are `committed`).
    unused_count: Signal<Local, Bit>,
    burst_done: Signal<Local, Bit>,
    delivered: Signal<Local, Bit>,
}

impl<const DW: usize, const A: usize> crate::unit::Unit for BurstReader<DW, A> {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            queue,
            rule,
            running,
            failed,
            next_address,
            to_request,
            to_deliver,
            in_flight,
            committed,
            ar_valid,
            ar_address,
            ar_length,
            burst_q,
            burst_ok
        );
    }
    fn settings(&self) -> Vec<(&'static str, String)> {
        vec![
            ("max_burst", self.rule.max_burst().to_string()),
            ("outstanding", self.outstanding.val().index().to_string()),
        ]
    }
}

impl<const DW: usize, const A: usize> BurstReader<DW, A> {
    /// A reader issuing bursts of at most `max_burst` beats, at most
    /// `outstanding` in flight.
    pub fn new(max_burst: usize, outstanding: usize) -> Self {
        let config = super::TransferConfig {
            data_bits: DW,
            max_burst,
            outstanding,
            queue_beats: BeatFifo::<DW, A>::CAPACITY,
        };
        if let Err(e) = config.check() {
            panic!("BurstReader: {e}");
        }
        let beat_bytes = (DW / 8) as u64;
        BurstReader {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            base: Default::default(),
            beats: Default::default(),
            m_axi_arid: Default::default(),
            m_axi_araddr: Default::default(),
            m_axi_arlen: Default::default(),
            m_axi_arsize: Default::default(),
            m_axi_arburst: Default::default(),
            m_axi_arcache: Default::default(),
            m_axi_arprot: Default::default(),
            m_axi_arvalid: Default::default(),
            m_axi_arready: Default::default(),
            m_axi_rid: Default::default(),
            m_axi_rdata: Default::default(),
            m_axi_rresp: Default::default(),
            m_axi_rlast: Default::default(),
            m_axi_rvalid: Default::default(),
            m_axi_rready: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_data: Default::default(),
            out_last: Default::default(),
            busy: Default::default(),
            error: Default::default(),
            queue: Default::default(),
            rule: BurstRule::new(beat_bytes, max_burst),
            outstanding: Constant::new((outstanding as u64).into()),
            capacity: Constant::new((BeatFifo::<DW, A>::CAPACITY as u64).into()),
            size: Constant::new((beat_bytes.trailing_zeros() as u64).into()),
            running: Default::default(),
            failed: Default::default(),
            next_address: Default::default(),
            to_request: Default::default(),
            to_deliver: Default::default(),
            in_flight: Default::default(),
            committed: Default::default(),
            ar_valid: Default::default(),
            ar_address: Default::default(),
            ar_length: Default::default(),
            burst_q: Default::default(),
            burst_ok: Default::default(),
            issue: Default::default(),
            unused_count: Default::default(),
            burst_done: Default::default(),
            delivered: Default::default(),
        }
    }
}

impl<const DW: usize, const A: usize> Logic for BurstReader<DW, A> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            running,
            failed,
            next_address,
            to_request,
            to_deliver,
            in_flight,
            committed,
            ar_valid,
            ar_address,
            ar_length,
            burst_q,
            burst_ok
        );
        clock!(self, clock, queue);
        self.queue.reset.next = self.reset.val();
        self.unused_count.next = self.queue.count.val().any();
        self.m_axi_arid.next = false;
        self.m_axi_araddr.next = self.ar_address.q.val();
        self.m_axi_arlen.next = self.ar_length.q.val();
        self.m_axi_arsize.next = self.size.val();
        self.m_axi_arburst.next = 1.into();
        self.m_axi_arcache.next = 3.into();
        self.m_axi_arprot.next = 0.into();
        self.m_axi_arvalid.next = self.ar_valid.q.val();
        self.m_axi_rready.next = true;
        self.busy.next = self.running.q.val();
        self.error.next = self.failed.q.val();
        // Every beat goes into the queue: the credits kept room for it.
        self.queue.push.next = self.m_axi_rvalid.val();
        self.queue.push_data.next = self.m_axi_rdata.val();
        if self.m_axi_rvalid.val() & ((self.m_axi_rresp.val() != 0) | self.m_axi_rid.val()) {
            self.failed.d.next = true;
        }
        self.burst_done.next = self.m_axi_rvalid.val() & self.m_axi_rlast.val();
        self.out_valid.next = self.queue.out_valid.val();
        self.out_data.next = self.queue.out_data.val();
        self.out_last.next = self.to_deliver.q.val() == 1;
        self.delivered.next = self.queue.out_valid.val() & self.out_ready.val();
        self.queue.pop.next = self.delivered.val();
        if self.delivered.val() {
            self.to_deliver.d.next = self.to_deliver.q.val() - 1;
        }
        if self.ar_valid.q.val() & self.m_axi_arready.val() {
            self.ar_valid.d.next = false;
        }
        // The next burst: at most max_burst beats, to the page's end, and
        // what is left.
        self.rule.address.next = bit_cast::<RULE_BITS, ADDRESS_BITS>(self.next_address.q.val());
        self.rule.left.next = self.to_request.q.val();
        self.burst_q.d.next = self.rule.beats.val();
        self.burst_ok.d.next = true;
        self.issue.next = self.running.q.val()
            & !self.ar_valid.q.val()
            & self.burst_ok.q.val()
            & (self.to_request.q.val() != 0)
            & (self.in_flight.q.val() < self.outstanding.val())
            & (self.committed.q.val() + self.burst_q.q.val() <= self.capacity.val());
        if self.issue.val() {
            self.burst_ok.d.next = false;
            self.ar_valid.d.next = true;
            self.ar_address.d.next = self.next_address.q.val();
            self.ar_length.d.next = bit_cast::<8, COUNT_BITS>(self.burst_q.q.val() - 1);
            self.next_address.d.next = self.next_address.q.val()
                + (bit_cast::<BEAT_BITS, COUNT_BITS>(self.burst_q.q.val()) << self.size.val());
            self.to_request.d.next =
                self.to_request.q.val() - bit_cast::<BEAT_BITS, COUNT_BITS>(self.burst_q.q.val());
        }
        if self.issue.val() & !self.burst_done.val() {
            self.in_flight.d.next = self.in_flight.q.val() + 1;
        } else if !self.issue.val() & self.burst_done.val() {
            self.in_flight.d.next = self.in_flight.q.val() - 1;
        }
        if self.issue.val() & self.delivered.val() {
            self.committed.d.next = self.committed.q.val() + self.burst_q.q.val() - 1;
        } else if self.issue.val() {
            self.committed.d.next = self.committed.q.val() + self.burst_q.q.val();
        } else if self.delivered.val() {
            self.committed.d.next = self.committed.q.val() - 1;
        }
        if self.running.q.val() & (self.to_deliver.q.val() == 0) {
            self.running.d.next = false;
        }
        if self.start.val() & !self.running.q.val() {
            self.burst_ok.d.next = false;
            self.running.d.next = true;
            self.failed.d.next = false;
            self.next_address.d.next = self.base.val();
            self.to_request.d.next = self.beats.val();
            self.to_deliver.d.next = self.beats.val();
        }
        if self.reset.val() {
            self.running.d.next = false;
            self.failed.d.next = false;
            self.to_request.d.next = 0.into();
            self.to_deliver.d.next = 0.into();
            self.in_flight.d.next = 0.into();
            self.committed.d.next = 0.into();
            self.ar_valid.d.next = false;
        }
    }
}
