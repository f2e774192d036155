//! A cell's pass with its lists in external memory: the cell's A list and
//! B list are read front to back over AXI4, each entry is classified
//! against the cell's eight children, and the entry is appended to the
//! list of every child it meets, in external memory too. Entries carry
//! their vertices ([`super::list_entry`]), so the pass is long bursts only:
//! one read stream and sixteen write streams (two objects, eight children).
//!
//! ```text
//! AR/R ─► reader ─► gearbox ─┬─► lane (setup, classifier) ─► masks ─┐
//!                  (beats →   └─► entries ──────────────────────────┴─► distributor
//!                   entries)                                              │ a beat a clock
//!                                              child buffers (block RAM) ◄┘
//!                                  two slots of a burst per child; a full slot is a command
//! AW ◄─ commands (address, beats, slot) ◄──────────────────────────────────┘
//! W  ◄─ feeder: the commanded slot's beats, read from the buffers, in AW order
//! B  ─► every response awaited
//! ```
//!
//! * The reader ([`crate::axi::burst_reader`]) reads A's list, then B's:
//!   `count · 256 / DW` beats each. The gearbox shifts `256 / DW` beats
//!   into an entry, last beat on top, and hands it on the clock its last
//!   beat comes, to the lane and, beside it, to a queue of entries; an
//!   entry goes only when that queue has room, and the lane's entries count
//!   in the queue, so the queue of masks behind the lane never overflows.
//! * The distributor takes an entry and its mask and writes the entry's
//!   beats into the buffer of each child the mask names, lowest octant
//!   first, a beat a clock. Each child has two slots of [`WRITE_BURST_BEATS`]
//!   beats (a burst); a slot that fills becomes a write command, and the
//!   child goes on in its other slot, waiting only when that one has not
//!   yet been read out. The next entry is taken in the clock the last
//!   beat of the last child is written.
//! * A B entry goes only to the children an A entry went to: a child
//!   without A is dropped by the split rule, and its B list would never be
//!   read. The controller gives the shorter of a cell's lists as A, so the
//!   longer is the one cut down.
//! * Child `o` of object `k` is the list at `child_base[k] + o ·
//!   child_stride[k]`; a slot goes to its list's next burst. The unit needs
//!   `child_base` and `child_stride` aligned to a burst ([`WRITE_BURST_BEATS`]
//!   beats) and a burst to divide 4 KB, so no burst crosses a 4 KB
//!   boundary, and `child_stride` at least the cell's list of that object,
//!   so no list runs into the next (the controller that allocates the
//!   lists sees to both).
//! * After the last entry the sixteen children's partly filled slots are
//!   written as shorter bursts, one child a clock; `done` rises when every
//!   write response is in, with each child's entry count on `child_count`.
//!
//! The clock-exact model is [`super::list_pass_machine`].

use super::child_select::ChildSelect;
use super::classify_lane::{ClassifyLane, LANE_LATENCY};
use super::list_entry::ENTRY_BITS;
use crate::axi::beat_fifo::{BeatFifo, COUNT_BITS};
use crate::axi::burst_reader::{BurstReader, OUTSTANDING_BITS};
use crate::axi::ADDRESS_BITS;
use crate::system::dual_port_ram::SimpleDualPortRam;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Two objects, eight children each.
pub const CHILDREN: usize = 16;
/// Bits of a child's slot number (`2 · child + half`).
pub const SLOT_BITS: usize = 5;
/// Bits of an entry count.
pub const ENTRY_COUNT_BITS: usize = 32;
/// Address bits of the queues of entries and masks (34 entries: the lane's
/// latency and the queues' own, with room to spare at one entry a clock).
pub const ENTRY_QUEUE_ADDRESS_BITS: usize = 5;
/// Address bits of the reader's queue.
pub const READ_QUEUE_ADDRESS_BITS: usize = 9;
/// Beats of a child's slot: the longest write burst (a power of two; with
/// 64- to 256-bit beats, 128 to 512 bytes, so a burst aligned to its size
/// never crosses 4 KB).
pub const WRITE_BURST_BEATS: usize = 16;
/// Address bits of the children's buffer: 32 slots of a burst.
const BA: usize = SLOT_BITS + WRITE_BURST_BEATS.trailing_zeros() as usize;
/// Address bits of the W side's queue of beats.
const W_QUEUE_ADDRESS_BITS: usize = 4;
/// An entry and its object.
const TAGGED_ENTRY_BITS: usize = ENTRY_BITS + 1;
/// A command: address (32), beats (9), slot (5).
const COMMAND_BITS: usize = ADDRESS_BITS + 9 + SLOT_BITS;
/// A burst on the W side: beats (9), slot (5).
const BURST_BITS: usize = 9 + SLOT_BITS;
/// Clocks after `start` until every child's list address is set (the
/// eight addresses of an object are a chain of adds, one a clock).
pub const ADDRESS_SETUP_CLOCKS: usize = 7;
// No slot fills before its address is set: an entry's mask comes at least
// a lane's latency after the start.
const _: () = assert!(LANE_LATENCY > ADDRESS_SETUP_CLOCKS);
const _: () = assert!(COUNT_BITS == 16);
// `update` slices with literals (hdl_gen reads a constant's name as a
// signal): the tag at bit 256, a command's beats at bit 32.
const _: () = assert!(ENTRY_BITS == 256 && ADDRESS_BITS == 32);

