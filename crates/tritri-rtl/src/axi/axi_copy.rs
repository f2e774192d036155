//! A region copied to another through one AXI4 manager port: a
//! [`BurstReader`] streams the source's beats into a [`BurstWriter`] that
//! writes them from the destination. It is the smallest unit with every
//! channel of the port, reads and writes in flight together, so the port,
//! the memory models and the clock-exact model
//! ([`super::transfer_machine`]) are proven on it before the accelerator
//! uses them.
//!
//! Clocks are counted from `start` (clock 0) to the first clock with
//! `done` high.

use super::beat_fifo::BeatFifo;
use super::burst_reader::{BurstReader, BEAT_BITS};
use super::burst_writer::BurstWriter;
use super::ADDRESS_BITS;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Address bits of each unit's queue: 512 beats, a DP16KD pair at 64 bits.
pub const COPY_QUEUE_ADDRESS_BITS: usize = 9;

#[derive(LogicBlock)]
pub struct AxiCopy<const DW: usize, const S: usize, const A: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high.
    pub reset: Signal<In, Bit>,
    /// One clock high while not busy: copy `beats` beats from `source` to
    /// `destination`.
    pub start: Signal<In, Bit>,
    pub source: Signal<In, Bits<ADDRESS_BITS>>,
    pub destination: Signal<In, Bits<ADDRESS_BITS>>,
    pub beats: Signal<In, Bits<BEAT_BITS>>,
    pub busy: Signal<Out, Bit>,
    /// High from the end of a copy until the next `start`.
    pub done: Signal<Out, Bit>,
    /// A read or write response was not OKAY in the last copy.
    pub error: Signal<Out, Bit>,
    pub m_axi_arid: Signal<Out, Bit>,
    pub m_axi_araddr: Signal<Out, Bits<ADDRESS_BITS>>,
    pub m_axi_arlen: Signal<Out, Bits<8>>,
    pub m_axi_arsize: Signal<Out, Bits<3>>,
    pub m_axi_arburst: Signal<Out, Bits<2>>,
    pub m_axi_arcache: Signal<Out, Bits<4>>,
    pub m_axi_arprot: Signal<Out, Bits<3>>,
    pub m_axi_arvalid: Signal<Out, Bit>,
    pub m_axi_arready: Signal<In, Bit>,
    pub m_axi_rid: Signal<In, Bit>,
    pub m_axi_rdata: Signal<In, Bits<DW>>,
    pub m_axi_rresp: Signal<In, Bits<2>>,
    pub m_axi_rlast: Signal<In, Bit>,
    pub m_axi_rvalid: Signal<In, Bit>,
    pub m_axi_rready: Signal<Out, Bit>,
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
    pub m_axi_bid: Signal<In, Bit>,
    pub m_axi_bresp: Signal<In, Bits<2>>,
    pub m_axi_bvalid: Signal<In, Bit>,
    pub m_axi_bready: Signal<Out, Bit>,
    reader: BurstReader<DW, A>,
    writer: BurstWriter<DW, S, A>,
    active: DFF<Bit>,
    finished: DFF<Bit>,
    /// The writer's count of beats, not needed (the copy knows its beats).
    unused_written: Signal<Local, Bit>,
}

impl<const DW: usize, const S: usize, const A: usize> crate::unit::Unit for AxiCopy<DW, S, A> {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, reader, writer, active, finished);
    }
}

impl<const DW: usize, const S: usize, const A: usize> AxiCopy<DW, S, A> {
    /// Both units with bursts of at most `max_burst` beats and at most
    /// `outstanding` bursts in flight each.
    pub fn new(max_burst: usize, outstanding: usize) -> Self {
        AxiCopy {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            source: Default::default(),
            destination: Default::default(),
            beats: Default::default(),
            busy: Default::default(),
            done: Default::default(),
            error: Default::default(),
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
            reader: BurstReader::new(max_burst, outstanding),
            writer: BurstWriter::new(max_burst, outstanding),
            active: Default::default(),
            finished: Default::default(),
            unused_written: Default::default(),
        }
    }

    /// Beats each unit's queue holds.
    pub const QUEUE_BEATS: usize = BeatFifo::<DW, A>::CAPACITY;
}

