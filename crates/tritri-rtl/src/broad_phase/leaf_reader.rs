//! A leaf's lists read back from external memory for the narrow phase:
//! the leaf the DRAM binning controller ([`super::dram_binning_unit`])
//! decides is a cell and its two lists' places; this unit reads A's list,
//! then B's, over AXI4 and streams the leaf as the binning unit's leaf
//! stream: a header (the cell and both counts), A's entries, B's entries,
//! each entry with its triangle's index and vertices. It is the stream the
//! leaf batcher ([`super::leaf_batcher`]) takes.
//!
//! ```text
//! AR/R ─► reader ─► gearbox ─► entries (6) ─► header, A's entries, B's entries ─► out (valid/ready)
//!                  (beats →
//!                   entries)
//! ```
//!
//! * The reader ([`crate::axi::burst_reader`]) starts on A's list in the
//!   clock of `start`, `count · 256 / DW` beats, and on B's once A's has
//!   left it. The gearbox is the list pass's ([`super::list_pass`]): an
//!   entry on the clock of its last beat, when the queue of entries has
//!   room; the queue's head is the output, so `out_ready` reaches no
//!   further than the queue's pop.
//! * The header goes first, in the clock after `start` at the earliest;
//!   the entries wait behind it. Its cell and counts stay on `out_x` ..
//!   `out_count_b` until the next `start`.
//! * `reading` is high from the clock after `start` until B's last beat
//!   has left the reader: until then the read channel is the unit's, and
//!   the lists must not be written (the controller's next pass waits on
//!   it). `busy` stays high until the last entry has gone.
//!
//! The clock-exact model is [`super::leaf_reader_machine`].

use super::list_entry::{ENTRY_BITS, INDEX_OFFSET};
use super::list_pass::{ENTRY_COUNT_BITS, READ_QUEUE_ADDRESS_BITS};
use crate::axi::beat_fifo::{BeatFifo, COUNT_BITS};
use crate::axi::burst_reader::BurstReader;
use crate::axi::ADDRESS_BITS;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Address bits of the queue of entries: 6 entries, enough for one a
/// clock (the queue's count is a register, and an entry takes two clocks
/// from push to head).
pub const LEAF_QUEUE_ADDRESS_BITS: usize = 2;
/// An entry and its object.
const TAGGED_ENTRY_BITS: usize = ENTRY_BITS + 1;
/// Bits of the entries a leaf has left to send (two counts).
const LEFT_BITS: usize = ENTRY_COUNT_BITS + 1;
// `update` slices with literals (hdl_gen reads a constant's name as a
// signal): the object at bit 256, the index at bit 224.
const _: () = assert!(ENTRY_BITS == 256 && INDEX_OFFSET == 224);