#[derive(LogicBlock)]
pub struct ListPass<
    const G: usize,
    const V: usize,
    const N: usize,
    const T: usize,
    const DW: usize,
    const S: usize,
> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high.
    pub reset: Signal<In, Bit>,
    /// One clock high while not busy: a pass over the cell and lists on
    /// the inputs (read in that clock only).
    pub start: Signal<In, Bit>,
    pub corner_x: Signal<In, Bits<G>>,
    pub corner_y: Signal<In, Bits<G>>,
    pub corner_z: Signal<In, Bits<G>>,
    /// The cell's level, at least 1.
    pub level: Signal<In, Bits<6>>,
    /// Object `k`'s list: its first entry's address and its entries.
    pub list_base: [Signal<In, Bits<ADDRESS_BITS>>; 2],
    pub list_count: [Signal<In, Bits<ENTRY_COUNT_BITS>>; 2],
    /// Where object `k`'s child lists go: child `o` at `child_base[k] + o ·
    /// child_stride[k]`.
    pub child_base: [Signal<In, Bits<ADDRESS_BITS>>; 2],
    pub child_stride: [Signal<In, Bits<ADDRESS_BITS>>; 2],
    /// From the clock after `start` until `done`.
    pub busy: Signal<Out, Bit>,
    /// High from the end of a pass until the next `start`.
    pub done: Signal<Out, Bit>,
    /// A read or write response of the pass was not OKAY, or not for ID 0.
    pub error: Signal<Out, Bit>,
    /// Entries written to child `8k + o` (object `k`, octant `o`).
    pub child_count: [Signal<Out, Bits<ENTRY_COUNT_BITS>>; CHILDREN],
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
    reader: BurstReader<DW, READ_QUEUE_ADDRESS_BITS>,
    lane: ClassifyLane<G, V, N, T>,
    entries: BeatFifo<TAGGED_ENTRY_BITS, ENTRY_QUEUE_ADDRESS_BITS>,
    masks: BeatFifo<8, ENTRY_QUEUE_ADDRESS_BITS>,
    /// The child the distributor writes this clock.
    select: ChildSelect,
    /// The children's slots, slot `s` at `s · WRITE_BURST_BEATS`.
    buffer: SimpleDualPortRam<Bits<DW>, BA>,
    commands: BeatFifo<COMMAND_BITS, SLOT_BITS>,
    /// The bursts issued on AW, in order, for the W side.
    bursts: BeatFifo<BURST_BITS, SLOT_BITS>,
    w_data: BeatFifo<DW, W_QUEUE_ADDRESS_BITS>,
    w_last: BeatFifo<1, W_QUEUE_ADDRESS_BITS>,
    // Constants of the build.
    outstanding: Constant<Bits<OUTSTANDING_BITS>>,
    size: Constant<Bits<3>>,
    strobes: Constant<Bits<S>>,
    log_beats_per_entry: Constant<Bits<2>>,
    last_beat: Constant<Bits<3>>,
    /// A beat's bits, as a shift: 0 at DW = 256, where an entry is one
    /// beat and nothing is shifted (a shift by 256 would be out of the
    /// operand's range).
    beat_step: Constant<Bits<8>>,
    /// What the gearbox keeps of its earlier beats: nothing at DW = 256.
    gear_keep: Constant<Bits<ENTRY_BITS>>,
    top_offset: Constant<Bits<16>>,
    slot_full_beats: Constant<Bits<9>>,
    burst_bytes: Constant<Bits<ADDRESS_BITS>>,
    log_burst_beats: Constant<Bits<4>>,
    entry_capacity: Constant<Bits<COUNT_BITS>>,
    w_capacity: Constant<Bits<COUNT_BITS>>,
    object_bit: Constant<Bits<TAGGED_ENTRY_BITS>>,
    beats_shift: Constant<Bits<6>>,
    slot_shift: Constant<Bits<6>>,
    // The pass.
    running: DFF<Bit>,
    finished: DFF<Bit>,
    failed: DFF<Bit>,
    corner_x_q: DFF<Bits<G>>,
    corner_y_q: DFF<Bits<G>>,
    corner_z_q: DFF<Bits<G>>,
    level_q: DFF<Bits<6>>,
    count_a: DFF<Bits<ENTRY_COUNT_BITS>>,
    base_b: DFF<Bits<ADDRESS_BITS>>,
    count_b: DFF<Bits<ENTRY_COUNT_BITS>>,
    stride: [DFF<Bits<ADDRESS_BITS>>; 2],
    /// 1: A's read under way (it starts in the clock of `start`), 2: B's,
    /// 3: both done.
    read_stage: DFF<Bits<2>>,
    setup_left: DFF<Bits<3>>,
    // The gearbox.
    gear: DFF<Bits<ENTRY_BITS>>,
    gear_count: DFF<Bits<3>>,
    entries_in: DFF<Bits<ENTRY_COUNT_BITS>>,
    // The distributor.
    entry: DFF<Bits<ENTRY_BITS>>,
    object: DFF<Bit>,
    mask_left: DFF<Bits<8>>,
    /// The children an entry of object A has been written to in this pass.
    reached: DFF<Bits<8>>,
    beat: DFF<Bits<3>>,
    /// The entry's beats not yet written to this child, next at bit 0: a
    /// shift by a constant a beat, where indexing the entry by the beat
    /// would be a 256-bit barrel shifter.
    beat_data: DFF<Bits<ENTRY_BITS>>,
    flushing: DFF<Bit>,
    flushed: DFF<Bit>,
    flush_child: DFF<Bits<4>>,
    // Per child.
    fill: [DFF<Bits<9>>; CHILDREN],
    half: [DFF<Bit>; CHILDREN],
    pending_low: [DFF<Bit>; CHILDREN],
    pending_high: [DFF<Bit>; CHILDREN],
    count: [DFF<Bits<ENTRY_COUNT_BITS>>; CHILDREN],
    /// The address of the child's next burst.
    region: [DFF<Bits<ADDRESS_BITS>>; CHILDREN],
    // AW and B.
    aw_valid: DFF<Bit>,
    aw_address: DFF<Bits<ADDRESS_BITS>>,
    aw_length: DFF<Bits<8>>,
    unanswered: DFF<Bits<OUTSTANDING_BITS>>,
    // The feeder: the beats of the burst under way, from the buffer.
    feed_left: DFF<Bits<9>>,
    feed_slot: DFF<Bits<SLOT_BITS>>,
    feed_address: DFF<Bits<BA>>,
    read_valid: DFF<Bit>,
    read_last: DFF<Bit>,
    // Between the parts.
    accepted: Signal<Local, Bit>,
    room: Signal<Local, Bit>,
    push: Signal<Local, Bit>,
    beat_in: Signal<Local, Bits<ENTRY_BITS>>,
    assembled: Signal<Local, Bits<ENTRY_BITS>>,
    tagged: Signal<Local, Bits<TAGGED_ENTRY_BITS>>,
    sel_address: Signal<Local, Bits<BA>>,
    write: Signal<Local, Bit>,
    /// The octants left of the entry in the distributor, gated: a B entry
    /// goes only to the children an A entry went to.
    live: Signal<Local, Bits<8>>,
    /// The gate after this clock: all children for an A entry, those in
    /// `reached` for a B entry.
    gate_next: Signal<Local, Bits<8>>,
    /// The chosen child among A's (zero for a B entry).
    target_low: Signal<Local, Bits<8>>,
    entry_done: Signal<Local, Bit>,
    last_child: Signal<Local, Bit>,
    slot_full: Signal<Local, Bit>,
    flush_out: Signal<Local, Bit>,
    load: Signal<Local, Bit>,
    command_beats: Signal<Local, Bits<9>>,
    command_address: Signal<Local, Bits<COMMAND_BITS>>,
    command_beats_wide: Signal<Local, Bits<COMMAND_BITS>>,
    command_slot_wide: Signal<Local, Bits<COMMAND_BITS>>,
    issue: Signal<Local, Bit>,
    command_head: Signal<Local, Bits<COMMAND_BITS>>,
    burst_head: Signal<Local, Bits<BURST_BITS>>,
    head_slot: Signal<Local, Bits<BA>>,
    start_feed: Signal<Local, Bit>,
    /// Beats in the W queue and the one read from the buffer.
    w_held: Signal<Local, Bits<COUNT_BITS>>,
    feed: Signal<Local, Bit>,
    freed: Signal<Local, Bit>,
    beat_out: Signal<Local, Bit>,
    /// Outputs of the parts the pass does not need, folded into one bit.
    unused_outputs: Signal<Local, Bit>,
}

