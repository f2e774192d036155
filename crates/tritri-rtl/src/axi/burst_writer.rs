//! A stream of beats written to external memory over AXI4: `start` with a
//! base address (aligned to the beat), then the beats (`in_last` with the
//! last, or `flush` after it), and the unit writes them in INCR bursts
//! ([`super::burst_beats`]: at most `max_burst` beats, cut at 4 KB
//! boundaries), at most `outstanding` without their write response.
//!
//! A burst is issued only when the queue holds every beat of it: a full
//! burst while the stream runs, the rest once it has ended. So `wvalid`
//! never falls inside a burst for want of data, and the stream's length
//! need not be known at `start`. Every byte of a beat is written (`wstrb`
//! all ones): a region is a whole number of beats.
//!
//! The W channel takes each burst's length from a small queue the AW side
//! writes as it issues the burst, so `wlast` is a register compare.
//! `busy` falls when every burst's response has come back.

use super::beat_fifo::BeatFifo;
use super::burst_reader::{BEAT_BITS, OUTSTANDING_BITS};
use super::burst_rule::{BurstRule, RULE_BITS};
use super::ADDRESS_BITS;

/// Bits of a burst length (1 to 256 beats).
pub const LENGTH_BITS: usize = 9;
/// Address bits of the queue of burst lengths: 16 words, more than the
/// bursts that can be in flight.
const LENGTH_QUEUE_ADDRESS_BITS: usize = 4;
const _: () = assert!(super::MAX_OUTSTANDING < 1 << LENGTH_QUEUE_ADDRESS_BITS);
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

#[derive(LogicBlock)]
pub struct BurstWriter<const DW: usize, const S: usize, const A: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high.
    pub reset: Signal<In, Bit>,
    /// One clock high while not busy: a stream to write from `base` begins.
    pub start: Signal<In, Bit>,
    pub base: Signal<In, Bits<ADDRESS_BITS>>,
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_data: Signal<In, Bits<DW>>,
    /// With the stream's last beat.
    pub in_last: Signal<In, Bit>,
    /// The stream has ended (after its last beat, or with none at all).
    pub flush: Signal<In, Bit>,
    /// Always 0: one ID, so responses come in order.
    pub m_axi_awid: Signal<Out, Bit>,
    pub m_axi_awaddr: Signal<Out, Bits<ADDRESS_BITS>>,
    pub m_axi_awlen: Signal<Out, Bits<8>>,
    pub m_axi_awsize: Signal<Out, Bits<3>>,
    pub m_axi_awburst: Signal<Out, Bits<2>>,
    pub m_axi_awcache: Signal<Out, Bits<4>>,
    pub m_axi_awprot: Signal<Out, Bits<3>>,
    pub m_axi_awvalid: Signal<Out, Bit>,
    pub m_axi_awready: Signal<In, Bit>,
    pub m_axi_wdata: Signal<Out, Bits<DW>>,
    pub m_axi_wstrb: Signal<Out, Bits<S>>,
    pub m_axi_wlast: Signal<Out, Bit>,
    pub m_axi_wvalid: Signal<Out, Bit>,
    pub m_axi_wready: Signal<In, Bit>,
    /// A response with another ID than 0 is a fault (`error`).
    pub m_axi_bid: Signal<In, Bit>,
    pub m_axi_bresp: Signal<In, Bits<2>>,
    pub m_axi_bvalid: Signal<In, Bit>,
    pub m_axi_bready: Signal<Out, Bit>,
    /// From the clock after `start` until the last write response.
    pub busy: Signal<Out, Bit>,
    /// A write response was not OKAY, or not for ID 0, since `start`
    /// (sticky).
    pub error: Signal<Out, Bit>,
    /// Beats taken since `start`.
    pub written: Signal<Out, Bits<BEAT_BITS>>,
    queue: BeatFifo<DW, A>,
    /// The longest burst at the AW side's address.
    aw_rule: BurstRule,
    /// The length of each burst issued on AW and not yet begun on W.
    lengths: BeatFifo<LENGTH_BITS, LENGTH_QUEUE_ADDRESS_BITS>,
    outstanding: Constant<Bits<OUTSTANDING_BITS>>,
    capacity: Constant<Bits<BEAT_BITS>>,
    size: Constant<Bits<3>>,
    strobes: Constant<Bits<S>>,
    running: DFF<Bit>,
    failed: DFF<Bit>,
    ended: DFF<Bit>,
    /// Beats taken, beats given to an AW burst, beats sent on W.
    received: DFF<Bits<BEAT_BITS>>,
    issued: DFF<Bits<BEAT_BITS>>,
    sent: DFF<Bits<BEAT_BITS>>,
    aw_next: DFF<Bits<ADDRESS_BITS>>,
    /// Beats left in the W burst under way (0 between bursts).
    w_left: DFF<Bits<LENGTH_BITS>>,
    unanswered: DFF<Bits<OUTSTANDING_BITS>>,
    aw_valid: DFF<Bit>,
    aw_address: DFF<Bits<ADDRESS_BITS>>,
    aw_length: DFF<Bits<8>>,
    /// The longest burst at `aw_next`, a clock behind it, and whether it
    /// is up to date (not in the clock after a start or an issue).
    aw_full: DFF<Bits<BEAT_BITS>>,
    aw_full_ok: DFF<Bit>,
    taken: Signal<Local, Bit>,
    pending: Signal<Local, Bits<BEAT_BITS>>,
    issue: Signal<Local, Bit>,
    /// The length queue's count, not needed (it never holds more than the
    /// bursts in flight).
    unused_count: Signal<Local, Bit>,
    beat_out: Signal<Local, Bit>,
    answered: Signal<Local, Bit>,
}

