//! The octree broad phase's binning unit: the host streams each object's
//! triangles once, the unit subdivides the root cell depth first with the
//! split rule and writes the leaves, then streams them out for the
//! collision system. How it works, clock by clock, is the cycle-exact
//! model's documentation ([`super::binning_machine`]); this is that
//! machine in rust-hdl, and the co-simulation holds it to the model's
//! leaves and cycles.
//!
//! ```text
//!  host ─► triangle memories (one per lane) ─┐
//!    └──── root's pass ──┐                   ▼
//!  list memory ─► index ─┴─► triangle ─► setup at the cell's corner ─► classifier
//!  (8 per object,             memory      (5 clocks)                  (6 clocks)
//!   2 indices a word)                                                      │ mask
//!        ▲                                                                  ▼
//!        └─────────────── list packers (8 per object) ◄────────────────────┘
//!  counts ─► leaf costs (split rule) ─► decide ─► frames (stack) / leaves
//! ```
//!
//! Four lanes: A0, A1, B0, B1. A lane is a triangle memory and a setup
//! unit with a classifier step ([`super::classify_lane`]); the two lanes of an object read one list word
//! (two indices) per clock.

use super::binning_machine::{BinningParams, BinningRun, IDENTITY_LIST, PASS_DRAIN};
use super::classify_lane::{ClassifyLane, LANE_LATENCY};
use super::leaf_cost::{LeafCost, COUNT_BITS, LEAF_COST_LATENCY};
use super::list_packer::{ListPacker, INDEX_BITS, LIST_ADDRESS_BITS, LIST_WORD_BITS};
use crate::octree::cell_classifier::{AXES, CELL_CLASSIFIER_LATENCY};
use crate::system::dual_port_ram::SimpleDualPortRam;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Bits of a leaf memory address.
pub const LEAF_ADDRESS_BITS: usize = 20;
/// Bits of a frame memory address: the stack holds a frame per level.
pub const FRAME_ADDRESS_BITS: usize = 6;
/// Bits of a children memory address: a frame's eight children per level.
pub const CHILD_ADDRESS_BITS: usize = FRAME_ADDRESS_BITS + 3;
// The kernel counts clocks with literals: the drain's last clock is
// PASS_DRAIN - 1 = 12, the cost queries' results come 4 clocks after them;
// memory addresses are cut to their widths with literals too.
const _: () = assert!(
    FRAME_ADDRESS_BITS == 6
        && CHILD_ADDRESS_BITS == 9
        && PASS_DRAIN == 2 + LANE_LATENCY as u64 + 1
        && PASS_DRAIN == 13
        && LEAF_COST_LATENCY == 4
        && INDEX_BITS == 18
        && COUNT_BITS == 20
);
/// `binning_cost::cell_cycles(0, 0)`: what the split rule charges a cell
/// besides its entries.
const CLASSIFY_BASE: u64 = CELL_CLASSIFIER_LATENCY as u64 + 1;

/// What the unit is built for: its grid, its memories' sizes and its
/// split rule (the system it feeds).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BinningUnitConfig {
    /// Bits of a grid coordinate (16, 24 or 32, [`BINNING_GRID_WIDTHS`]).
    pub grid_bits: usize,
    /// Triangles per object: the depth of each lane's triangle memory.
    pub triangles: usize,
    /// Words (two indices each) of each of the sixteen list memories.
    pub list_words: usize,
    /// Leaf descriptors the leaf memory holds.
    pub leaves: usize,
    /// The system's memory depth is `2^log_depth` triangles per array.
    pub log_depth: u32,
    /// The system has `2^log_pipelines` pipelines.
    pub log_pipelines: u32,
}

/// The grids the unit is built for (its setup's and classifier's widths).
pub const BINNING_GRID_WIDTHS: [usize; 3] = [16, 24, 32];

impl BinningUnitConfig {
    /// Top module name, every build parameter in it:
    /// `tritri_binning_g<G>_t<triangles>_w<list words>_l<leaves>_d<depth>_p<pipelines>`.
    pub fn unit_name(&self) -> String {
        format!(
            "tritri_binning_g{}_t{}_w{}_l{}_d{}_p{}",
            self.grid_bits,
            self.triangles,
            self.list_words,
            self.leaves,
            1u64 << self.log_depth,
            1u64 << self.log_pipelines
        )
    }

    /// Bits of every memory: four triangle memories of `9 G` bits a word,
    /// sixteen list memories of two indices a word, the leaf memory, the
    /// frame stack and the children's lists.
    pub fn memory_bits(&self) -> u64 {
        let triangles = 4 * self.triangles as u64 * (9 * self.grid_bits) as u64;
        let lists = 16 * self.list_words as u64 * LIST_WORD_BITS as u64;
        let leaves = self.leaves as u64 * CellLists::BITS as u64;
        let frames = (1u64 << FRAME_ADDRESS_BITS) * Frame::BITS as u64;
        let children = (1u64 << CHILD_ADDRESS_BITS) * ChildLists::BITS as u64;
        triangles + lists + leaves + frames + children
    }

    /// A unit for a scene: a `grid_bits` grid, the system of `params`, and
    /// memories just large enough for the model's `run` of the scene with
    /// at most `triangles` per object.
    pub fn sized_for(
        grid_bits: usize,
        params: BinningParams,
        triangles: usize,
        run: &BinningRun,
    ) -> Self {
        BinningUnitConfig {
            grid_bits,
            triangles: triangles.max(1),
            list_words: run
                .list_words
                .iter()
                .flatten()
                .max()
                .copied()
                .unwrap_or(1)
                .max(1) as usize,
            leaves: run.peak_leaves.max(1),
            log_depth: params.log_depth,
            log_pipelines: params.log_pipelines,
        }
    }

    /// An error naming the parameter out of the unit's range, if any.
    pub fn check(&self) -> Result<(), String> {
        if !BINNING_GRID_WIDTHS.contains(&self.grid_bits) {
            return Err(format!(
                "the binning unit is built for {BINNING_GRID_WIDTHS:?}-bit grids, not {}",
                self.grid_bits
            ));
        }
        let fits = |what: &str, n: usize, bits: usize| {
            if n == 0 || n > 1 << bits {
                Err(format!(
                    "{what} {n}: 1 to {} ({bits} address bits)",
                    1u64 << bits
                ))
            } else {
                Ok(())
            }
        };
        fits("triangles per object", self.triangles, INDEX_BITS)?;
        fits("list words", self.list_words, LIST_ADDRESS_BITS)?;
        fits("leaves", self.leaves, LEAF_ADDRESS_BITS)?;
        Ok(())
    }
}

/// Runs `work` on a thread with a stack large enough for the largest
/// units: their rust-hdl models are built on the stack and outgrow a test
/// thread's 2 MiB (this unit's four setups, four classifiers, sixteen
/// packers and memory ports; the pipeline with the shared rare-case unit).
pub fn on_unit_stack<T: Send>(work: impl FnOnce() -> T + Send) -> T {
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .name("binning-unit".into())
            .stack_size(256 << 20)
            .spawn_scoped(scope, work)
            .expect("a thread for the binning unit")
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    })
}