#[derive(LogicBlock)]
pub struct LeafReader<const G: usize, const T: usize, const DW: usize, const S: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high.
    pub reset: Signal<In, Bit>,
    /// One clock high while not busy: read the leaf on the inputs (read in
    /// that clock only).
    pub start: Signal<In, Bit>,
    pub corner_x: Signal<In, Bits<G>>,
    pub corner_y: Signal<In, Bits<G>>,
    pub corner_z: Signal<In, Bits<G>>,
    pub level: Signal<In, Bits<6>>,
    /// Object `k`'s list: its first entry's address and its entries.
    pub list_base: [Signal<In, Bits<ADDRESS_BITS>>; 2],
    pub list_count: [Signal<In, Bits<ENTRY_COUNT_BITS>>; 2],
    /// From the clock after `start` until the last entry has gone.
    pub busy: Signal<Out, Bit>,
    /// From the clock after `start` until the last beat has left the
    /// reader: the read channel is in use and the lists must stay.
    pub reading: Signal<Out, Bit>,
    /// A read response was not OKAY, or not for ID 0, since `start`.
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
    /// The write channels, idle: the port is a whole AXI4 manager port so
    /// that it meets the same memories and interconnects as the others.
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
    /// The leaf stream: the header, then the entries.
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_header: Signal<Out, Bit>,
    /// An entry's object (0: A), its triangle's index and vertices.
    pub out_object: Signal<Out, Bit>,
    pub out_index: Signal<Out, Bits<32>>,
    pub out_vertices: Signal<Out, Bits<T>>,
    /// The leaf's cell and counts, for the header.
    pub out_x: Signal<Out, Bits<G>>,
    pub out_y: Signal<Out, Bits<G>>,
    pub out_z: Signal<Out, Bits<G>>,
    pub out_level: Signal<Out, Bits<6>>,
    pub out_count_a: Signal<Out, Bits<ENTRY_COUNT_BITS>>,
    pub out_count_b: Signal<Out, Bits<ENTRY_COUNT_BITS>>,
    reader: BurstReader<DW, READ_QUEUE_ADDRESS_BITS>,
    entries: BeatFifo<TAGGED_ENTRY_BITS, LEAF_QUEUE_ADDRESS_BITS>,
    // Constants of the build (as in the list pass's gearbox).
    log_beats_per_entry: Constant<Bits<2>>,
    last_beat: Constant<Bits<3>>,
    beat_step: Constant<Bits<8>>,
    gear_keep: Constant<Bits<ENTRY_BITS>>,
    top_offset: Constant<Bits<16>>,
    entry_capacity: Constant<Bits<COUNT_BITS>>,
    object_bit: Constant<Bits<TAGGED_ENTRY_BITS>>,
    /// The entry's bits between the vertices and the index (zero in the
    /// format), for the lint's fold.
    padding_bits: Constant<Bits<TAGGED_ENTRY_BITS>>,
    // The leaf.
    running: DFF<Bit>,
    header_due: DFF<Bit>,
    /// 1: A's read under way (it starts in the clock of `start`), 2: B's,
    /// 3: both done.
    read_stage: DFF<Bits<2>>,
    corner_x_q: DFF<Bits<G>>,
    corner_y_q: DFF<Bits<G>>,
    corner_z_q: DFF<Bits<G>>,
    level_q: DFF<Bits<6>>,
    count_a: DFF<Bits<ENTRY_COUNT_BITS>>,
    base_b: DFF<Bits<ADDRESS_BITS>>,
    count_b: DFF<Bits<ENTRY_COUNT_BITS>>,
    /// Entries not yet sent.
    left: DFF<Bits<LEFT_BITS>>,
    // The gearbox.
    gear: DFF<Bits<ENTRY_BITS>>,
    gear_count: DFF<Bits<3>>,
    entries_in: DFF<Bits<ENTRY_COUNT_BITS>>,
    room: Signal<Local, Bit>,
    accepted: Signal<Local, Bit>,
    push: Signal<Local, Bit>,
    beat_in: Signal<Local, Bits<ENTRY_BITS>>,
    assembled: Signal<Local, Bits<ENTRY_BITS>>,
    tagged: Signal<Local, Bits<TAGGED_ENTRY_BITS>>,
    send_entry: Signal<Local, Bit>,
    /// The reader's `out_last` (the unit counts entries itself), the idle
    /// write channels' inputs and the entries' padding, folded into one
    /// bit.
    unused_outputs: Signal<Local, Bit>,
}

impl<const G: usize, const T: usize, const DW: usize, const S: usize> crate::unit::Unit
    for LeafReader<G, T, DW, S>
{
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self, units, reader, entries, running, header_due, read_stage, corner_x_q, corner_y_q,
            corner_z_q, level_q, count_a, base_b, count_b, left, gear, gear_count, entries_in
        );
    }
}

impl<const G: usize, const T: usize, const DW: usize, const S: usize> LeafReader<G, T, DW, S> {
    /// Beats of an entry.
    pub const BEATS_PER_ENTRY: usize = ENTRY_BITS / DW;