impl<const DW: usize, const S: usize, const A: usize> crate::unit::Unit for BurstWriter<DW, S, A> {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self, units, queue, aw_rule, lengths, running, failed, ended, received, issued, sent,
            aw_next, w_left, unanswered, aw_valid, aw_address, aw_length, aw_full, aw_full_ok
        );
    }
    fn settings(&self) -> Vec<(&'static str, String)> {
        vec![
            ("max_burst", self.aw_rule.max_burst().to_string()),
            ("outstanding", self.outstanding.val().index().to_string()),
        ]
    }
}

impl<const DW: usize, const S: usize, const A: usize> BurstWriter<DW, S, A> {
    /// A writer issuing bursts of at most `max_burst` beats, at most
    /// `outstanding` awaiting their response.
    pub fn new(max_burst: usize, outstanding: usize) -> Self {
        assert_eq!(S * 8, DW, "BurstWriter: S is the bytes of a beat");
        let config = super::TransferConfig {
            data_bits: DW,
            max_burst,
            outstanding,
            queue_beats: BeatFifo::<DW, A>::CAPACITY,
        };
        if let Err(e) = config.check() {
            panic!("BurstWriter: {e}");
        }
        let beat_bytes = S as u64;
        BurstWriter {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            base: Default::default(),
            in_valid: Default::default(),
            in_ready: Default::default(),
            in_data: Default::default(),
            in_last: Default::default(),
            flush: Default::default(),
            m_axi_awid: Default::default(),
            m_axi_awaddr: Default::default(),
            m_axi_awlen: Default::default(),
            m_axi_awsize: Default::default(),
            m_axi_awburst: Default::default(),
            m_axi_awcache: Default::default(),
            m_axi_awprot: Default::default(),
            m_axi_awvalid: Default::default(),
            m_axi_awready: Default::default(),
            m_axi_wdata: Default::default(),
            m_axi_wstrb: Default::default(),
            m_axi_wlast: Default::default(),
            m_axi_wvalid: Default::default(),
            m_axi_wready: Default::default(),
            m_axi_bid: Default::default(),
            m_axi_bresp: Default::default(),
            m_axi_bvalid: Default::default(),
            m_axi_bready: Default::default(),
            busy: Default::default(),
            error: Default::default(),
            written: Default::default(),
            queue: Default::default(),
            aw_rule: BurstRule::new(beat_bytes, max_burst),
            lengths: BeatFifo::in_distributed_ram(),
            outstanding: Constant::new((outstanding as u64).into()),
            capacity: Constant::new((BeatFifo::<DW, A>::CAPACITY as u64).into()),
            size: Constant::new((beat_bytes.trailing_zeros() as u64).into()),
            strobes: Constant::new(!Bits::<S>::default()),
            running: Default::default(),
            failed: Default::default(),
            ended: Default::default(),
            received: Default::default(),
            issued: Default::default(),
            sent: Default::default(),
            aw_next: Default::default(),
            w_left: Default::default(),
            unanswered: Default::default(),
            aw_valid: Default::default(),
            aw_address: Default::default(),
            aw_length: Default::default(),
            aw_full: Default::default(),
            aw_full_ok: Default::default(),
            taken: Default::default(),
            pending: Default::default(),
            issue: Default::default(),
            unused_count: Default::default(),
            beat_out: Default::default(),
            answered: Default::default(),
        }
    }
}