/// A cell and its two lists: the current cell, and a leaf.
#[derive(Clone, Copy, Debug, PartialEq, Default, LogicStruct)]
pub struct CellLists {
    pub x: Bits<32>,
    pub y: Bits<32>,
    pub z: Bits<32>,
    pub level: Bits<6>,
    pub a_memory: Bits<4>,
    pub a_start: Bits<20>,
    pub a_count: Bits<20>,
    pub b_memory: Bits<4>,
    pub b_start: Bits<20>,
    pub b_count: Bits<20>,
}

/// A cell whose children are being visited.
#[derive(Clone, Copy, Debug, PartialEq, Default, LogicStruct)]
pub struct Frame {
    pub x: Bits<32>,
    pub y: Bits<32>,
    pub z: Bits<32>,
    pub level: Bits<6>,
    pub a_memory: Bits<4>,
    pub a_start: Bits<20>,
    pub a_count: Bits<20>,
    pub b_memory: Bits<4>,
    pub b_start: Bits<20>,
    pub b_count: Bits<20>,
    pub leaf_cost: Bits<48>,
    pub classify: Bits<48>,
    pub subtree: Bits<48>,
    pub slack_next: Bits<2>,
    pub forced: Bit,
    pub leaf_mark: Bits<20>,
    pub octant: Bits<4>,
}

/// A child's two lists, written by its parent's pass.
#[derive(Clone, Copy, Debug, PartialEq, Default, LogicStruct)]
pub struct ChildLists {
    pub a_start: Bits<20>,
    pub a_count: Bits<20>,
    pub b_start: Bits<20>,
    pub b_count: Bits<20>,
}

#[derive(Copy, Clone, PartialEq, Eq, Debug, LogicState)]
pub enum BinState {
    Idle,
    Load,
    Drain,
    Costs,
    Decide,
    Next,
    Check,
    ChildWait,
    ChildDecide,
    Pass,
    Return,
    Finish,
    PopWait,
    OutLeaf,
    OutHeader,
    OutTile,
    OutA,
    OutB,
    Done,
}

/// A cell's pass: `ceil(max(a, b) / 2)` list words per object and clock,
/// and what the split rule charges for it, `binning_cost::cell_cycles`.
/// Combinational, and a block of its own: in the unit's one combinational
/// block, a multiplexer read back through a continuous assignment would
/// look like a loop to Verilator.
#[derive(LogicBlock)]
struct PassLength {
    pub a_count: Signal<In, Bits<20>>,
    pub b_count: Signal<In, Bits<20>>,
    pub words: Signal<Out, Bits<20>>,
    pub classify: Signal<Out, Bits<48>>,
    classify_base: Constant<Bits<48>>,
    count_up_a: Signal<Local, Bits<20>>,
    count_up_b: Signal<Local, Bits<20>>,
    words_a: Signal<Local, Bits<20>>,
    words_b: Signal<Local, Bits<20>>,
}

impl crate::unit::Unit for PassLength {}

impl Default for PassLength {
    fn default() -> Self {
        PassLength {
            a_count: Default::default(),
            b_count: Default::default(),
            words: Default::default(),
            classify: Default::default(),
            classify_base: Constant::new(Bits::<48>::from(CLASSIFY_BASE)),
            count_up_a: Default::default(),
            count_up_b: Default::default(),
            words_a: Default::default(),
            words_b: Default::default(),
        }
    }
}

impl Logic for PassLength {
    #[hdl_gen]
    fn update(&mut self) {
        // A right shift stands alone in its statement: the emitted Verilog
        // then needs no width casts.
        self.count_up_a.next = self.a_count.val() + 1;
        self.count_up_b.next = self.b_count.val() + 1;
        self.words_a.next = self.count_up_a.val() >> 1;
        self.words_b.next = self.count_up_b.val() >> 1;
        self.words.next = self.words_a.val();
        if self.words_b.val() > self.words_a.val() {
            self.words.next = self.words_b.val();
        }
        self.classify.next = bit_cast::<48, 20>(self.words.val()) + self.classify_base.val();
    }
}