impl<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
    > crate::unit::Unit for ListPass<G, V, N, T, DW, S>
{
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            reader,
            lane,
            entries,
            masks,
            select,
            buffer,
            commands,
            bursts,
            w_data,
            w_last,
            running,
            finished,
            failed,
            corner_x_q,
            corner_y_q,
            corner_z_q,
            level_q,
            count_a,
            base_b,
            count_b,
            stride,
            read_stage,
            setup_left,
            gear,
            gear_count,
            entries_in,
            entry,
            object,
            mask_left,
            reached,
            beat,
            beat_data,
            flushing,
            flushed,
            flush_child,
            fill,
            half,
            pending_low,
            pending_high,
            count,
            region,
            aw_valid,
            aw_address,
            aw_length,
            unanswered,
            feed_left,
            feed_slot,
            feed_address,
            read_valid,
            read_last
        );
    }
    fn settings(&self) -> Vec<(&'static str, String)> {
        vec![
            ("burst_beats", WRITE_BURST_BEATS.to_string()),
            ("outstanding", self.outstanding.val().index().to_string()),
        ]
    }
}

impl<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
    > ListPass<G, V, N, T, DW, S>
{
    /// Beats of an entry.
    pub const BEATS_PER_ENTRY: usize = ENTRY_BITS / DW;

    /// A pass whose reads are bursts of at most `max_read_burst` beats and
    /// whose reads and writes each keep at most `outstanding` bursts in
    /// flight.
    pub fn new(max_read_burst: usize, outstanding: usize) -> Self {
        assert!(
            super::list_pass_machine::PASS_DATA_BITS.contains(&DW) && S * 8 == DW,
            "ListPass: a 64-, 128- or 256-bit port, not {DW}"
        );
        let burst = WRITE_BURST_BEATS;
        let per_entry = Self::BEATS_PER_ENTRY;
        assert!((1..=crate::axi::MAX_OUTSTANDING).contains(&outstanding));
        ListPass {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            corner_x: Default::default(),
            corner_y: Default::default(),
            corner_z: Default::default(),
            level: Default::default(),
            list_base: Default::default(),
            list_count: Default::default(),
            child_base: Default::default(),
            child_stride: Default::default(),
            busy: Default::default(),
            done: Default::default(),
            error: Default::default(),
            child_count: Default::default(),
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
            reader: BurstReader::new(max_read_burst, outstanding),
            // An entry comes at most every `ENTRY_BITS / DW` clocks: the
            // lane shares its setup's products over them.
            lane: ClassifyLane::with_phases(ENTRY_BITS / DW),
            entries: Default::default(),
            masks: BeatFifo::in_distributed_ram(),
            select: Default::default(),
            buffer: SimpleDualPortRam::new(1 << BA).in_block_ram(),
            commands: BeatFifo::in_distributed_ram(),
            bursts: BeatFifo::in_distributed_ram(),
            w_data: BeatFifo::in_distributed_ram(),
            w_last: BeatFifo::in_distributed_ram(),
            outstanding: Constant::new((outstanding as u64).into()),
            size: Constant::new(((S as u64).trailing_zeros() as u64).into()),
            strobes: Constant::new(!Bits::<S>::default()),
            log_beats_per_entry: Constant::new((per_entry.trailing_zeros() as u64).into()),
            last_beat: Constant::new((per_entry as u64 - 1).into()),
            beat_step: Constant::new(((DW % ENTRY_BITS) as u64).into()),
            gear_keep: Constant::new(if DW == ENTRY_BITS {
                Bits::default()
            } else {
                !Bits::<ENTRY_BITS>::default()
            }),
            top_offset: Constant::new(((ENTRY_BITS - DW) as u64).into()),
            slot_full_beats: Constant::new((burst as u64 - 1).into()),
            burst_bytes: Constant::new(((burst * S) as u64).into()),
            log_burst_beats: Constant::new((burst.trailing_zeros() as u64).into()),
            entry_capacity: Constant::new(
                (BeatFifo::<TAGGED_ENTRY_BITS, ENTRY_QUEUE_ADDRESS_BITS>::CAPACITY as u64).into(),
            ),
            w_capacity: Constant::new(
                (BeatFifo::<DW, W_QUEUE_ADDRESS_BITS>::CAPACITY as u64).into(),
            ),
            object_bit: Constant::new(
                Bits::<TAGGED_ENTRY_BITS>::default().replace_bit(ENTRY_BITS, true),
            ),
            beats_shift: Constant::new((ADDRESS_BITS as u64).into()),
            slot_shift: Constant::new(((ADDRESS_BITS + 9) as u64).into()),
            running: Default::default(),
            finished: Default::default(),
            failed: Default::default(),
            corner_x_q: Default::default(),
            corner_y_q: Default::default(),
            corner_z_q: Default::default(),
            level_q: Default::default(),
            count_a: Default::default(),
            base_b: Default::default(),
            count_b: Default::default(),
            stride: Default::default(),
            read_stage: Default::default(),
            setup_left: Default::default(),
            gear: Default::default(),
            gear_count: Default::default(),
            entries_in: Default::default(),
            entry: Default::default(),
            object: Default::default(),
            mask_left: Default::default(),
            reached: Default::default(),
            beat: Default::default(),
            beat_data: Default::default(),
            flushing: Default::default(),
            flushed: Default::default(),
            flush_child: Default::default(),
            fill: Default::default(),
            half: Default::default(),
            pending_low: Default::default(),
            pending_high: Default::default(),
            count: Default::default(),
            region: Default::default(),
            aw_valid: Default::default(),
            aw_address: Default::default(),
            aw_length: Default::default(),
            unanswered: Default::default(),
            feed_left: Default::default(),
            feed_slot: Default::default(),
            feed_address: Default::default(),
            read_valid: Default::default(),
            read_last: Default::default(),
            accepted: Default::default(),
            room: Default::default(),
            push: Default::default(),
            beat_in: Default::default(),
            assembled: Default::default(),
            tagged: Default::default(),
            sel_address: Default::default(),
            write: Default::default(),
            live: Default::default(),
            gate_next: Default::default(),
            target_low: Default::default(),
            entry_done: Default::default(),
            last_child: Default::default(),
            slot_full: Default::default(),
            flush_out: Default::default(),
            load: Default::default(),
            command_beats: Default::default(),
            command_address: Default::default(),
            command_beats_wide: Default::default(),
            command_slot_wide: Default::default(),
            issue: Default::default(),
            command_head: Default::default(),
            burst_head: Default::default(),
            head_slot: Default::default(),
            start_feed: Default::default(),
            w_held: Default::default(),
            feed: Default::default(),
            freed: Default::default(),
            beat_out: Default::default(),
            unused_outputs: Default::default(),
        }
    }
}