    /// A reader whose bursts are at most `max_read_burst` beats, at most
    /// `outstanding` in flight.
    pub fn new(max_read_burst: usize, outstanding: usize) -> Self {
        assert!(
            super::list_pass_machine::PASS_DATA_BITS.contains(&DW) && S * 8 == DW,
            "LeafReader: a 64-, 128- or 256-bit port, not {DW}"
        );
        assert!(T == 9 * G && T <= INDEX_OFFSET, "LeafReader: T = 9 G");
        let per_entry = Self::BEATS_PER_ENTRY;
        LeafReader {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            corner_x: Default::default(),
            corner_y: Default::default(),
            corner_z: Default::default(),
            level: Default::default(),
            list_base: Default::default(),
            list_count: Default::default(),
            busy: Default::default(),
            reading: Default::default(),
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
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_header: Default::default(),
            out_object: Default::default(),
            out_index: Default::default(),
            out_vertices: Default::default(),
            out_x: Default::default(),
            out_y: Default::default(),
            out_z: Default::default(),
            out_level: Default::default(),
            out_count_a: Default::default(),
            out_count_b: Default::default(),
            reader: BurstReader::new(max_read_burst, outstanding),
            entries: BeatFifo::in_distributed_ram(),
            log_beats_per_entry: Constant::new((per_entry.trailing_zeros() as u64).into()),
            last_beat: Constant::new((per_entry as u64 - 1).into()),
            beat_step: Constant::new(((DW % ENTRY_BITS) as u64).into()),
            gear_keep: Constant::new(if DW == ENTRY_BITS {
                Bits::default()
            } else {
                !Bits::<ENTRY_BITS>::default()
            }),
            top_offset: Constant::new(((ENTRY_BITS - DW) as u64).into()),
            entry_capacity: Constant::new(
                (BeatFifo::<TAGGED_ENTRY_BITS, LEAF_QUEUE_ADDRESS_BITS>::CAPACITY as u64).into(),
            ),
            object_bit: Constant::new(
                Bits::<TAGGED_ENTRY_BITS>::default().replace_bit(ENTRY_BITS, true),
            ),
            padding_bits: Constant::new(
                (T..INDEX_OFFSET).fold(Bits::<TAGGED_ENTRY_BITS>::default(), |b, i| {
                    b.replace_bit(i, true)
                }),
            ),
            running: Default::default(),
            header_due: Default::default(),
            read_stage: Default::default(),
            corner_x_q: Default::default(),
            corner_y_q: Default::default(),
            corner_z_q: Default::default(),
            level_q: Default::default(),
            count_a: Default::default(),
            base_b: Default::default(),
            count_b: Default::default(),
            left: Default::default(),
            gear: Default::default(),
            gear_count: Default::default(),
            entries_in: Default::default(),
            room: Default::default(),
            accepted: Default::default(),
            push: Default::default(),
            beat_in: Default::default(),
            assembled: Default::default(),
            tagged: Default::default(),
            send_entry: Default::default(),
            unused_outputs: Default::default(),
        }
    }
}