#[derive(LogicBlock)]
pub struct BinningUnit<const G: usize, const V: usize, const N: usize, const T: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: idle, every memory empty.
    pub reset: Signal<In, Bit>,
    /// One clock high while idle: a run begins with the root cell below,
    /// held until `done`.
    pub start: Signal<In, Bit>,
    pub root_x: Signal<In, Bits<G>>,
    pub root_y: Signal<In, Bits<G>>,
    pub root_z: Signal<In, Bits<G>>,
    pub root_level: Signal<In, Bits<6>>,
    /// With `max_leaf_enable`, cells above this level are always split.
    pub max_leaf_level: Signal<In, Bits<6>>,
    pub max_leaf_enable: Signal<In, Bit>,
    // Triangles in (valid/ready): A's and B's, any order, the last marked.
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_last: Signal<In, Bit>,
    /// 0: object A, 1: object B.
    pub in_object: Signal<In, Bit>,
    /// The vertices, `x0 y0 z0 x1 … z2` from bit 0 up, G bits each.
    pub in_vertices: Signal<In, Bits<T>>,
    // Leaves out (valid/ready): a header, then the A indices, then the B ones.
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_header: Signal<Out, Bit>,
    pub out_object: Signal<Out, Bit>,
    /// An entry: the triangle's index in its object's stream (from 0).
    pub out_index: Signal<Out, Bits<INDEX_BITS>>,
    /// An entry: the triangle's vertices as they were streamed in (read
    /// from the object's first lane's triangle memory, idle while leaves
    /// stream out), so the collision system needs no copy of its own.
    pub out_vertices: Signal<Out, Bits<T>>,
    /// A header: the leaf's cell and its arrays' sizes.
    pub out_x: Signal<Out, Bits<G>>,
    pub out_y: Signal<Out, Bits<G>>,
    pub out_z: Signal<Out, Bits<G>>,
    pub out_level: Signal<Out, Bits<6>>,
    pub out_count_a: Signal<Out, Bits<COUNT_BITS>>,
    pub out_count_b: Signal<Out, Bits<COUNT_BITS>>,
    /// A header: the leaf's number in stream order, from 0 (the tiles of
    /// a leaf share it).
    pub out_leaf_number: Signal<Out, Bits<LEAF_ADDRESS_BITS>>,
    /// Binning is over (the leaves are being streamed out, or are out).
    pub binned: Signal<Out, Bit>,
    /// Every leaf is out.
    pub done: Signal<Out, Bit>,
    /// A memory was too small for the run (sticky until the next start):
    /// a triangle past `triangles`, a list word past `list_words` or a
    /// leaf past `leaves` was dropped. The leaves would be wrong, so none
    /// is streamed: `binned` and `done` come at once.
    pub overflow: Signal<Out, Bit>,
    overflow_q: DFF<Bit>,
    triangle_limit: Constant<Bits<20>>,
    list_limit: Constant<Bits<LIST_ADDRESS_BITS>>,
    leaf_limit: Constant<Bits<LEAF_ADDRESS_BITS>>,
    state: DFF<BinState>,
    counter: DFF<Bits<20>>,
    loaded_a: DFF<Bits<20>>,
    loaded_b: DFF<Bits<20>>,
    cur: DFF<CellLists>,
    cur_slack: DFF<Bits<2>>,
    cur_classify: DFF<Bits<48>>,
    cur_leaf_cost: DFF<Bits<48>>,
    children_cost: DFF<Bits<48>>,
    returned: DFF<Bits<48>>,
    top_frame: DFF<Frame>,
    frame_count: DFF<Bits<7>>,
    frames: SimpleDualPortRam<Frame, FRAME_ADDRESS_BITS>,
    children: SimpleDualPortRam<ChildLists, CHILD_ADDRESS_BITS>,
    leaf_count: DFF<Bits<LEAF_ADDRESS_BITS>>,
    leaves: SimpleDualPortRam<CellLists, LEAF_ADDRESS_BITS>,
    cost: LeafCost,
    triangles: [SimpleDualPortRam<Bits<T>, INDEX_BITS>; 4],
    list_a: [SimpleDualPortRam<Bits<LIST_WORD_BITS>, LIST_ADDRESS_BITS>; 8],
    list_b: [SimpleDualPortRam<Bits<LIST_WORD_BITS>, LIST_ADDRESS_BITS>; 8],
    packer_a: [ListPacker; 8],
    packer_b: [ListPacker; 8],
    /// The memory the lists being read are in (the selects of the list words).
    read_memory_a: DFF<Bits<4>>,
    read_memory_b: DFF<Bits<4>>,
    // Lanes A0, A1, B0, B1: stage 1 (index), stage 2 (vertices).
    s1_root: DFF<Bit>,
    s1_valid: [DFF<Bit>; 4],
    /// The root pass's index per object (lanes A0 and B0 take the stream).
    s1_root_index: [DFF<Bits<INDEX_BITS>>; 2],
    s2_valid: [DFF<Bit>; 4],
    s2_index: [DFF<Bits<INDEX_BITS>>; 4],
    lane: [ClassifyLane<G, V, N, T>; 4],
    // Output.
    out_valid_q: DFF<Bit>,
    out_header_q: DFF<Bit>,
    out_object_q: DFF<Bit>,
    out_index_q: DFF<Bits<INDEX_BITS>>,
    out_leaf: DFF<Bits<LEAF_ADDRESS_BITS>>,
    out_cell: DFF<CellLists>,
    /// The leaf's tile being streamed: its first A and B entries (a leaf
    /// larger than the system's memory depth goes out as tiles of at most
    /// the depth in triangles per object, every A tile with every B tile).
    tile_a: DFF<Bits<20>>,
    tile_b: DFF<Bits<20>>,
    /// The system's memory depth.
    tile_depth: Constant<Bits<20>>,
    // Constants: octant numbers, the identity list, a cell's pass base cost.
    octant_id: [Constant<Bits<4>>; 8],
    identity: Constant<Bits<4>>,
    classify_base: Constant<Bits<48>>,
    pass_length: PassLength,
    // Combinational.
    advance_out: Signal<Local, Bit>,
    word_a: Signal<Local, Bits<LIST_WORD_BITS>>,
    word_b: Signal<Local, Bits<LIST_WORD_BITS>>,
    index1: [Signal<Local, Bits<INDEX_BITS>>; 4],
    accept: Signal<Local, Bit>,
    pass_words: Signal<Local, Bits<20>>,
    slot_up: Signal<Local, Bits<20>>,
    next_word: Signal<Local, Bits<20>>,
    classify: Signal<Local, Bits<48>>,
    both: Signal<Local, Bit>,
    forced: Signal<Local, Bit>,
    improving: Signal<Local, Bit>,
    half: Signal<Local, Bits<32>>,
    child_data: Signal<Local, ChildLists>,
    slot: Signal<Local, Bits<INDEX_BITS>>,
    entry_a: Signal<Local, Bits<INDEX_BITS>>,
    entry_b: Signal<Local, Bits<INDEX_BITS>>,
    /// The current tile: its entries past its first, capped at the depth, and the
    /// entry after its last.
    rest_a: Signal<Local, Bits<20>>,
    rest_b: Signal<Local, Bits<20>>,
    tile_count_a: Signal<Local, Bits<20>>,
    tile_count_b: Signal<Local, Bits<20>>,
    tile_end_a: Signal<Local, Bits<20>>,
    tile_end_b: Signal<Local, Bits<20>>,
    /// The first word of the current tile's lists.
    tile_word_a: Signal<Local, Bits<20>>,
    tile_word_b: Signal<Local, Bits<20>>,
}

impl<const G: usize, const V: usize, const N: usize, const T: usize> crate::unit::Unit
    for BinningUnit<G, V, N, T>
{
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            overflow_q,
            state,
            counter,
            loaded_a,
            loaded_b,
            cur,
            cur_slack,
            cur_classify,
            cur_leaf_cost,
            children_cost,
            returned,
            top_frame,
            frame_count,
            frames,
            children,
            leaf_count,
            leaves,
            cost,
            triangles,
            list_a,
            list_b,
            packer_a,
            packer_b,
            read_memory_a,
            read_memory_b,
            s1_root,
            s1_valid,
            s1_root_index,
            s2_valid,
            s2_index,
            lane,
            out_valid_q,
            out_header_q,
            out_object_q,
            out_index_q,
            out_leaf,
            out_cell,
            tile_a,
            tile_b,
            pass_length
        );
    }
}

