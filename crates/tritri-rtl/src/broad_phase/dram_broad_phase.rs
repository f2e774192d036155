//! The broad-phase accelerator with its scene in external memory: the
//! binning controller ([`super::dram_binning_unit`]) walks the octree in
//! passes over DRAM, and each leaf it decides is read back
//! ([`super::leaf_reader`]) into the leaf batcher, the collision system
//! and the owner filter, all on one AXI4 manager port.
//!
//! ```text
//!            ┌── controller: passes (AR, R, AW, W, B) ──► leaf ──► sequencer (one leaf, A tile × B tile)
//!  AXI4 ◄────┤                                                          │ a tile
//!            └── leaf reader (AR, R while the sequencer holds a leaf) ◄──┘
//!  leaf reader ──► leaf batcher ──► collision system ──► owner filter ──► pairs (valid/ready)
//! ```
//!
//! * **The host** writes each object's root list (32-byte entries, their
//!   vertices on the grid and their triangle's index,
//!   [`super::list_entry`]) into the memory, gives their places, the root
//!   cell and the arena, and pulses `start`; it reads the pairs from the
//!   `out_*` stream, each intersecting pair (or pair without a
//!   certificate) once, as its triangles' indices.
//! * **One leaf at a time.** The sequencer takes a leaf when it holds none
//!   (`leaf_ready`), and reads it as tiles: every A tile of at most the
//!   system's depth with every B tile, each a batch of the system, under
//!   the leaf's number (the owner filter skips a pair's appearances in
//!   earlier tiles of the same leaf). While it holds a leaf, or the reader
//!   still reads, no pass starts (`pass_hold`): a pass may write over a
//!   leaf's lists, and the read channel is the reader's.
//! * **The owner filter's heads** are cleared before the first leaf, one
//!   index a clock (`index_count_0` indices of A, then B's), while the
//!   root's pass runs.
//!
//! * **Two systems.** [`DramBroadPhase`] holds pipelines with their rare
//!   pairs on units of their own; [`SharedDramBroadPhase`] pipelines that
//!   share one (it fits the ECP5-85 beside the controller). One macro
//!   writes both.
//!
//! Its clock-exact model to the last verdict is
//! [`super::dram_broad_phase_machine`]. The co-simulation
//! (`tritri-cosim/tests/dram_broad_phase.rs`) holds the pairs to the exact
//! answer on the grid and rust-hdl, Verilator and the model to one
//! another.

use super::dram_binning_unit::{DramBinningUnit, DramCell};
use super::leaf_batcher::LeafBatcher;
use super::leaf_cost::COUNT_BITS;
use super::leaf_reader::LeafReader;
use super::list_entry::ENTRY_BYTES;
use super::list_packer::INDEX_BITS;
use super::list_pass::ENTRY_COUNT_BITS;
use super::owner_chain_filter::{OwnerChainFilter, CHAIN_LEAF_BITS};
use crate::axi::ADDRESS_BITS;
use crate::system::collision_system::{CollisionSystem, SharedCollisionSystem};
use crate::system::{SystemConfig, COUNTER_BITS, ID_BITS};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

// `update` cuts with literals: 32-bit counts into the batcher's 20-bit
// header counts and 18-bit indices.
const _: () = assert!(
    ENTRY_COUNT_BITS == 32
        && COUNT_BITS == 20
        && INDEX_BITS == 18
        && CHAIN_LEAF_BITS == 20
        && ADDRESS_BITS == 32
);

#[derive(Copy, Clone, PartialEq, Eq, Debug, LogicState)]
pub enum LeafSequence {
    /// No leaf held: the next is taken.
    Idle,
    /// A tile waits for the reader to be free, then starts it.
    Issue,
    /// The tile is read; when the reader's reading ends, the next tile.
    Read,
}

/// How the top is built besides its widths.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DramBroadPhaseBuild {
    /// Reads of at most this many beats, at most `outstanding` in flight
    /// (the controller's passes and the leaf reader alike).
    pub max_read_burst: usize,
    pub outstanding: usize,
    /// Cells above this level are always split (local frames).
    pub max_leaf_level: Option<u32>,
    /// Leaves that can wait under tried splits.
    pub waiting_capacity: usize,
    /// The owner filter's head table (triangle indices per object) and
    /// record tables (entries streamed per object over a run).
    pub triangles: usize,
    pub slots: usize,
    /// Take each leaf's centre off its coordinates (`G > W`).
    pub local_frames: bool,
}