impl<const DW: usize, const S: usize, const A: usize> Logic for BurstWriter<DW, S, A> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, running, failed, ended, received, issued, sent, aw_next, w_left,
            unanswered, aw_valid, aw_address, aw_length, aw_full, aw_full_ok
        );
        clock!(self, clock, queue, lengths);
        self.queue.reset.next = self.reset.val();
        self.busy.next = self.running.q.val();
        self.error.next = self.failed.q.val();
        self.written.next = self.received.q.val();
        // Beats in: while the stream runs and the queue has room.
        self.in_ready.next = self.running.q.val()
            & !self.ended.q.val()
            & (bit_cast::<BEAT_BITS, 16>(self.queue.count.val()) < self.capacity.val());
        self.taken.next = self.in_valid.val() & self.in_ready.val();
        self.queue.push.next = self.taken.val();
        self.queue.push_data.next = self.in_data.val();
        if self.taken.val() {
            self.received.d.next = self.received.q.val() + 1;
        }
        if (self.taken.val() & self.in_last.val()) | (self.running.q.val() & self.flush.val()) {
            self.ended.d.next = true;
        }
        // AW: a full burst once the queue holds it, the rest at the end.
        self.m_axi_awid.next = false;
        self.m_axi_awaddr.next = self.aw_address.q.val();
        self.m_axi_awlen.next = self.aw_length.q.val();
        self.m_axi_awsize.next = self.size.val();
        self.m_axi_awburst.next = 1.into();
        self.m_axi_awcache.next = 3.into();
        self.m_axi_awprot.next = 0.into();
        self.m_axi_awvalid.next = self.aw_valid.q.val();
        if self.aw_valid.q.val() & self.m_axi_awready.val() {
            self.aw_valid.d.next = false;
        }
        self.pending.next = self.received.q.val() - self.issued.q.val();
        self.aw_rule.address.next = bit_cast::<RULE_BITS, ADDRESS_BITS>(self.aw_next.q.val());
        self.aw_rule.left.next = 0xFFFF_FFFF_u64.into();
        self.aw_full.d.next = bit_cast::<BEAT_BITS, RULE_BITS>(self.aw_rule.beats.val());
        self.aw_full_ok.d.next = true;
        self.issue.next = self.running.q.val()
            & !self.aw_valid.q.val()
            & self.aw_full_ok.q.val()
            & (self.unanswered.q.val() < self.outstanding.val())
            & ((self.pending.val() >= self.aw_full.q.val())
                | (self.ended.q.val() & (self.pending.val() != 0)));
        self.lengths.push_data.next = 0.into();
        if self.issue.val() {
            self.aw_full_ok.d.next = false;
            self.aw_valid.d.next = true;
            self.aw_address.d.next = self.aw_next.q.val();
            // A full burst, or what is left at the end.
            if self.pending.val() >= self.aw_full.q.val() {
                self.aw_length.d.next = bit_cast::<8, BEAT_BITS>(self.aw_full.q.val() - 1);
                self.lengths.push_data.next =
                    bit_cast::<LENGTH_BITS, BEAT_BITS>(self.aw_full.q.val());
                self.aw_next.d.next =
                    self.aw_next.q.val() + (self.aw_full.q.val() << self.size.val());
                self.issued.d.next = self.issued.q.val() + self.aw_full.q.val();
            } else {
                self.aw_length.d.next = bit_cast::<8, BEAT_BITS>(self.pending.val() - 1);
                self.lengths.push_data.next =
                    bit_cast::<LENGTH_BITS, BEAT_BITS>(self.pending.val());
                self.aw_next.d.next =
                    self.aw_next.q.val() + (self.pending.val() << self.size.val());
                self.issued.d.next = self.issued.q.val() + self.pending.val();
            }
        }
        // W: the beats of issued bursts; a burst's length from the queue
        // of lengths as it begins.
        self.m_axi_wdata.next = self.queue.out_data.val();
        self.m_axi_wstrb.next = self.strobes.val();
        self.lengths.reset.next = self.reset.val();
        self.unused_count.next = self.lengths.count.val().any();
        self.lengths.push.next = self.issue.val();
        self.m_axi_wvalid.next = self.queue.out_valid.val()
            & ((self.w_left.q.val() != 0) | self.lengths.out_valid.val());
        self.m_axi_wlast.next = self.w_left.q.val() == 1;
        if self.w_left.q.val() == 0 {
            self.m_axi_wlast.next = self.lengths.out_data.val() == 1;
        }
        self.beat_out.next = self.m_axi_wvalid.val() & self.m_axi_wready.val();
        self.queue.pop.next = self.beat_out.val();
        self.lengths.pop.next = self.beat_out.val() & (self.w_left.q.val() == 0);
        if self.beat_out.val() {
            self.sent.d.next = self.sent.q.val() + 1;
            if self.w_left.q.val() == 0 {
                self.w_left.d.next = self.lengths.out_data.val() - 1;
            } else {
                self.w_left.d.next = self.w_left.q.val() - 1;
            }
        }
        // B: every response taken at once.
        self.m_axi_bready.next = true;
        self.answered.next = self.m_axi_bvalid.val();
        if self.m_axi_bvalid.val() & ((self.m_axi_bresp.val() != 0) | self.m_axi_bid.val()) {
            self.failed.d.next = true;
        }
        if self.issue.val() & !self.answered.val() {
            self.unanswered.d.next = self.unanswered.q.val() + 1;
        } else if !self.issue.val() & self.answered.val() {
            self.unanswered.d.next = self.unanswered.q.val() - 1;
        }
        if self.running.q.val()
            & self.ended.q.val()
            & (self.sent.q.val() == self.received.q.val())
            & (self.unanswered.q.val() == 0)
            & !self.aw_valid.q.val()
        {
            self.running.d.next = false;
        }
        if self.start.val() & !self.running.q.val() {
            self.aw_full_ok.d.next = false;
            self.running.d.next = true;
            self.failed.d.next = false;
            self.ended.d.next = self.flush.val();
            self.received.d.next = 0.into();
            self.issued.d.next = 0.into();
            self.sent.d.next = 0.into();
            self.aw_next.d.next = self.base.val();
            self.w_left.d.next = 0.into();
        }
        if self.reset.val() {
            self.running.d.next = false;
            self.failed.d.next = false;
            self.ended.d.next = false;
            self.unanswered.d.next = 0.into();
            self.aw_valid.d.next = false;
            self.w_left.d.next = 0.into();
        }
    }
}