impl<const G: usize, const V: usize, const N: usize, const T: usize> BinningUnit<G, V, N, T> {
    /// A unit for up to `triangles` per object, `list_words` words per list
    /// memory and `leaves` leaf descriptors.
    pub fn new(triangles: usize, list_words: usize, leaves: usize) -> Self {
        assert!(
            V == crate::octree::value_bits(G) && N == AXES * V && T == 9 * G && G <= 32,
            "binning unit for G = {G}"
        );
        BinningUnit {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            root_x: Default::default(),
            root_y: Default::default(),
            root_z: Default::default(),
            root_level: Default::default(),
            max_leaf_level: Default::default(),
            max_leaf_enable: Default::default(),
            in_valid: Default::default(),
            in_ready: Default::default(),
            in_last: Default::default(),
            in_object: Default::default(),
            in_vertices: Default::default(),
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
            out_leaf_number: Default::default(),
            binned: Default::default(),
            done: Default::default(),
            overflow: Default::default(),
            overflow_q: Default::default(),
            triangle_limit: Constant::new(Bits::<20>::from(triangles as u64)),
            list_limit: Constant::new(Bits::<LIST_ADDRESS_BITS>::from(list_words as u64)),
            leaf_limit: Constant::new(Bits::<LEAF_ADDRESS_BITS>::from(leaves as u64)),
            state: Default::default(),
            counter: Default::default(),
            loaded_a: Default::default(),
            loaded_b: Default::default(),
            cur: Default::default(),
            cur_slack: Default::default(),
            cur_classify: Default::default(),
            cur_leaf_cost: Default::default(),
            children_cost: Default::default(),
            returned: Default::default(),
            top_frame: Default::default(),
            frame_count: Default::default(),
            frames: SimpleDualPortRam::new(1 << FRAME_ADDRESS_BITS),
            children: SimpleDualPortRam::new(1 << CHILD_ADDRESS_BITS),
            leaf_count: Default::default(),
            leaves: SimpleDualPortRam::new(leaves),
            cost: Default::default(),
            triangles: std::array::from_fn(|_| SimpleDualPortRam::new(triangles)),
            list_a: std::array::from_fn(|_| SimpleDualPortRam::new(list_words)),
            list_b: std::array::from_fn(|_| SimpleDualPortRam::new(list_words)),
            packer_a: Default::default(),
            packer_b: Default::default(),
            read_memory_a: Default::default(),
            read_memory_b: Default::default(),
            s1_root: Default::default(),
            s1_valid: Default::default(),
            s1_root_index: Default::default(),
            s2_valid: Default::default(),
            s2_index: Default::default(),
            lane: Default::default(),
            out_valid_q: Default::default(),
            out_header_q: Default::default(),
            out_object_q: Default::default(),
            out_index_q: Default::default(),
            out_leaf: Default::default(),
            out_cell: Default::default(),
            tile_a: Default::default(),
            tile_b: Default::default(),
            tile_depth: Constant::new(Bits::<20>::from(256u64)),
            octant_id: std::array::from_fn(|o| Constant::new(Bits::<4>::from(o as u64))),
            identity: Constant::new(Bits::<4>::from(IDENTITY_LIST as u64)),
            classify_base: Constant::new(Bits::<48>::from(CLASSIFY_BASE)),
            pass_length: Default::default(),
            advance_out: Default::default(),
            word_a: Default::default(),
            word_b: Default::default(),
            index1: Default::default(),
            accept: Default::default(),
            pass_words: Default::default(),
            slot_up: Default::default(),
            next_word: Default::default(),
            classify: Default::default(),
            both: Default::default(),
            forced: Default::default(),
            improving: Default::default(),
            half: Default::default(),
            child_data: Default::default(),
            slot: Default::default(),
            entry_a: Default::default(),
            entry_b: Default::default(),
            rest_a: Default::default(),
            rest_b: Default::default(),
            tile_count_a: Default::default(),
            tile_count_b: Default::default(),
            tile_end_a: Default::default(),
            tile_end_b: Default::default(),
            tile_word_a: Default::default(),
            tile_word_b: Default::default(),
        }
    }

    /// With a unit split rule for memory depth `2^log_depth` and
    /// `2^log_pipelines` pipelines (the default is the system's 256 and 2).
    pub fn with_system(mut self, log_depth: u32, log_pipelines: u32) -> Self {
        self.cost = LeafCost::new(log_depth, log_pipelines);
        self.tile_depth = Constant::new(Bits::<20>::from(1u64 << log_depth));
        self
    }
}