impl<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
    > Logic for ListPass<G, V, N, T, DW, S>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            running,
            finished,
            failed,
            corner_x_q,
            corner_y_q,
            corner_z_q,
            level_q,
            count_a,
            base_b,
            count_b,
            read_stage,
            setup_left,
            gear,
            gear_count,
            entries_in,
            entry,
            object,
            mask_left,
            reached,
            beat,
            beat_data,
            flushing,
            flushed,
            flush_child,
            aw_valid,
            aw_address,
            aw_length,
            unanswered,
            feed_left,
            feed_slot,
            feed_address,
            read_valid,
            read_last
        );
        for k in 0..2 {
            self.stride[k].clock.next = self.clock.val();
            self.stride[k].d.next = self.stride[k].q.val();
        }
        for i in 0..16 {
            self.fill[i].clock.next = self.clock.val();
            self.fill[i].d.next = self.fill[i].q.val();
            self.half[i].clock.next = self.clock.val();
            self.half[i].d.next = self.half[i].q.val();
            self.pending_low[i].clock.next = self.clock.val();
            self.pending_low[i].d.next = self.pending_low[i].q.val();
            self.pending_high[i].clock.next = self.clock.val();
            self.pending_high[i].d.next = self.pending_high[i].q.val();
            self.count[i].clock.next = self.clock.val();
            self.count[i].d.next = self.count[i].q.val();
            self.region[i].clock.next = self.clock.val();
            self.region[i].d.next = self.region[i].q.val();
            self.child_count[i].next = self.count[i].q.val();
        }
        clock!(
            self, clock, reader, lane, entries, masks, select, buffer, commands, bursts, w_data,
            w_last
        );
        self.reader.reset.next = self.reset.val();
        self.entries.reset.next = self.reset.val();
        self.masks.reset.next = self.reset.val();
        self.commands.reset.next = self.reset.val();
        self.bursts.reset.next = self.reset.val();
        self.w_data.reset.next = self.reset.val();
        self.w_last.reset.next = self.reset.val();
        self.lane.reset.next = self.reset.val();
        self.busy.next = self.running.q.val();
        self.done.next = self.finished.q.val();
        self.error.next = self.failed.q.val() | self.reader.error.val();

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

        // The lane: setup at the cell's corner, the classifier at its level.
        self.lane.in_valid.next = self.push.val();
        self.lane.in_index.next = 0.into();
        self.lane.in_vertices.next = bit_cast::<T, ENTRY_BITS>(self.assembled.val());
        self.lane.in_corner_x.next = self.corner_x_q.q.val();
        self.lane.in_corner_y.next = self.corner_y_q.q.val();
        self.lane.in_corner_z.next = self.corner_z_q.q.val();
        self.lane.in_level.next = self.level_q.q.val();
        self.masks.push.next = self.lane.out_valid.val();
        self.masks.push_data.next = self.lane.out_mask.val();

        // The distributor: the lowest octant left, in its child's slot.
        // A B entry goes only to children that A's entries reached: a child
        // without A is dropped by the split rule, so its B list would never
        // be read (the controller reads the shorter list as A).
        // The choice is registered: `select` made it on this clock's state
        // in the clock before (its inputs are set at the end).
        self.live.next = self.select.live.val();
        self.sel_address.next = (bit_cast::<BA, SLOT_BITS>(self.select.slot.val())
            << self.log_burst_beats.val())
            + bit_cast::<BA, 9>(self.select.fill_of.val());
        self.write.next =
            (self.live.val() != 0) & !self.select.blocked.val() & !self.flushing.q.val();
        self.entry_done.next = self.write.val() & (self.beat.q.val() == self.last_beat.val());
        self.last_child.next = self.select.single.val();
        self.slot_full.next =
            self.write.val() & (self.select.fill_of.val() == self.slot_full_beats.val());
        self.flush_out.next = self.flushing.q.val() & (self.select.fill_of.val() != 0);
        self.buffer.write_enable.next = self.write.val();
        self.buffer.write_address.next = self.sel_address.val();
        self.buffer.write_data.next = self.beat_data.q.val().get_bits::<DW>(0);
        if self.write.val() {
            if self.entry_done.val() {
                self.beat.d.next = 0.into();
                self.beat_data.d.next = self.entry.q.val();
                self.mask_left.d.next = self.live.val() & !self.select.lowest.val();
            } else {
                self.beat.d.next = self.beat.q.val() + 1;
                self.beat_data.d.next = self.beat_data.q.val() >> self.beat_step.val();
            }
        }
        for i in 0..16 {
            if self.select.target.val().get_bit(i) {
                if self.write.val() {
                    self.fill[i].d.next = self.fill[i].q.val() + 1;
                }
                if self.entry_done.val() {
                    self.count[i].d.next = self.count[i].q.val() + 1;
                }
                if self.slot_full.val() | self.flush_out.val() {
                    self.fill[i].d.next = 0.into();
                    self.half[i].d.next = !self.half[i].q.val();
                    if self.half[i].q.val() {
                        self.pending_high[i].d.next = true;
                    } else {
                        self.pending_low[i].d.next = true;
                    }
                    self.region[i].d.next = self.region[i].q.val() + self.burst_bytes.val();
                }
            }
        }
        self.target_low.next = bit_cast::<8, CHILDREN>(self.select.target.val());
        if self.write.val() {
            self.reached.d.next = self.reached.q.val() | self.target_low.val();
        }
        // The next entry, in the clock the last beat of the last child goes.
        self.load.next = self.masks.out_valid.val()
            & self.entries.out_valid.val()
            & ((self.live.val() == 0) | (self.entry_done.val() & self.last_child.val()));
        self.entries.pop.next = self.load.val();
        self.masks.pop.next = self.load.val();
        if self.load.val() {
            self.entry.d.next = self.entries.out_data.val().get_bits::<ENTRY_BITS>(0);
            self.object.d.next = self.entries.out_data.val().get_bit(256);
            self.mask_left.d.next = self.masks.out_data.val();
            self.beat.d.next = 0.into();
            self.beat_data.d.next = self.entries.out_data.val().get_bits::<ENTRY_BITS>(0);
        }
        // After the last entry: the partly filled slots, one child a clock.
        if self.running.q.val()
            & (self.read_stage.q.val() == 3)
            & (self.entries.count.val() == 0)
            & (self.live.val() == 0)
            & !self.flushing.q.val()
            & !self.flushed.q.val()
        {
            self.flushing.d.next = true;
            self.flush_child.d.next = 0.into();
        }
        if self.flushing.q.val() {
            self.flush_child.d.next = self.flush_child.q.val() + 1;
            if self.flush_child.q.val() == 15 {
                self.flushing.d.next = false;
                self.flushed.d.next = true;
            }
        }
        self.command_beats.next = self.select.fill_of.val();
        if self.slot_full.val() {
            self.command_beats.next = self.select.fill_of.val() + 1;
        }
        self.command_address.next =
            bit_cast::<COMMAND_BITS, ADDRESS_BITS>(self.select.region_of.val());
        self.command_beats_wide.next = bit_cast::<COMMAND_BITS, 9>(self.command_beats.val());
        self.command_slot_wide.next = bit_cast::<COMMAND_BITS, SLOT_BITS>(self.select.slot.val());
        self.commands.push.next = self.slot_full.val() | self.flush_out.val();
        self.commands.push_data.next = self.command_address.val()
            | (self.command_beats_wide.val() << self.beats_shift.val())
            | (self.command_slot_wide.val() << self.slot_shift.val());

        // AW: a command at a time, at most `outstanding` unanswered.
        self.command_head.next = self.commands.out_data.val();
        self.issue.next = self.commands.out_valid.val()
            & !self.aw_valid.q.val()
            & (self.unanswered.q.val() < self.outstanding.val());
        self.commands.pop.next = self.issue.val();
        self.bursts.push.next = self.issue.val();
        self.bursts.push_data.next = self.command_head.val().get_bits::<BURST_BITS>(32);
        if self.aw_valid.q.val() & self.m_axi_awready.val() {
            self.aw_valid.d.next = false;
        }
        if self.issue.val() {
            self.aw_valid.d.next = true;
            self.aw_address.d.next = self.command_head.val().get_bits::<ADDRESS_BITS>(0);
            self.aw_length.d.next = self.command_head.val().get_bits::<8>(32) - 1;
        }
        self.m_axi_awid.next = false;
        self.m_axi_awaddr.next = self.aw_address.q.val();
        self.m_axi_awlen.next = self.aw_length.q.val();
        self.m_axi_awsize.next = self.size.val();
        self.m_axi_awburst.next = 1.into();
        self.m_axi_awcache.next = 3.into();
        self.m_axi_awprot.next = 0.into();
        self.m_axi_awvalid.next = self.aw_valid.q.val();

        // The feeder: each issued burst's beats out of its slot, in order.
        self.burst_head.next = self.bursts.out_data.val();
        self.head_slot.next =
            bit_cast::<BA, SLOT_BITS>(self.burst_head.val().get_bits::<SLOT_BITS>(9))
                << self.log_burst_beats.val();
        self.start_feed.next = (self.feed_left.q.val() == 0) & self.bursts.out_valid.val();
        self.bursts.pop.next = self.start_feed.val();
        if self.start_feed.val() {
            self.feed_left.d.next = self.burst_head.val().get_bits::<9>(0);
            self.feed_slot.d.next = self.burst_head.val().get_bits::<SLOT_BITS>(9);
            self.feed_address.d.next = self.head_slot.val();
        }
        self.w_held.next = self.w_data.count.val();
        if self.read_valid.q.val() {
            self.w_held.next = self.w_data.count.val() + 1;
        }
        self.feed.next =
            (self.feed_left.q.val() != 0) & (self.w_held.val() < self.w_capacity.val());
        self.buffer.read_enable.next = self.feed.val();
        self.buffer.read_address.next = self.feed_address.q.val();
        self.read_valid.d.next = self.feed.val();
        self.read_last.d.next = self.feed.val() & (self.feed_left.q.val() == 1);
        self.freed.next = self.feed.val() & (self.feed_left.q.val() == 1);
        if self.feed.val() {
            self.feed_left.d.next = self.feed_left.q.val() - 1;
            self.feed_address.d.next = self.feed_address.q.val() + 1;
        }
        for i in 0..16 {
            if self.freed.val() & (self.feed_slot.q.val().get_bits::<4>(1).index() == i) {
                if self.feed_slot.q.val().get_bit(0) {
                    self.pending_high[i].d.next = false;
                } else {
                    self.pending_low[i].d.next = false;
                }
            }
        }
        self.w_data.push.next = self.read_valid.q.val();
        self.w_data.push_data.next = self.buffer.read_data.val();
        self.w_last.push.next = self.read_valid.q.val();
        self.w_last.push_data.next = self.read_last.q.val().into();
        self.m_axi_wvalid.next = self.w_data.out_valid.val();
        self.m_axi_wdata.next = self.w_data.out_data.val();
        self.m_axi_wlast.next = self.w_last.out_data.val().any();
        self.m_axi_wstrb.next = self.strobes.val();
        self.beat_out.next = self.w_data.out_valid.val() & self.m_axi_wready.val();
        self.w_data.pop.next = self.beat_out.val();
        self.w_last.pop.next = self.beat_out.val();

        // B: every response taken at once.
        self.m_axi_bready.next = true;
        if self.m_axi_bvalid.val() & ((self.m_axi_bresp.val() != 0) | self.m_axi_bid.val()) {
            self.failed.d.next = true;
        }
        if self.issue.val() & !self.m_axi_bvalid.val() {
            self.unanswered.d.next = self.unanswered.q.val() + 1;
        } else if !self.issue.val() & self.m_axi_bvalid.val() {
            self.unanswered.d.next = self.unanswered.q.val() - 1;
        }

        // The end: flushed, and every burst written and answered.
        if self.running.q.val()
            & self.flushed.q.val()
            & (self.commands.count.val() == 0)
            & !self.aw_valid.q.val()
            & (self.bursts.count.val() == 0)
            & (self.feed_left.q.val() == 0)
            & !self.read_valid.q.val()
            & (self.w_data.count.val() == 0)
            & (self.unanswered.q.val() == 0)
        {
            self.running.d.next = false;
            self.finished.d.next = true;
        }
        // The list addresses: a chain of adds per object after `start`.
        if self.setup_left.q.val() != 0 {
            self.setup_left.d.next = self.setup_left.q.val() - 1;
            for i in 1..8 {
                self.region[i].d.next = self.region[i - 1].q.val() + self.stride[0].q.val();
            }
            for i in 9..16 {
                self.region[i].d.next = self.region[i - 1].q.val() + self.stride[1].q.val();
            }
        }
        if self.start.val() & !self.running.q.val() {
            self.reader.start.next = true;
            self.running.d.next = true;
            self.finished.d.next = false;
            self.failed.d.next = false;
            self.corner_x_q.d.next = self.corner_x.val();
            self.corner_y_q.d.next = self.corner_y.val();
            self.corner_z_q.d.next = self.corner_z.val();
            self.level_q.d.next = self.level.val();
            self.count_a.d.next = self.list_count[0].val();
            self.base_b.d.next = self.list_base[1].val();
            self.count_b.d.next = self.list_count[1].val();
            self.stride[0].d.next = self.child_stride[0].val();
            self.stride[1].d.next = self.child_stride[1].val();
            self.read_stage.d.next = 1.into();
            self.setup_left.d.next = 7.into();
            self.gear_count.d.next = 0.into();
            self.entries_in.d.next = 0.into();
            self.flushing.d.next = false;
            self.flushed.d.next = false;
            self.reached.d.next = 0.into();
            for i in 0..16 {
                self.fill[i].d.next = 0.into();
                self.half[i].d.next = false;
                self.pending_low[i].d.next = false;
                self.pending_high[i].d.next = false;
                self.count[i].d.next = 0.into();
            }
            for i in 0..8 {
                self.region[i].d.next = self.child_base[0].val();
            }
            for i in 8..16 {
                self.region[i].d.next = self.child_base[1].val();
            }
        }
        if self.reset.val() {
            self.running.d.next = false;
            self.finished.d.next = false;
            self.mask_left.d.next = 0.into();
            self.flushing.d.next = false;
            self.aw_valid.d.next = false;
            self.unanswered.d.next = 0.into();
            self.feed_left.d.next = 0.into();
            self.read_valid.d.next = false;
        }
        // The next clock's choice, on the registers' next values (every
        // one of them is written above).
        self.gate_next.next = 255.into();
        if self.object.d.val() {
            self.gate_next.next = self.reached.d.val();
        }
        self.select.mask_left.next = self.mask_left.d.val() & self.gate_next.val();
        self.select.object.next = self.object.d.val();
        self.select.flushing.next = self.flushing.d.val();
        self.select.flush_child.next = self.flush_child.d.val();
        for i in 0..16 {
            self.select.fill[i].next = self.fill[i].d.val();
            self.select.half[i].next = self.half[i].d.val();
            self.select.pending_low[i].next = self.pending_low[i].d.val();
            self.select.pending_high[i].next = self.pending_high[i].d.val();
            self.select.region[i].next = self.region[i].d.val();
        }
        self.unused_outputs.next = self.reader.out_last.val()
            ^ self.lane.out_index.val().any()
            ^ self.masks.count.val().any()
            ^ self.w_last.count.val().any()
            ^ self.w_last.out_valid.val();
    }
}