/// The top around a system of type `$system` (whose pipelines decide the
/// rare cases in parallel or on a shared unit), written once for both.
macro_rules! dram_broad_phase {
    ($(#[$meta:meta])* pub struct $name:ident { system: $system:ident $(,)? }) => {
        $(#[$meta])*
        #[derive(LogicBlock)]
        pub struct $name<
            const G: usize,
            const V: usize,
            const N: usize,
            const T: usize,
            const DW: usize,
            const S: usize,
            const W: usize,
            const D: usize,
            const C: usize,
            const O: usize,
        > {
            pub clock: Signal<In, Clock>,
            /// Synchronous, active high.
            pub reset: Signal<In, Bit>,
            /// One clock high while idle or done: a run from the inputs below,
            /// which are held until `done`.
            pub start: Signal<In, Bit>,
            pub corner_x: Signal<In, Bits<G>>,
            pub corner_y: Signal<In, Bits<G>>,
            pub corner_z: Signal<In, Bits<G>>,
            pub level: Signal<In, Bits<6>>,
            /// Object `k`'s root list: its first entry's address and its entries.
            pub list_base: [Signal<In, Bits<ADDRESS_BITS>>; 2],
            pub list_count: [Signal<In, Bits<ENTRY_COUNT_BITS>>; 2],
            /// Object `k`'s triangle indices are below this (its heads cleared).
            pub index_count: [Signal<In, Bits<ENTRY_COUNT_BITS>>; 2],
            /// The arena for the children's lists, `[arena_start, arena_end)`.
            pub arena_start: Signal<In, Bits<ADDRESS_BITS>>,
            pub arena_end: Signal<In, Bits<ADDRESS_BITS>>,
            // Pairs out (valid/ready), the owner filter's.
            pub out_valid: Signal<Out, Bit>,
            pub out_ready: Signal<In, Bit>,
            pub out_index_a: Signal<Out, Bits<ID_BITS>>,
            pub out_index_b: Signal<Out, Bits<ID_BITS>>,
            /// The pair's verdict on the grid and its certificate.
            pub out_hit: Signal<Out, Bit>,
            pub out_certain: Signal<Out, Bit>,
            /// The walk is over (every leaf decided).
            pub binned: Signal<Out, Bit>,
            /// Every leaf read and tested: the system's last verdict is in.
            pub tested: Signal<Out, Bit>,
            /// Every pair decided and the last owned pair taken.
            pub done: Signal<Out, Bit>,
            /// A pass or a read saw a response that was not OKAY.
            pub error: Signal<Out, Bit>,
            /// The system's memory or the owner filter's tables were too small.
            pub overflow: Signal<Out, Bit>,
            pub passes: Signal<Out, Bits<32>>,
            pub leaves: Signal<Out, Bits<CHAIN_LEAF_BITS>>,
            pub arena_full: Signal<Out, Bits<32>>,
            pub waiting_commits: Signal<Out, Bits<32>>,
            pub pairs_tested: Signal<Out, Bits<COUNTER_BITS>>,
            pub hits: Signal<Out, Bits<COUNTER_BITS>>,
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
            controller: DramBinningUnit<G, V, N, T, DW, S>,
            reader: LeafReader<G, T, DW, S>,
            batcher: LeafBatcher<G, T, W>,
            system: $system<W, D, C, O>,
            owner: OwnerChainFilter,
            // The sequencer: the leaf it holds, its tiles.
            seq: DFF<LeafSequence>,
            leaf: DFF<DramCell>,
            /// The current A tile's first entry and the entries from it to the
            /// list's end; the same for B.
            a_at: DFF<Bits<ADDRESS_BITS>>,
            a_rest: DFF<Bits<ENTRY_COUNT_BITS>>,
            b_at: DFF<Bits<ADDRESS_BITS>>,
            b_rest: DFF<Bits<ENTRY_COUNT_BITS>>,
            /// The held leaf's number, and the next leaf's.
            number: DFF<Bits<CHAIN_LEAF_BITS>>,
            next_number: DFF<Bits<CHAIN_LEAF_BITS>>,
            /// Heads still to clear, object by object.
            clear_left: [DFF<Bits<ENTRY_COUNT_BITS>>; 2],
            /// Some head is still to clear: set from the counts' next values,
            /// so that the leaf sequencer and the list pass's hold start from a
            /// register rather than from two 13-bit compares (the routed top's
            /// worst path began at `clear_left`). Zero at power-on, as the
            /// counts are.
            clearing: DFF<Bit>,
            /// Constants of the build: the system's depth, a tile's bytes.
            depth: Constant<Bits<ENTRY_COUNT_BITS>>,
            tile_bytes: Constant<Bits<ADDRESS_BITS>>,
            reader_owns: Signal<Local, Bit>,
            cleared: Signal<Local, Bit>,
            take_leaf: Signal<Local, Bit>,
            tile_a: Signal<Local, Bits<ENTRY_COUNT_BITS>>,
            tile_b: Signal<Local, Bits<ENTRY_COUNT_BITS>>,
            /// Outputs this top does not use, folded into one bit for the lint.
            unused_outputs: Signal<Local, Bit>,
            _config: SystemConfig,
        }

        impl<
                const G: usize,
                const V: usize,
                const N: usize,
                const T: usize,
                const DW: usize,
                const S: usize,
                const W: usize,
                const D: usize,
                const C: usize,
                const O: usize,
            > crate::unit::Unit for $name<G, V, N, T, DW, S, W, D, C, O>
        {
            fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
                crate::sub_units!(
                    self, units, controller, reader, batcher, system, owner, seq, leaf, a_at, a_rest, b_at,
                    b_rest, number, next_number, clear_left, clearing
                );
            }
        }

        impl<
                const G: usize,
                const V: usize,
                const N: usize,
                const T: usize,
                const DW: usize,
                const S: usize,
                const W: usize,
                const D: usize,
                const C: usize,
                const O: usize,
            > $name<G, V, N, T, DW, S, W, D, C, O>
        {
            /// The top of `build` around the system of `config` (whose width must
            /// be `W`, its depth and pipelines powers of two).
            pub fn new(build: DramBroadPhaseBuild, config: SystemConfig) -> Self {
                assert_eq!(config.coordinate_bits, W, "the system's width differs from the type's");
                let depth = config.triangles_per_bank;
                assert!(
                    depth.is_power_of_two() && config.pipelines.is_power_of_two(),
                    "the split rule in hardware needs a power-of-two depth and pipeline count"
                );
                $name {
                    clock: Default::default(),
                    reset: Default::default(),
                    start: Default::default(),
                    corner_x: Default::default(),
                    corner_y: Default::default(),
                    corner_z: Default::default(),
                    level: Default::default(),
                    list_base: Default::default(),
                    list_count: Default::default(),
                    index_count: Default::default(),
                    arena_start: Default::default(),
                    arena_end: Default::default(),
                    out_valid: Default::default(),
                    out_ready: Default::default(),
                    out_index_a: Default::default(),
                    out_index_b: Default::default(),
                    out_hit: Default::default(),
                    out_certain: Default::default(),
                    binned: Default::default(),
                    tested: Default::default(),
                    done: Default::default(),
                    error: Default::default(),
                    overflow: Default::default(),
                    passes: Default::default(),
                    leaves: Default::default(),
                    arena_full: Default::default(),
                    waiting_commits: Default::default(),
                    pairs_tested: Default::default(),
                    hits: Default::default(),
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
                    controller: DramBinningUnit::new(
                        build.max_read_burst,
                        build.outstanding,
                        depth.trailing_zeros(),
                        config.pipelines.trailing_zeros(),
                        build.max_leaf_level,
                        build.waiting_capacity,
                    ),
                    reader: LeafReader::new(build.max_read_burst, build.outstanding),
                    batcher: LeafBatcher::new(build.local_frames),
                    system: $system::with_pipelines(config),
                    owner: OwnerChainFilter::new(build.triangles, build.slots),
                    seq: Default::default(),
                    leaf: Default::default(),
                    a_at: Default::default(),
                    a_rest: Default::default(),
                    b_at: Default::default(),
                    b_rest: Default::default(),
                    number: Default::default(),
                    next_number: Default::default(),
                    clear_left: Default::default(),
                    clearing: Default::default(),
                    depth: Constant::new((depth as u64).into()),
                    tile_bytes: Constant::new(((depth * ENTRY_BYTES) as u64).into()),
                    reader_owns: Default::default(),
                    cleared: Default::default(),
                    take_leaf: Default::default(),
                    tile_a: Default::default(),
                    tile_b: Default::default(),
                    unused_outputs: Default::default(),
                    _config: config,
                }
            }

            pub fn system_config(&self) -> SystemConfig {
                self._config
            }
        }

        impl<
                const G: usize,
                const V: usize,
                const N: usize,
                const T: usize,
                const DW: usize,
                const S: usize,
                const W: usize,
                const D: usize,
                const C: usize,
                const O: usize,
            > Logic for $name<G, V, N, T, DW, S, W, D, C, O>
        {
            #[hdl_gen]
            fn update(&mut self) {
                dff_setup!(
                    self, clock, seq, leaf, a_at, a_rest, b_at, b_rest, number, next_number, clearing
                );
                self.clear_left[0].clock.next = self.clock.val();
                self.clear_left[0].d.next = self.clear_left[0].q.val();
                self.clear_left[1].clock.next = self.clock.val();
                self.clear_left[1].d.next = self.clear_left[1].q.val();
                clock!(self, clock, controller, reader, batcher, system, owner);
                self.controller.reset.next = self.reset.val();
                self.reader.reset.next = self.reset.val();
                self.batcher.reset.next = self.reset.val();
                self.system.reset.next = self.reset.val();
                self.owner.reset.next = self.reset.val();

                // ---- The controller: the root from the inputs.
                self.controller.start.next = self.start.val();
                self.controller.corner_x.next = self.corner_x.val();
                self.controller.corner_y.next = self.corner_y.val();
                self.controller.corner_z.next = self.corner_z.val();
                self.controller.level.next = self.level.val();
                self.controller.list_base[0].next = self.list_base[0].val();
                self.controller.list_base[1].next = self.list_base[1].val();
                self.controller.list_count[0].next = self.list_count[0].val();
                self.controller.list_count[1].next = self.list_count[1].val();
                self.controller.arena_start.next = self.arena_start.val();
                self.controller.arena_end.next = self.arena_end.val();

                // ---- The owner filter's heads, cleared one index a clock from
                // the clock after `start`: A's, then B's.
                self.cleared.next = !self.clearing.q.val();
                self.owner.start.next = self.start.val();
                self.owner.load_valid.next = !self.cleared.val();
                self.owner.load_object.next = self.clear_left[0].q.val() == 0;
                if self.clear_left[0].q.val() != 0 {
                    self.clear_left[0].d.next = self.clear_left[0].q.val() - 1;
                } else if self.clear_left[1].q.val() != 0 {
                    self.clear_left[1].d.next = self.clear_left[1].q.val() - 1;
                }

                // ---- The sequencer: one leaf at a time, tile by tile; no pass
                // while it holds one or the reader reads.
                self.take_leaf.next = (self.seq.q.val() == LeafSequence::Idle) & self.cleared.val();
                self.controller.leaf_ready.next = self.take_leaf.val();
                self.controller.pass_hold.next = (self.seq.q.val() != LeafSequence::Idle)
                    | self.reader.reading.val()
                    | !self.cleared.val();
                self.tile_a.next = self.a_rest.q.val();
                if self.a_rest.q.val() > self.depth.val() {
                    self.tile_a.next = self.depth.val();
                }
                self.tile_b.next = self.b_rest.q.val();
                if self.b_rest.q.val() > self.depth.val() {
                    self.tile_b.next = self.depth.val();
                }
                self.reader.start.next = false;
                self.reader.corner_x.next = bit_cast::<G, 32>(self.leaf.q.val().x);
                self.reader.corner_y.next = bit_cast::<G, 32>(self.leaf.q.val().y);
                self.reader.corner_z.next = bit_cast::<G, 32>(self.leaf.q.val().z);
                self.reader.level.next = self.leaf.q.val().level;
                self.reader.list_base[0].next = self.a_at.q.val();
                self.reader.list_count[0].next = self.tile_a.val();
                self.reader.list_base[1].next = self.b_at.q.val();
                self.reader.list_count[1].next = self.tile_b.val();
                match self.seq.q.val() {
                    LeafSequence::Idle => {
                        if self.take_leaf.val() & self.controller.leaf_valid.val() {
                            self.leaf.d.next.x = bit_cast::<32, G>(self.controller.leaf_x.val());
                            self.leaf.d.next.y = bit_cast::<32, G>(self.controller.leaf_y.val());
                            self.leaf.d.next.z = bit_cast::<32, G>(self.controller.leaf_z.val());
                            self.leaf.d.next.level = self.controller.leaf_level.val();
                            self.leaf.d.next.base_a = self.controller.leaf_base[0].val();
                            self.leaf.d.next.count_a = self.controller.leaf_count[0].val();
                            self.leaf.d.next.base_b = self.controller.leaf_base[1].val();
                            self.leaf.d.next.count_b = self.controller.leaf_count[1].val();
                            self.a_at.d.next = self.controller.leaf_base[0].val();
                            self.a_rest.d.next = self.controller.leaf_count[0].val();
                            self.b_at.d.next = self.controller.leaf_base[1].val();
                            self.b_rest.d.next = self.controller.leaf_count[1].val();
                            self.number.d.next = self.next_number.q.val();
                            self.next_number.d.next = self.next_number.q.val() + 1;
                            // A leaf without an object has no pair (the controller
                            // sends none; taken and dropped all the same).
                            if (self.controller.leaf_count[0].val() != 0)
                                & (self.controller.leaf_count[1].val() != 0)
                            {
                                self.seq.d.next = LeafSequence::Issue;
                            }
                        }
                    }
                    LeafSequence::Issue => {
                        if !self.reader.busy.val() {
                            self.reader.start.next = true;
                            self.seq.d.next = LeafSequence::Read;
                        }
                    }
                    LeafSequence::Read => {
                        if !self.reader.reading.val() {
                            self.seq.d.next = LeafSequence::Issue;
                            if self.b_rest.q.val() > self.depth.val() {
                                self.b_at.d.next = self.b_at.q.val() + self.tile_bytes.val();
                                self.b_rest.d.next = self.b_rest.q.val() - self.depth.val();
                            } else if self.a_rest.q.val() > self.depth.val() {
                                self.a_at.d.next = self.a_at.q.val() + self.tile_bytes.val();
                                self.a_rest.d.next = self.a_rest.q.val() - self.depth.val();
                                self.b_at.d.next = self.leaf.q.val().base_b;
                                self.b_rest.d.next = self.leaf.q.val().count_b;
                            } else {
                                self.seq.d.next = LeafSequence::Idle;
                            }
                        }
                    }
                    _ => {}
                }
                if self.start.val() {
                    self.clear_left[0].d.next = self.index_count[0].val();
                    self.clear_left[1].d.next = self.index_count[1].val();
                    self.next_number.d.next = 0.into();
                }
                if self.reset.val() {
                    self.seq.d.next = LeafSequence::Idle;
                    self.clear_left[0].d.next = 0.into();
                    self.clear_left[1].d.next = 0.into();
                }
                self.clearing.d.next =
                    (self.clear_left[0].d.val() != 0) | (self.clear_left[1].d.val() != 0);

                // ---- The port: AR and R are the reader's while the sequencer
                // holds a leaf, the controller's otherwise; AW, W and B are always
                // the controller's (the reader never writes).
                self.reader_owns.next = self.seq.q.val() != LeafSequence::Idle;
                self.m_axi_arid.next = self.controller.m_axi_arid.val();
                self.m_axi_araddr.next = self.controller.m_axi_araddr.val();
                self.m_axi_arlen.next = self.controller.m_axi_arlen.val();
                self.m_axi_arsize.next = self.controller.m_axi_arsize.val();
                self.m_axi_arburst.next = self.controller.m_axi_arburst.val();
                self.m_axi_arcache.next = self.controller.m_axi_arcache.val();
                self.m_axi_arprot.next = self.controller.m_axi_arprot.val();
                self.m_axi_arvalid.next = self.controller.m_axi_arvalid.val();
                self.m_axi_rready.next = self.controller.m_axi_rready.val();
                if self.reader_owns.val() {
                    self.m_axi_arid.next = self.reader.m_axi_arid.val();
                    self.m_axi_araddr.next = self.reader.m_axi_araddr.val();
                    self.m_axi_arlen.next = self.reader.m_axi_arlen.val();
                    self.m_axi_arsize.next = self.reader.m_axi_arsize.val();
                    self.m_axi_arburst.next = self.reader.m_axi_arburst.val();
                    self.m_axi_arcache.next = self.reader.m_axi_arcache.val();
                    self.m_axi_arprot.next = self.reader.m_axi_arprot.val();
                    self.m_axi_arvalid.next = self.reader.m_axi_arvalid.val();
                    self.m_axi_rready.next = self.reader.m_axi_rready.val();
                }
                self.controller.m_axi_rid.next = self.m_axi_rid.val();
                self.reader.m_axi_rid.next = self.m_axi_rid.val();
                self.controller.m_axi_rdata.next = self.m_axi_rdata.val();
                self.reader.m_axi_rdata.next = self.m_axi_rdata.val();
                self.controller.m_axi_rresp.next = self.m_axi_rresp.val();
                self.reader.m_axi_rresp.next = self.m_axi_rresp.val();
                self.controller.m_axi_rlast.next = self.m_axi_rlast.val();
                self.reader.m_axi_rlast.next = self.m_axi_rlast.val();
                self.controller.m_axi_arready.next = self.m_axi_arready.val() & !self.reader_owns.val();
                self.reader.m_axi_arready.next = self.m_axi_arready.val() & self.reader_owns.val();
                self.controller.m_axi_rvalid.next = self.m_axi_rvalid.val() & !self.reader_owns.val();
                self.reader.m_axi_rvalid.next = self.m_axi_rvalid.val() & self.reader_owns.val();
                self.m_axi_awid.next = self.controller.m_axi_awid.val();
                self.m_axi_awaddr.next = self.controller.m_axi_awaddr.val();
                self.m_axi_awlen.next = self.controller.m_axi_awlen.val();
                self.m_axi_awsize.next = self.controller.m_axi_awsize.val();
                self.m_axi_awburst.next = self.controller.m_axi_awburst.val();
                self.m_axi_awcache.next = self.controller.m_axi_awcache.val();
                self.m_axi_awprot.next = self.controller.m_axi_awprot.val();
                self.m_axi_awvalid.next = self.controller.m_axi_awvalid.val();
                self.m_axi_wdata.next = self.controller.m_axi_wdata.val();
                self.m_axi_wstrb.next = self.controller.m_axi_wstrb.val();
                self.m_axi_wlast.next = self.controller.m_axi_wlast.val();
                self.m_axi_wvalid.next = self.controller.m_axi_wvalid.val();
                self.m_axi_bready.next = self.controller.m_axi_bready.val();
                self.controller.m_axi_awready.next = self.m_axi_awready.val();
                self.controller.m_axi_wready.next = self.m_axi_wready.val();
                self.controller.m_axi_bid.next = self.m_axi_bid.val();
                self.controller.m_axi_bresp.next = self.m_axi_bresp.val();
                self.controller.m_axi_bvalid.next = self.m_axi_bvalid.val();
                self.reader.m_axi_awready.next = false;
                self.reader.m_axi_wready.next = false;
                self.reader.m_axi_bid.next = false;
                self.reader.m_axi_bresp.next = 0.into();
                self.reader.m_axi_bvalid.next = false;

                // ---- Leaf stream → batcher.
                self.batcher.start.next = self.start.val();
                self.batcher.in_valid.next = self.reader.out_valid.val();
                self.reader.out_ready.next = self.batcher.in_ready.val();
                self.batcher.in_header.next = self.reader.out_header.val();
                self.batcher.in_object.next = self.reader.out_object.val();
                self.batcher.in_index.next = bit_cast::<INDEX_BITS, 32>(self.reader.out_index.val());
                self.batcher.in_vertices.next = self.reader.out_vertices.val();
                self.batcher.in_x.next = self.reader.out_x.val();
                self.batcher.in_y.next = self.reader.out_y.val();
                self.batcher.in_z.next = self.reader.out_z.val();
                self.batcher.in_level.next = self.reader.out_level.val();
                self.batcher.in_count_a.next = bit_cast::<COUNT_BITS, 32>(self.reader.out_count_a.val());
                self.batcher.in_count_b.next = bit_cast::<COUNT_BITS, 32>(self.reader.out_count_b.val());
                self.batcher.in_leaf_number.next = self.number.q.val();

                // ---- Batches → system.
                self.system.in_valid.next = self.batcher.out_valid.val();
                self.batcher.out_ready.next = self.system.in_ready.val();
                self.system.in_end.next = self.batcher.out_end.val();
                self.system.in_object.next = self.batcher.out_object.val();
                self.system.in_id.next = self.batcher.out_id.val();
                self.system.in_x0.next = self.batcher.out_x0.val();
                self.system.in_y0.next = self.batcher.out_y0.val();
                self.system.in_z0.next = self.batcher.out_z0.val();
                self.system.in_x1.next = self.batcher.out_x1.val();
                self.system.in_y1.next = self.batcher.out_y1.val();
                self.system.in_z1.next = self.batcher.out_z1.val();
                self.system.in_x2.next = self.batcher.out_x2.val();
                self.system.in_y2.next = self.batcher.out_y2.val();
                self.system.in_z2.next = self.batcher.out_z2.val();

                // ---- Hits → owner filter → pairs.
                self.owner.entry_valid.next = self.batcher.entry_valid.val();
                self.owner.entry_object.next = self.batcher.entry_object.val();
                self.owner.entry_index.next = self.batcher.entry_index.val();
                self.owner.entry_slot.next = self.batcher.entry_slot.val();
                self.owner.entry_leaf.next = self.batcher.entry_leaf.val();
                self.owner.in_valid.next = self.system.out_valid.val();
                self.system.out_ready.next = self.owner.in_ready.val();
                self.owner.in_slot_a.next = self.system.out_id_a.val();
                self.owner.in_slot_b.next = self.system.out_id_b.val();
                self.owner.in_hit.next = self.system.out_hit.val();
                self.owner.in_certain.next = self.system.out_certain.val();
                self.out_valid.next = self.owner.out_valid.val();
                self.owner.out_ready.next = self.out_ready.val();
                self.out_index_a.next = self.owner.out_index_a.val();
                self.out_index_b.next = self.owner.out_index_b.val();
                self.out_hit.next = self.owner.out_hit.val();
                self.out_certain.next = self.owner.out_certain.val();

                // ---- Status.
                self.binned.next = self.controller.done.val();
                self.tested.next = self.controller.done.val()
                    & self.cleared.val()
                    & (self.seq.q.val() == LeafSequence::Idle)
                    & !self.reader.busy.val()
                    & !self.batcher.busy.val()
                    & self.system.done.val();
                self.done.next = self.tested.val()
                    & self.system.results_empty.val()
                    & !self.system.out_valid.val()
                    & self.owner.idle.val();
                self.error.next = self.controller.error.val() | self.reader.error.val();
                self.overflow.next = self.system.overflow.val() | self.owner.overflow.val();
                self.passes.next = self.controller.passes.val();
                self.leaves.next = self.next_number.q.val();
                self.arena_full.next = self.controller.arena_full.val();
                self.waiting_commits.next = self.controller.waiting_commits.val();
                self.pairs_tested.next = self.system.pairs_tested.val();
                self.hits.next = self.system.hits.val();
                self.unused_outputs.next = self.system.stall_cycles.val().any()
                    ^ self.reader.m_axi_awvalid.val()
                    ^ self.reader.m_axi_wvalid.val()
                    ^ self.reader.m_axi_bready.val()
                    ^ self.reader.m_axi_awaddr.val().any()
                    ^ self.reader.m_axi_awlen.val().any()
                    ^ self.reader.m_axi_awsize.val().any()
                    ^ self.reader.m_axi_awburst.val().any()
                    ^ self.reader.m_axi_awcache.val().any()
                    ^ self.reader.m_axi_awprot.val().any()
                    ^ self.reader.m_axi_awid.val()
                    ^ self.reader.m_axi_wdata.val().any()
                    ^ self.reader.m_axi_wstrb.val().any()
                    ^ self.reader.m_axi_wlast.val()
                    // The reader's fields are 32 bits wide; the batcher
                    // takes an index of 18 and counts of 20 (checked above).
                    ^ self.reader.out_index.val().get_bits::<14>(18).any()
                    ^ self.reader.out_count_a.val().get_bits::<12>(20).any()
                    ^ self.reader.out_count_b.val().get_bits::<12>(20).any();
            }
        }
    };
}

dram_broad_phase!(
    /// The top with the system's Devillers–Guigue pipelines, their rare
    /// pairs on parallel units of their own.
    pub struct DramBroadPhase {
        system: CollisionSystem,
    }
);

dram_broad_phase!(
    /// The top with pipelines that test their rare pairs on a shared unit
    /// (the one that fits the ECP5-85 beside the controller): the system
    /// holds while a rare pair waits for it.
    pub struct SharedDramBroadPhase {
        system: SharedCollisionSystem,
    }
);