impl<const DW: usize, const S: usize, const A: usize> Logic for AxiCopy<DW, S, A> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, active, finished);
        clock!(self, clock, reader, writer);
        self.reader.reset.next = self.reset.val();
        self.writer.reset.next = self.reset.val();
        self.reader.start.next = self.start.val() & !self.active.q.val();
        self.reader.base.next = self.source.val();
        self.reader.beats.next = self.beats.val();
        self.writer.start.next = self.start.val() & !self.active.q.val();
        self.writer.base.next = self.destination.val();
        // A copy of nothing ends the writer's stream at once.
        self.writer.flush.next = self.start.val() & !self.active.q.val() & (self.beats.val() == 0);
        self.writer.in_valid.next = self.reader.out_valid.val();
        self.writer.in_data.next = self.reader.out_data.val();
        self.writer.in_last.next = self.reader.out_last.val();
        self.reader.out_ready.next = self.writer.in_ready.val();
        // The port: AR and R are the reader's, AW, W and B the writer's.
        self.m_axi_arid.next = self.reader.m_axi_arid.val();
        self.m_axi_araddr.next = self.reader.m_axi_araddr.val();
        self.m_axi_arlen.next = self.reader.m_axi_arlen.val();
        self.m_axi_arsize.next = self.reader.m_axi_arsize.val();
        self.m_axi_arburst.next = self.reader.m_axi_arburst.val();
        self.m_axi_arcache.next = self.reader.m_axi_arcache.val();
        self.m_axi_arprot.next = self.reader.m_axi_arprot.val();
        self.m_axi_arvalid.next = self.reader.m_axi_arvalid.val();
        self.reader.m_axi_arready.next = self.m_axi_arready.val();
        self.reader.m_axi_rid.next = self.m_axi_rid.val();
        self.reader.m_axi_rdata.next = self.m_axi_rdata.val();
        self.reader.m_axi_rresp.next = self.m_axi_rresp.val();
        self.reader.m_axi_rlast.next = self.m_axi_rlast.val();
        self.reader.m_axi_rvalid.next = self.m_axi_rvalid.val();
        self.m_axi_rready.next = self.reader.m_axi_rready.val();
        self.m_axi_awid.next = self.writer.m_axi_awid.val();
        self.m_axi_awaddr.next = self.writer.m_axi_awaddr.val();
        self.m_axi_awlen.next = self.writer.m_axi_awlen.val();
        self.m_axi_awsize.next = self.writer.m_axi_awsize.val();
        self.m_axi_awburst.next = self.writer.m_axi_awburst.val();
        self.m_axi_awcache.next = self.writer.m_axi_awcache.val();
        self.m_axi_awprot.next = self.writer.m_axi_awprot.val();
        self.m_axi_awvalid.next = self.writer.m_axi_awvalid.val();
        self.writer.m_axi_awready.next = self.m_axi_awready.val();
        self.m_axi_wdata.next = self.writer.m_axi_wdata.val();
        self.m_axi_wstrb.next = self.writer.m_axi_wstrb.val();
        self.m_axi_wlast.next = self.writer.m_axi_wlast.val();
        self.m_axi_wvalid.next = self.writer.m_axi_wvalid.val();
        self.writer.m_axi_wready.next = self.m_axi_wready.val();
        self.writer.m_axi_bid.next = self.m_axi_bid.val();
        self.writer.m_axi_bresp.next = self.m_axi_bresp.val();
        self.writer.m_axi_bvalid.next = self.m_axi_bvalid.val();
        self.m_axi_bready.next = self.writer.m_axi_bready.val();
        self.unused_written.next = self.writer.written.val().any();
        self.busy.next = self.active.q.val();
        self.done.next = self.finished.q.val();
        self.error.next = self.reader.error.val() | self.writer.error.val();
        // Both units are busy from the clock after start.
        if self.active.q.val() & !self.reader.busy.val() & !self.writer.busy.val() {
            self.active.d.next = false;
            self.finished.d.next = true;
        }
        if self.start.val() & !self.active.q.val() {
            self.active.d.next = true;
            self.finished.d.next = false;
        }
        if self.reset.val() {
            self.active.d.next = false;
            self.finished.d.next = false;
        }
    }
}