impl<const G: usize, const T: usize, const DW: usize, const S: usize> Logic
    for LeafReader<G, T, DW, S>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, running, header_due, read_stage, corner_x_q, corner_y_q, corner_z_q,
            level_q, count_a, base_b, count_b, left, gear, gear_count, entries_in
        );
        clock!(self, clock, reader, entries);
        self.reader.reset.next = self.reset.val();
        self.entries.reset.next = self.reset.val();
        self.busy.next = self.running.q.val();
        self.reading.next = self.running.q.val() & (self.read_stage.q.val() != 3);
        self.error.next = self.reader.error.val();
        self.unused_outputs.next = self.reader.out_last.val()
            | self.m_axi_awready.val()
            | self.m_axi_wready.val()
            | self.m_axi_bid.val()
            | self.m_axi_bresp.val().any()
            | self.m_axi_bvalid.val()
            | (self.entries.out_data.val() & self.padding_bits.val()).any();
        self.m_axi_awid.next = false;
        self.m_axi_awaddr.next = 0.into();
        self.m_axi_awlen.next = 0.into();
        self.m_axi_awsize.next = 0.into();
        self.m_axi_awburst.next = 0.into();
        self.m_axi_awcache.next = 0.into();
        self.m_axi_awprot.next = 0.into();
        self.m_axi_awvalid.next = false;
        self.m_axi_wdata.next = 0.into();
        self.m_axi_wstrb.next = 0.into();
        self.m_axi_wlast.next = false;
        self.m_axi_wvalid.next = false;
        self.m_axi_bready.next = true;

        // The reads: A's list, then B's.
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
        self.reader.start.next = false;
        self.reader.base.next = self.list_base[0].val();
        self.reader.beats.next = self.list_count[0].val() << self.log_beats_per_entry.val();
        if self.running.q.val() & (self.read_stage.q.val() == 1) & !self.reader.busy.val() {
            self.reader.start.next = true;
            self.reader.base.next = self.base_b.q.val();
            self.reader.beats.next = self.count_b.q.val() << self.log_beats_per_entry.val();
            self.read_stage.d.next = 2.into();
        }
        if self.running.q.val() & (self.read_stage.q.val() == 2) & !self.reader.busy.val() {
            self.read_stage.d.next = 3.into();
        }

        // The gearbox: beats shifted in from the top, an entry on its last.
        self.room.next = self.entries.count.val() < self.entry_capacity.val();
        self.reader.out_ready.next =
            (self.gear_count.q.val() != self.last_beat.val()) | self.room.val();
        self.accepted.next = self.reader.out_valid.val() & self.reader.out_ready.val();
        self.push.next = self.accepted.val() & (self.gear_count.q.val() == self.last_beat.val());
        self.beat_in.next = bit_cast::<ENTRY_BITS, DW>(self.reader.out_data.val());
        self.assembled.next = ((self.gear.q.val() >> self.beat_step.val()) & self.gear_keep.val())
            | (self.beat_in.val() << self.top_offset.val());
        if self.accepted.val() {
            self.gear.d.next = self.assembled.val();
            self.gear_count.d.next = self.gear_count.q.val() + 1;
        }
        if self.push.val() {
            self.gear_count.d.next = 0.into();
            self.entries_in.d.next = self.entries_in.q.val() + 1;
        }
        self.tagged.next = bit_cast::<TAGGED_ENTRY_BITS, ENTRY_BITS>(self.assembled.val());
        if self.entries_in.q.val() >= self.count_a.q.val() {
            self.tagged.next = bit_cast::<TAGGED_ENTRY_BITS, ENTRY_BITS>(self.assembled.val())
                | self.object_bit.val();
        }
        self.entries.push.next = self.push.val();
        self.entries.push_data.next = self.tagged.val();

        // The stream: the header, then the queue's head.
        self.out_header.next = self.header_due.q.val();
        self.out_valid.next = self.header_due.q.val() | self.entries.out_valid.val();
        self.out_object.next = self.entries.out_data.val().get_bit(256);
        self.out_index.next = self.entries.out_data.val().get_bits::<32>(224);
        self.out_vertices.next = bit_cast::<T, TAGGED_ENTRY_BITS>(self.entries.out_data.val());
        self.out_x.next = self.corner_x_q.q.val();
        self.out_y.next = self.corner_y_q.q.val();
        self.out_z.next = self.corner_z_q.q.val();
        self.out_level.next = self.level_q.q.val();
        self.out_count_a.next = self.count_a.q.val();
        self.out_count_b.next = self.count_b.q.val();
        self.send_entry.next =
            !self.header_due.q.val() & self.entries.out_valid.val() & self.out_ready.val();
        self.entries.pop.next = self.send_entry.val();
        if self.header_due.q.val() & self.out_ready.val() {
            self.header_due.d.next = false;
            if self.left.q.val() == 0 {
                self.running.d.next = false;
            }
        }
        if self.send_entry.val() {
            self.left.d.next = self.left.q.val() - 1;
            if self.left.q.val() == 1 {
                self.running.d.next = false;
            }
        }

        if self.start.val() & !self.running.q.val() {
            self.reader.start.next = true;
            self.running.d.next = true;
            self.header_due.d.next = true;
            self.corner_x_q.d.next = self.corner_x.val();
            self.corner_y_q.d.next = self.corner_y.val();
            self.corner_z_q.d.next = self.corner_z.val();
            self.level_q.d.next = self.level.val();
            self.count_a.d.next = self.list_count[0].val();
            self.base_b.d.next = self.list_base[1].val();
            self.count_b.d.next = self.list_count[1].val();
            self.left.d.next = bit_cast::<LEFT_BITS, ENTRY_COUNT_BITS>(self.list_count[0].val())
                + bit_cast::<LEFT_BITS, ENTRY_COUNT_BITS>(self.list_count[1].val());
            self.read_stage.d.next = 1.into();
            self.gear_count.d.next = 0.into();
            self.entries_in.d.next = 0.into();
        }
        if self.reset.val() {
            self.running.d.next = false;
            self.header_due.d.next = false;
            self.read_stage.d.next = 0.into();
        }
    }
}