impl<const G: usize, const V: usize, const N: usize, const T: usize> Logic
    for BinningUnit<G, V, N, T>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            state,
            counter,
            loaded_a,
            loaded_b,
            cur,
            cur_slack,
            cur_classify,
            cur_leaf_cost,
            children_cost,
            returned,
            top_frame,
            frame_count,
            leaf_count,
            read_memory_a,
            read_memory_b,
            s1_root,
            overflow_q,
            out_valid_q,
            out_header_q,
            out_object_q,
            out_index_q,
            out_leaf,
            out_cell,
            tile_a,
            tile_b
        );
        clock!(self, clock, frames, children, leaves, cost);

        // ---- Defaults: no writes, no reads, no lane entry.
        self.frames.write_enable.next = false;
        self.frames.write_address.next = bit_cast::<6, 7>(self.frame_count.q.val() - 1);
        self.frames.write_data.next = self.top_frame.q.val();
        self.frames.read_enable.next = false;
        self.frames.read_address.next = bit_cast::<6, 7>(self.frame_count.q.val() - 2);
        self.children.write_enable.next = false;
        self.children.write_address.next = (bit_cast::<9, 7>(self.frame_count.q.val()) << 3)
            | bit_cast::<9, 20>(self.counter.q.val() & 7);
        // (A value in every state, so that the lists' word is no latch; it
        // is written only from Costs.)
        self.children.write_data.next.a_start = self.packer_a[0].start.val();
        self.children.write_data.next.a_count = self.packer_a[0].count.val();
        self.children.write_data.next.b_start = self.packer_b[0].start.val();
        self.children.write_data.next.b_count = self.packer_b[0].count.val();
        self.children.read_enable.next = false;
        self.children.read_address.next = (bit_cast::<9, 7>(self.frame_count.q.val() - 1) << 3)
            | bit_cast::<9, 4>(self.top_frame.q.val().octant & 7);
        self.leaves.write_enable.next = false;
        self.leaves.write_address.next = self.leaf_count.q.val();
        self.leaves.write_data.next = self.cur.q.val();
        self.leaves.read_enable.next = false;
        self.leaves.read_address.next = self.out_leaf.q.val();
        self.cost.a.next = self.cur.q.val().a_count;
        self.cost.b.next = self.cur.q.val().b_count;
        for o in 0..8 {
            self.list_a[o].clock.next = self.clock.val();
            self.list_b[o].clock.next = self.clock.val();
            self.packer_a[o].clock.next = self.clock.val();
            self.packer_b[o].clock.next = self.clock.val();
            self.packer_a[o].reset.next = self.reset.val();
            self.packer_b[o].reset.next = self.reset.val();
            self.packer_a[o].new_list.next = false;
            self.packer_b[o].new_list.next = false;
            self.packer_a[o].flush.next = false;
            self.packer_b[o].flush.next = false;
            self.list_a[o].write_enable.next = self.packer_a[o].write_enable.val();
            self.list_a[o].write_address.next = self.packer_a[o].write_address.val();
            self.list_a[o].write_data.next = self.packer_a[o].write_data.val();
            self.list_b[o].write_enable.next = self.packer_b[o].write_enable.val();
            self.list_b[o].write_address.next = self.packer_b[o].write_address.val();
            self.list_b[o].write_data.next = self.packer_b[o].write_data.val();
            self.list_a[o].read_enable.next = false;
            self.list_b[o].read_enable.next = false;
            self.list_a[o].read_address.next = self.cur.q.val().a_start + self.counter.q.val();
            self.list_b[o].read_address.next = self.cur.q.val().b_start + self.counter.q.val();
        }
        for o in 0..2 {
            self.s1_root_index[o].clock.next = self.clock.val();
            self.s1_root_index[o].d.next = self.s1_root_index[o].q.val();
        }
        for l in 0..4 {
            self.s1_valid[l].clock.next = self.clock.val();
            self.s2_valid[l].clock.next = self.clock.val();
            self.s2_index[l].clock.next = self.clock.val();
            self.s1_valid[l].d.next = false;
            self.triangles[l].clock.next = self.clock.val();
            self.triangles[l].write_enable.next = false;
            self.triangles[l].write_data.next = self.in_vertices.val();
            self.triangles[l].read_enable.next = true;
        }
        self.triangles[0].write_address.next = bit_cast::<INDEX_BITS, 20>(self.loaded_a.q.val());
        self.triangles[1].write_address.next = bit_cast::<INDEX_BITS, 20>(self.loaded_a.q.val());
        self.triangles[2].write_address.next = bit_cast::<INDEX_BITS, 20>(self.loaded_b.q.val());
        self.triangles[3].write_address.next = bit_cast::<INDEX_BITS, 20>(self.loaded_b.q.val());

        // ---- The list words being read, from the memory they are in.
        self.word_a.next = 0.into();
        self.word_b.next = 0.into();
        for o in 0..8 {
            if self.read_memory_a.q.val() == self.octant_id[o].val() {
                self.word_a.next = self.list_a[o].read_data.val();
            }
            if self.read_memory_b.q.val() == self.octant_id[o].val() {
                self.word_b.next = self.list_b[o].read_data.val();
            }
        }

        // ---- Lanes: index (the root's from the stream, else from the list
        // word), triangle memory, setup at the cell's corner, classifier.
        self.index1[0].next = self.word_a.val().get_bits::<INDEX_BITS>(0);
        self.index1[1].next = self.word_a.val().get_bits::<INDEX_BITS>(18);
        self.index1[2].next = self.word_b.val().get_bits::<INDEX_BITS>(0);
        self.index1[3].next = self.word_b.val().get_bits::<INDEX_BITS>(18);
        if self.s1_root.q.val() {
            self.index1[0].next = self.s1_root_index[0].q.val();
            self.index1[2].next = self.s1_root_index[1].q.val();
        }
        for l in 0..4 {
            self.triangles[l].read_address.next = self.index1[l].val();
            self.s2_valid[l].d.next = self.s1_valid[l].q.val();
            self.s2_index[l].d.next = self.index1[l].val();
            self.lane[l].clock.next = self.clock.val();
            self.lane[l].reset.next = self.reset.val();
            self.lane[l].in_valid.next = self.s2_valid[l].q.val();
            self.lane[l].in_index.next = self.s2_index[l].q.val();
            self.lane[l].in_vertices.next = self.triangles[l].read_data.val();
            self.lane[l].in_corner_x.next = bit_cast::<G, 32>(self.cur.q.val().x);
            self.lane[l].in_corner_y.next = bit_cast::<G, 32>(self.cur.q.val().y);
            self.lane[l].in_corner_z.next = bit_cast::<G, 32>(self.cur.q.val().z);
            self.lane[l].in_level.next = self.cur.q.val().level;
        }
        // The masks into the packers: lane 0 before lane 1.
        for o in 0..8 {
            self.packer_a[o].in0_valid.next =
                self.lane[0].out_valid.val() & self.lane[0].out_mask.val().get_bit(o);
            self.packer_a[o].in0_index.next = self.lane[0].out_index.val();
            self.packer_a[o].in1_valid.next =
                self.lane[1].out_valid.val() & self.lane[1].out_mask.val().get_bit(o);
            self.packer_a[o].in1_index.next = self.lane[1].out_index.val();
            self.packer_b[o].in0_valid.next =
                self.lane[2].out_valid.val() & self.lane[2].out_mask.val().get_bit(o);
            self.packer_b[o].in0_index.next = self.lane[2].out_index.val();
            self.packer_b[o].in1_valid.next =
                self.lane[3].out_valid.val() & self.lane[3].out_mask.val().get_bit(o);
            self.packer_b[o].in1_index.next = self.lane[3].out_index.val();
        }

        // ---- The split rule's quantities for the current cell.
        self.pass_length.a_count.next = self.cur.q.val().a_count;
        self.pass_length.b_count.next = self.cur.q.val().b_count;
        self.pass_words.next = self.pass_length.words.val();
        self.classify.next = self.pass_length.classify.val();
        // The word holding the output's next index.
        self.slot_up.next = self.counter.q.val() + 1;
        self.next_word.next = self.slot_up.val() >> 1;
        self.both.next = (self.cur.q.val().a_count != 0) & (self.cur.q.val().b_count != 0);
        self.forced.next =
            self.max_leaf_enable.val() & (self.cur.q.val().level > self.max_leaf_level.val());
        self.improving.next =
            self.forced.val() | (self.children_cost.q.val() < self.cur_leaf_cost.q.val());
        self.half.next = bits::<32>(1) << (self.top_frame.q.val().level - 1);
        self.child_data.next = self.children.read_data.val();

        // ---- Output stream (stalls while a word waits).
        self.advance_out.next = !self.out_valid_q.q.val() | self.out_ready.val();
        self.out_valid.next = self.out_valid_q.q.val();
        self.out_header.next = self.out_header_q.q.val();
        self.out_object.next = self.out_object_q.q.val();
        self.out_index.next = self.out_index_q.q.val();
        self.out_vertices.next = self.triangles[0].read_data.val();
        if self.out_object_q.q.val() {
            self.out_vertices.next = self.triangles[2].read_data.val();
        }
        self.out_x.next = bit_cast::<G, 32>(self.out_cell.q.val().x);
        self.out_y.next = bit_cast::<G, 32>(self.out_cell.q.val().y);
        self.out_z.next = bit_cast::<G, 32>(self.out_cell.q.val().z);
        self.out_level.next = self.out_cell.q.val().level;
        // The tile's sizes: min(depth, count - first).
        self.rest_a.next = self.out_cell.q.val().a_count - self.tile_a.q.val();
        self.rest_b.next = self.out_cell.q.val().b_count - self.tile_b.q.val();
        self.tile_count_a.next = self.rest_a.val();
        if self.rest_a.val() > self.tile_depth.val() {
            self.tile_count_a.next = self.tile_depth.val();
        }
        self.tile_count_b.next = self.rest_b.val();
        if self.rest_b.val() > self.tile_depth.val() {
            self.tile_count_b.next = self.tile_depth.val();
        }
        self.tile_end_a.next = self.tile_a.q.val() + self.tile_count_a.val();
        self.tile_end_b.next = self.tile_b.q.val() + self.tile_count_b.val();
        self.tile_word_a.next = self.tile_a.q.val() >> 1;
        self.tile_word_b.next = self.tile_b.q.val() >> 1;
        self.out_leaf_number.next = self.out_leaf.q.val();
        self.out_count_a.next = self.tile_count_a.val();
        self.out_count_b.next = self.tile_count_b.val();
        self.slot.next = bit_cast::<INDEX_BITS, 20>(self.counter.q.val());
        self.entry_a.next = self.word_a.val().get_bits::<INDEX_BITS>(0);
        if self.slot.val().get_bit(0) {
            self.entry_a.next = self.word_a.val().get_bits::<INDEX_BITS>(18);
        }
        if self.out_cell.q.val().a_memory == self.identity.val() {
            self.entry_a.next = self.slot.val();
        }
        self.entry_b.next = self.word_b.val().get_bits::<INDEX_BITS>(0);
        if self.slot.val().get_bit(0) {
            self.entry_b.next = self.word_b.val().get_bits::<INDEX_BITS>(18);
        }
        if self.out_cell.q.val().b_memory == self.identity.val() {
            self.entry_b.next = self.slot.val();
        }

        self.in_ready.next = self.state.q.val() == BinState::Load;
        self.accept.next = self.in_valid.val() & self.in_ready.val();
        self.binned.next = (self.state.q.val() == BinState::OutLeaf)
            | (self.state.q.val() == BinState::OutHeader)
            | (self.state.q.val() == BinState::OutTile)
            | (self.state.q.val() == BinState::OutA)
            | (self.state.q.val() == BinState::OutB)
            | (self.state.q.val() == BinState::Done);
        self.done.next = self.state.q.val() == BinState::Done;
        // Overflow: a count past its memory (a write past the end happened),
        // a list memory written past its end (its packer's registered count
        // of words: the packers' combinational outputs feed back into this
        // block, which Icarus evaluates as a loop).
        self.overflow.next = self.overflow_q.q.val();
        if (self.loaded_a.q.val() > self.triangle_limit.val())
            | (self.loaded_b.q.val() > self.triangle_limit.val())
            | (self.leaf_count.q.val() > self.leaf_limit.val())
        {
            self.overflow_q.d.next = true;
        }
        for o in 0..8 {
            if (self.packer_a[o].used.val() > self.list_limit.val())
                | (self.packer_b[o].used.val() > self.list_limit.val())
            {
                self.overflow_q.d.next = true;
            }
        }

        match self.state.q.val() {
            BinState::Idle => {
                if self.start.val() {
                    self.overflow_q.d.next = false;
                    // The root: its lists are the streams themselves.
                    self.cur.d.next.x = bit_cast::<32, G>(self.root_x.val());
                    self.cur.d.next.y = bit_cast::<32, G>(self.root_y.val());
                    self.cur.d.next.z = bit_cast::<32, G>(self.root_z.val());
                    self.cur.d.next.level = self.root_level.val();
                    self.cur.d.next.a_memory = self.identity.val();
                    self.cur.d.next.b_memory = self.identity.val();
                    self.cur.d.next.a_start = 0.into();
                    self.cur.d.next.b_start = 0.into();
                    self.cur.d.next.a_count = 0.into();
                    self.cur.d.next.b_count = 0.into();
                    self.cur_slack.d.next = 2.into();
                    // cell_cycles(0, 0): the root is classified as it streams in.
                    self.cur_classify.d.next = self.classify_base.val();
                    self.loaded_a.d.next = 0.into();
                    self.loaded_b.d.next = 0.into();
                    self.frame_count.d.next = 0.into();
                    self.leaf_count.d.next = 0.into();
                    self.s1_root.d.next = true;
                    for o in 0..8 {
                        self.packer_a[o].new_list.next = true;
                        self.packer_b[o].new_list.next = true;
                    }
                    self.state.d.next = BinState::Load;
                }
            }
            BinState::Load => {
                if self.accept.val() {
                    if self.in_object.val() {
                        self.triangles[2].write_enable.next = true;
                        self.triangles[3].write_enable.next = true;
                        self.s1_valid[2].d.next = true;
                        self.s1_root_index[1].d.next =
                            bit_cast::<INDEX_BITS, 20>(self.loaded_b.q.val());
                        self.loaded_b.d.next = self.loaded_b.q.val() + 1;
                    } else {
                        self.triangles[0].write_enable.next = true;
                        self.triangles[1].write_enable.next = true;
                        self.s1_valid[0].d.next = true;
                        self.s1_root_index[0].d.next =
                            bit_cast::<INDEX_BITS, 20>(self.loaded_a.q.val());
                        self.loaded_a.d.next = self.loaded_a.q.val() + 1;
                    }
                    if self.in_last.val() {
                        self.counter.d.next = 0.into();
                        self.state.d.next = BinState::Drain;
                    }
                }
            }
            BinState::Pass => {
                // Word `counter` of each list; a slot past the count is empty.
                for o in 0..8 {
                    self.list_a[o].read_enable.next = true;
                    self.list_b[o].read_enable.next = true;
                }
                self.s1_valid[0].d.next = (self.counter.q.val() << 1) < self.cur.q.val().a_count;
                self.s1_valid[1].d.next =
                    ((self.counter.q.val() << 1) + 1) < self.cur.q.val().a_count;
                self.s1_valid[2].d.next = (self.counter.q.val() << 1) < self.cur.q.val().b_count;
                self.s1_valid[3].d.next =
                    ((self.counter.q.val() << 1) + 1) < self.cur.q.val().b_count;
                self.counter.d.next = self.counter.q.val() + 1;
                if self.counter.q.val() + 1 == self.pass_words.val() {
                    self.counter.d.next = 0.into();
                    self.state.d.next = BinState::Drain;
                }
            }
            BinState::Drain => {
                self.counter.d.next = self.counter.q.val() + 1;
                if self.counter.q.val() == 12 {
                    // The last masks were written: flush half words.
                    for o in 0..8 {
                        self.packer_a[o].flush.next = true;
                        self.packer_b[o].flush.next = true;
                    }
                    self.s1_root.d.next = false;
                    self.cur.d.next.a_count = self.loaded_a.q.val();
                    self.cur.d.next.b_count = self.loaded_b.q.val();
                    if self.cur.q.val().a_memory != self.identity.val() {
                        self.cur.d.next.a_count = self.cur.q.val().a_count;
                        self.cur.d.next.b_count = self.cur.q.val().b_count;
                    }
                    self.counter.d.next = 0.into();
                    self.state.d.next = BinState::Costs;
                }
            }
            BinState::Costs => {
                // Queries: children 0..7, then the cell (8); results 4 clocks later.
                for o in 0..8 {
                    if bit_cast::<4, 20>(self.counter.q.val()) == self.octant_id[o].val() {
                        self.cost.a.next = self.packer_a[o].count.val();
                        self.cost.b.next = self.packer_b[o].count.val();
                        self.children.write_data.next.a_start = self.packer_a[o].start.val();
                        self.children.write_data.next.a_count = self.packer_a[o].count.val();
                        self.children.write_data.next.b_start = self.packer_b[o].start.val();
                        self.children.write_data.next.b_count = self.packer_b[o].count.val();
                    }
                }
                if self.counter.q.val() < 8 {
                    self.children.write_enable.next = true;
                }
                if self.counter.q.val() == 0 {
                    self.children_cost.d.next = 0.into();
                }
                if (self.counter.q.val() >= 4) & (self.counter.q.val() < 12) {
                    self.children_cost.d.next = self.children_cost.q.val() + self.cost.cost.val();
                }
                self.counter.d.next = self.counter.q.val() + 1;
                if self.counter.q.val() == 12 {
                    self.cur_leaf_cost.d.next = self.cost.cost.val();
                    self.state.d.next = BinState::Decide;
                }
            }
            BinState::Decide => {
                if !self.both.val() {
                    self.returned.d.next = 0.into();
                    self.state.d.next = BinState::Return;
                } else if (self.cur.q.val().level == 0)
                    | (!self.improving.val() & (self.cur_slack.q.val() == 0))
                {
                    self.leaves.write_enable.next = true;
                    self.leaf_count.d.next = self.leaf_count.q.val() + 1;
                    self.returned.d.next = self.cur_leaf_cost.q.val() + self.cur_classify.q.val();
                    self.state.d.next = BinState::Return;
                } else {
                    // Push: the old top into the memory, the cell on top.
                    if self.frame_count.q.val() != 0 {
                        self.frames.write_enable.next = true;
                    }
                    self.top_frame.d.next.x = self.cur.q.val().x;
                    self.top_frame.d.next.y = self.cur.q.val().y;
                    self.top_frame.d.next.z = self.cur.q.val().z;
                    self.top_frame.d.next.level = self.cur.q.val().level;
                    self.top_frame.d.next.a_memory = self.cur.q.val().a_memory;
                    self.top_frame.d.next.a_start = self.cur.q.val().a_start;
                    self.top_frame.d.next.a_count = self.cur.q.val().a_count;
                    self.top_frame.d.next.b_memory = self.cur.q.val().b_memory;
                    self.top_frame.d.next.b_start = self.cur.q.val().b_start;
                    self.top_frame.d.next.b_count = self.cur.q.val().b_count;
                    self.top_frame.d.next.leaf_cost = self.cur_leaf_cost.q.val();
                    self.top_frame.d.next.classify = self.cur_classify.q.val();
                    self.top_frame.d.next.subtree = 0.into();
                    self.top_frame.d.next.slack_next = 2.into();
                    if !self.improving.val() {
                        self.top_frame.d.next.slack_next = self.cur_slack.q.val() - 1;
                    }
                    self.top_frame.d.next.forced = self.forced.val();
                    self.top_frame.d.next.leaf_mark = self.leaf_count.q.val();
                    self.top_frame.d.next.octant = 0.into();
                    self.frame_count.d.next = self.frame_count.q.val() + 1;
                    self.state.d.next = BinState::Next;
                }
            }
            BinState::Next => {
                self.children.read_enable.next = true;
                self.state.d.next = BinState::Check;
            }
            BinState::Check => {
                // The child: its cell, its lists in the octant's memories.
                self.cur.d.next.x = self.top_frame.q.val().x;
                self.cur.d.next.y = self.top_frame.q.val().y;
                self.cur.d.next.z = self.top_frame.q.val().z;
                if self.top_frame.q.val().octant.get_bit(0) {
                    self.cur.d.next.x = self.top_frame.q.val().x + self.half.val();
                }
                if self.top_frame.q.val().octant.get_bit(1) {
                    self.cur.d.next.y = self.top_frame.q.val().y + self.half.val();
                }
                if self.top_frame.q.val().octant.get_bit(2) {
                    self.cur.d.next.z = self.top_frame.q.val().z + self.half.val();
                }
                self.cur.d.next.level = self.top_frame.q.val().level - 1;
                self.cur.d.next.a_memory = self.top_frame.q.val().octant;
                self.cur.d.next.b_memory = self.top_frame.q.val().octant;
                self.cur.d.next.a_start = self.child_data.val().a_start;
                self.cur.d.next.a_count = self.child_data.val().a_count;
                self.cur.d.next.b_start = self.child_data.val().b_start;
                self.cur.d.next.b_count = self.child_data.val().b_count;
                self.read_memory_a.d.next = self.top_frame.q.val().octant;
                self.read_memory_b.d.next = self.top_frame.q.val().octant;
                self.cur_slack.d.next = self.top_frame.q.val().slack_next;
                self.cost.a.next = self.child_data.val().a_count;
                self.cost.b.next = self.child_data.val().b_count;
                self.counter.d.next = 0.into();
                if (self.child_data.val().a_count == 0) | (self.child_data.val().b_count == 0) {
                    self.returned.d.next = 0.into();
                    self.state.d.next = BinState::Return;
                } else {
                    self.state.d.next = BinState::ChildWait;
                }
            }
            BinState::ChildWait => {
                self.counter.d.next = self.counter.q.val() + 1;
                if self.counter.q.val() == 2 {
                    self.state.d.next = BinState::ChildDecide;
                }
            }
            BinState::ChildDecide => {
                self.cur_classify.d.next = self.classify.val();
                self.cur_leaf_cost.d.next = self.cost.cost.val();
                self.counter.d.next = 0.into();
                if (self.cur.q.val().level == 0)
                    | (!self.forced.val()
                        & (self.cost.cost.val()
                            <= bit_cast::<48, 20>(self.cur.q.val().a_count)
                                + bit_cast::<48, 20>(self.cur.q.val().b_count)
                                + 1
                                + self.classify.val()))
                {
                    self.leaves.write_enable.next = true;
                    self.leaf_count.d.next = self.leaf_count.q.val() + 1;
                    self.returned.d.next = self.cost.cost.val();
                    self.state.d.next = BinState::Return;
                } else {
                    for o in 0..8 {
                        self.packer_a[o].new_list.next = true;
                        self.packer_b[o].new_list.next = true;
                    }
                    self.state.d.next = BinState::Pass;
                }
            }
            BinState::Return => {
                if self.frame_count.q.val() == 0 {
                    self.counter.d.next = 0.into();
                    self.out_leaf.d.next = 0.into();
                    self.state.d.next = BinState::OutLeaf;
                    // A memory overflowed: the leaves are wrong, none is
                    // streamed (the root's own leaf may have been the last
                    // write, not yet in `overflow_q`).
                    if self.overflow_q.q.val() | (self.leaf_count.q.val() > self.leaf_limit.val()) {
                        self.state.d.next = BinState::Done;
                    }
                } else {
                    self.top_frame.d.next.subtree =
                        self.top_frame.q.val().subtree + self.returned.q.val();
                    self.top_frame.d.next.octant = self.top_frame.q.val().octant + 1;
                    if self.top_frame.q.val().octant == 7 {
                        self.state.d.next = BinState::Finish;
                    } else {
                        self.state.d.next = BinState::Next;
                    }
                }
            }
            BinState::Finish => {
                if !self.top_frame.q.val().forced
                    & (self.top_frame.q.val().subtree >= self.top_frame.q.val().leaf_cost)
                {
                    // The subtree did not pay: its leaves are dropped, the cell is one.
                    self.leaves.write_enable.next = true;
                    self.leaves.write_address.next = self.top_frame.q.val().leaf_mark;
                    self.leaves.write_data.next.x = self.top_frame.q.val().x;
                    self.leaves.write_data.next.y = self.top_frame.q.val().y;
                    self.leaves.write_data.next.z = self.top_frame.q.val().z;
                    self.leaves.write_data.next.level = self.top_frame.q.val().level;
                    self.leaves.write_data.next.a_memory = self.top_frame.q.val().a_memory;
                    self.leaves.write_data.next.a_start = self.top_frame.q.val().a_start;
                    self.leaves.write_data.next.a_count = self.top_frame.q.val().a_count;
                    self.leaves.write_data.next.b_memory = self.top_frame.q.val().b_memory;
                    self.leaves.write_data.next.b_start = self.top_frame.q.val().b_start;
                    self.leaves.write_data.next.b_count = self.top_frame.q.val().b_count;
                    self.leaf_count.d.next = self.top_frame.q.val().leaf_mark + 1;
                    self.returned.d.next =
                        self.top_frame.q.val().leaf_cost + self.top_frame.q.val().classify;
                } else {
                    self.returned.d.next =
                        self.top_frame.q.val().subtree + self.top_frame.q.val().classify;
                }
                // Pop: the frame below comes back from the memory.
                self.frames.read_enable.next = true;
                self.frame_count.d.next = self.frame_count.q.val() - 1;
                self.state.d.next = BinState::PopWait;
            }
            BinState::PopWait => {
                self.top_frame.d.next = self.frames.read_data.val();
                self.state.d.next = BinState::Return;
            }
            BinState::OutLeaf => {
                self.triangles[0].read_enable.next = false;
                self.triangles[2].read_enable.next = false;
                if self.advance_out.val() {
                    self.out_valid_q.d.next = false;
                    if self.out_leaf.q.val() == self.leaf_count.q.val() {
                        self.state.d.next = BinState::Done;
                    } else {
                        self.leaves.read_enable.next = true;
                        self.state.d.next = BinState::OutHeader;
                    }
                }
            }
            BinState::OutHeader => {
                self.triangles[0].read_enable.next = false;
                self.triangles[2].read_enable.next = false;
                if self.advance_out.val() {
                    self.out_cell.d.next = self.leaves.read_data.val();
                    self.out_valid_q.d.next = true;
                    self.out_header_q.d.next = true;
                    self.read_memory_a.d.next = self.leaves.read_data.val().a_memory;
                    self.read_memory_b.d.next = self.leaves.read_data.val().b_memory;
                    // The first word of A's list.
                    for o in 0..8 {
                        self.list_a[o].read_enable.next = true;
                        self.list_a[o].read_address.next = self.leaves.read_data.val().a_start;
                    }
                    self.counter.d.next = 0.into();
                    self.tile_a.d.next = 0.into();
                    self.tile_b.d.next = 0.into();
                    self.state.d.next = BinState::OutA;
                }
            }
            BinState::OutTile => {
                // The next tile of the same leaf: its header (the tile
                // registers already hold its first entries), then its A list.
                self.triangles[0].read_enable.next = false;
                self.triangles[2].read_enable.next = false;
                if self.advance_out.val() {
                    self.out_valid_q.d.next = true;
                    self.out_header_q.d.next = true;
                    for o in 0..8 {
                        self.list_a[o].read_enable.next = true;
                        self.list_a[o].read_address.next =
                            self.out_cell.q.val().a_start + self.tile_word_a.val();
                    }
                    self.counter.d.next = self.tile_a.q.val();
                    self.state.d.next = BinState::OutA;
                }
            }
            BinState::OutA => {
                // The entry's vertices come out beside its index (a held
                // read keeps them while the stream stalls).
                self.triangles[0].read_enable.next = self.advance_out.val();
                self.triangles[0].read_address.next = self.entry_a.val();
                self.triangles[2].read_enable.next = false;
                if self.advance_out.val() {
                    self.out_valid_q.d.next = true;
                    self.out_header_q.d.next = false;
                    self.out_object_q.d.next = false;
                    self.out_index_q.d.next = self.entry_a.val();
                    self.counter.d.next = self.counter.q.val() + 1;
                    for o in 0..8 {
                        self.list_a[o].read_enable.next = true;
                        self.list_a[o].read_address.next =
                            self.out_cell.q.val().a_start + self.next_word.val();
                    }
                    if self.counter.q.val() + 1 == self.tile_end_a.val() {
                        for o in 0..8 {
                            self.list_b[o].read_enable.next = true;
                            self.list_b[o].read_address.next =
                                self.out_cell.q.val().b_start + self.tile_word_b.val();
                        }
                        self.counter.d.next = self.tile_b.q.val();
                        self.state.d.next = BinState::OutB;
                    }
                }
            }
            BinState::OutB => {
                self.triangles[0].read_enable.next = false;
                self.triangles[2].read_enable.next = self.advance_out.val();
                self.triangles[2].read_address.next = self.entry_b.val();
                if self.advance_out.val() {
                    self.out_valid_q.d.next = true;
                    self.out_header_q.d.next = false;
                    self.out_object_q.d.next = true;
                    self.out_index_q.d.next = self.entry_b.val();
                    self.counter.d.next = self.counter.q.val() + 1;
                    for o in 0..8 {
                        self.list_b[o].read_enable.next = true;
                        self.list_b[o].read_address.next =
                            self.out_cell.q.val().b_start + self.next_word.val();
                    }
                    if self.counter.q.val() + 1 == self.tile_end_b.val() {
                        if self.tile_end_b.val() != self.out_cell.q.val().b_count {
                            // The next B tile with the same A tile.
                            self.tile_b.d.next = self.tile_end_b.val();
                            self.state.d.next = BinState::OutTile;
                        } else if self.tile_end_a.val() != self.out_cell.q.val().a_count {
                            // The next A tile, with B from its first tile.
                            self.tile_a.d.next = self.tile_end_a.val();
                            self.tile_b.d.next = 0.into();
                            self.state.d.next = BinState::OutTile;
                        } else {
                            self.out_leaf.d.next = self.out_leaf.q.val() + 1;
                            self.state.d.next = BinState::OutLeaf;
                        }
                    }
                }
            }
            BinState::Done => {
                self.triangles[0].read_enable.next = false;
                self.triangles[2].read_enable.next = false;
                if self.advance_out.val() {
                    self.out_valid_q.d.next = false;
                }
            }
        }
        if self.reset.val() {
            self.state.d.next = BinState::Idle;
            self.out_valid_q.d.next = false;
            self.s1_root.d.next = false;
            for l in 0..4 {
                self.s1_valid[l].d.next = false;
            }
        }
    }
}
