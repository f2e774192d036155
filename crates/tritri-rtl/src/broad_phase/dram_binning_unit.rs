//! The controller of the broad phase's binning with every list in external
//! memory: it walks the octree depth first, runs one pass of the list pass
//! unit ([`super::list_pass`]) per cell it splits, decides the split rule
//! from the children's counts, and sends each leaf on as it is decided.
//! How it bins, and what each step costs in clocks, is the clock-exact
//! model's documentation ([`super::dram_binning_machine`]); this is that
//! controller in rust-hdl, and the co-simulation holds it to the model's
//! leaves, clocks and memory.
//!
//! ```text
//!  root lists (inputs) ─► current cell ─► leaf cost ─► decide ─┬─► leaf out (or waiting, under a tried split)
//!        ▲                                                     └─► list pass ─► children's counts
//!        │                                                                        │ 8 leaf costs, 8 writes
//!  children memory (8 places per frame) ◄──────────────────────────────────────────┘
//!  frames (top in registers, the rest in block RAM): cell, costs, tried, arena top, children left
//! ```
//!
//! Where the model pushes a visit per child, the unit keeps a frame per
//! split cell and the places of its eight children's lists in a children
//! memory beside it, with a mask of the children that hold both objects;
//! the next child to visit is the lowest octant left in the mask, which is
//! the model's order (it pushes octant 7 first). The children's places are
//! written while their costs are queried, so a split costs no clock more.
//!
//! The leaf cost takes 20-bit counts ([`super::leaf_cost::COUNT_BITS`]);
//! the lists' counts are 32 bits.

use super::dram_split_terms::SplitTerms;
use super::leaf_cost::{LeafCost, COST_BITS, COUNT_BITS};
use super::list_entry::ENTRY_BYTES;
use super::list_pass::{ListPass, CHILDREN, ENTRY_COUNT_BITS};
use crate::axi::ADDRESS_BITS;
use crate::system::dual_port_ram::SimpleDualPortRam;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Address bits of the frame memory: a frame per level.
pub const DRAM_FRAME_ADDRESS_BITS: usize = 6;
/// Address bits of the children memory: eight places per frame.
const CHILD_ADDRESS_BITS: usize = DRAM_FRAME_ADDRESS_BITS + 3;
/// Address bits of the memory of leaves waiting under a tried split.
pub const WAITING_ADDRESS_BITS: usize = 10;
/// Leaves that can wait at once.
pub const WAITING_CAPACITY: usize = 1 << WAITING_ADDRESS_BITS;
// `update` counts with literals: the children's costs come 4 clocks after
// their queries, the last of eight at counter 11; the memories' addresses
// are cut with literals too.
const _: () = assert!(
    super::leaf_cost::LEAF_COST_LATENCY == 4
        && DRAM_FRAME_ADDRESS_BITS == 6
        && CHILD_ADDRESS_BITS == 9
        && WAITING_ADDRESS_BITS == 10
        && ADDRESS_BITS == 32
        && ENTRY_COUNT_BITS == 32
        && COUNT_BITS == 20
        && COST_BITS == 48
        && CHILDREN == 16
        && ENTRY_BYTES == 32
);

/// A cell and its two lists' places: the current cell, a waiting leaf.
#[derive(Clone, Copy, Debug, PartialEq, Default, LogicStruct)]
pub struct DramCell {
    pub x: Bits<32>,
    pub y: Bits<32>,
    pub z: Bits<32>,
    pub level: Bits<6>,
    pub base_a: Bits<32>,
    pub count_a: Bits<32>,
    pub base_b: Bits<32>,
    pub count_b: Bits<32>,
}

/// A child's two lists, as its parent's pass wrote them.
#[derive(Clone, Copy, Debug, PartialEq, Default, LogicStruct)]
pub struct ChildPlaces {
    pub base_a: Bits<32>,
    pub count_a: Bits<32>,
    pub base_b: Bits<32>,
    pub count_b: Bits<32>,
}

/// A split cell whose children are being visited.
#[derive(Clone, Copy, Debug, PartialEq, Default, LogicStruct)]
pub struct DramFrame {
    pub x: Bits<32>,
    pub y: Bits<32>,
    pub z: Bits<32>,
    pub level: Bits<6>,
    pub base_a: Bits<32>,
    pub count_a: Bits<32>,
    pub base_b: Bits<32>,
    pub count_b: Bits<32>,
    /// Its cost as a leaf, its pass's (the rule's estimate), and its
    /// children's costs so far.
    pub leaf_cost: Bits<48>,
    pub classify: Bits<48>,
    pub subtree: Bits<48>,
    /// Tried, not paid: its subtree may still be dropped.
    pub tried: Bit,
    /// Leaves waiting before its children's.
    pub waiting_mark: Bits<11>,
    /// The children's lookahead.
    pub slack_next: Bits<2>,
    /// The arena's top above its children's lists.
    pub children_top: Bits<32>,
    /// Children holding both objects, not yet visited.
    pub remaining: Bits<8>,
}

#[derive(Copy, Clone, PartialEq, Eq, Debug, LogicState)]
pub enum DramBinState {
    Idle,
    /// The current cell's leaf cost (counter 0 to 4) and the decision.
    Query,
    /// The cell's pass (started at counter 0).
    Pass,
    /// The children's costs and places (counter 0 to 12), the decision.
    Costs,
    /// Pop: the next child of the top frame, or its close.
    Next,
    /// The frame below the closed one comes back from memory.
    Close,
    SendCur,
    SendWaiting,
    Done,
}

/// The binning controller over DRAM passes (module doc): the list pass
/// unit inside, its AXI4 manager port outside.
#[derive(LogicBlock)]
pub struct DramBinningUnit<
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
    /// One clock high while not busy: bin from the root cell and lists on
    /// the inputs (read in that clock only).
    pub start: Signal<In, Bit>,
    pub corner_x: Signal<In, Bits<G>>,
    pub corner_y: Signal<In, Bits<G>>,
    pub corner_z: Signal<In, Bits<G>>,
    pub level: Signal<In, Bits<6>>,
    /// Object `k`'s root list: its first entry's address and its entries.
    pub list_base: [Signal<In, Bits<ADDRESS_BITS>>; 2],
    pub list_count: [Signal<In, Bits<ENTRY_COUNT_BITS>>; 2],
    /// The arena for the children's lists, `[arena_start, arena_end)`,
    /// `arena_start` on a write burst.
    pub arena_start: Signal<In, Bits<ADDRESS_BITS>>,
    pub arena_end: Signal<In, Bits<ADDRESS_BITS>>,
    /// High from the clock the walk ends until the next `start`.
    pub done: Signal<Out, Bit>,
    /// A pass raised its error (the walk stopped).
    pub error: Signal<Out, Bit>,
    /// Times a leaf found the waiting memory full: every tried split on
    /// the stack was kept, the waiting leaves went out, then it (nothing
    /// is lost).
    pub waiting_commits: Signal<Out, Bits<32>>,
    /// A leaf is offered in each clock this is high, and goes out in a
    /// clock that also has `leaf_ready`; until then it is held.
    pub leaf_valid: Signal<Out, Bit>,
    pub leaf_ready: Signal<In, Bit>,
    /// While high, no pass starts (the narrow phase still reads leaves'
    /// lists the pass may overwrite, or holds the read channel).
    pub pass_hold: Signal<In, Bit>,
    pub leaf_x: Signal<Out, Bits<G>>,
    pub leaf_y: Signal<Out, Bits<G>>,
    pub leaf_z: Signal<Out, Bits<G>>,
    pub leaf_level: Signal<Out, Bits<6>>,
    pub leaf_base: [Signal<Out, Bits<ADDRESS_BITS>>; 2],
    pub leaf_count: [Signal<Out, Bits<ENTRY_COUNT_BITS>>; 2],
    /// Cells passed, and cells made leaves because their children would
    /// not fit the arena.
    pub passes: Signal<Out, Bits<32>>,
    pub arena_full: Signal<Out, Bits<32>>,
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
    pass: ListPass<G, V, N, T, DW, S>,
    cost: LeafCost,
    terms: SplitTerms,
    frames: SimpleDualPortRam<DramFrame, DRAM_FRAME_ADDRESS_BITS>,
    children: SimpleDualPortRam<ChildPlaces, CHILD_ADDRESS_BITS>,
    waiting: SimpleDualPortRam<DramCell, WAITING_ADDRESS_BITS>,
    // Constants of the build.
    lookahead: Constant<Bits<2>>,
    grid_bits: Constant<Bits<6>>,
    max_leaf_enable: Constant<Bit>,
    max_leaf_level: Constant<Bits<6>>,
    octant_number: [Constant<Bits<9>>; 8],
    octant_bit: [Constant<Bits<8>>; 8],
    waiting_capacity: Constant<Bits<11>>,
    // The walk.
    state: DFF<DramBinState>,
    counter: DFF<Bits<4>>,
    cur: DFF<DramCell>,
    at_root: DFF<Bit>,
    slack: DFF<Bits<2>>,
    arena_top: DFF<Bits<32>>,
    cur_leaf_cost: DFF<Bits<48>>,
    cur_classify: DFF<Bits<48>>,
    /// Where the cell's children's lists go, object by object, and the
    /// arena's top above them.
    cur_children: [DFF<Bits<32>>; 2],
    cur_stride: [DFF<Bits<32>>; 2],
    cur_new_top: DFF<Bits<32>>,
    children_cost: DFF<Bits<48>>,
    /// Child `counter`'s list places while the costs are queried.
    run_base: [DFF<Bits<32>>; 2],
    live: DFF<Bits<8>>,
    top_frame: DFF<DramFrame>,
    depth: DFF<Bits<7>>,
    /// Tried splits on the stack, and how many of the lowest frames were
    /// kept when the waiting memory filled (tried no more).
    tried: DFF<Bits<7>>,
    committed: DFF<Bits<7>>,
    /// Sending the waiting leaves, then the current cell (a commit).
    then_cur: DFF<Bit>,
    commits: DFF<Bits<32>>,
    waiting_count: DFF<Bits<11>>,
    send_index: DFF<Bits<11>>,
    /// What a close gives its parent, and does next (0: pop, 1: send the
    /// closed cell, 2: send the waiting leaves).
    close_cost: DFF<Bits<48>>,
    close_action: DFF<Bits<2>>,
    passes_q: DFF<Bits<32>>,
    arena_full_q: DFF<Bits<32>>,
    failed: DFF<Bit>,
    // Between the parts.
    swapped: Signal<Local, Bit>,
    child_a: Signal<Local, Bits<32>>,
    child_b: Signal<Local, Bits<32>>,
    pays: Signal<Local, Bit>,
    frame_forced: Signal<Local, Bit>,
    dropped: Signal<Local, Bit>,
    tried_after: Signal<Local, Bits<7>>,
    frame_tried: Signal<Local, Bit>,
    depth_after: Signal<Local, Bits<7>>,
    lowest: Signal<Local, Bits<8>>,
    octant: Signal<Local, Bits<9>>,
    half: Signal<Local, Bits<32>>,
    leaf_cost_now: Signal<Local, Bits<48>>,
    to_parent: Signal<Local, Bits<48>>,
    give_to_parent: Signal<Local, Bit>,
    wait_write: Signal<Local, Bit>,
    wait_data: Signal<Local, DramCell>,
    wait_address: Signal<Local, Bits<11>>,
    out_cell: Signal<Local, DramCell>,
    /// What the controller does not read of its parts (the pass's `busy`,
    /// the leaf's coordinates above the grid's bits), folded into one bit.
    unused_outputs: Signal<Local, Bit>,
}

impl<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
    > crate::unit::Unit for DramBinningUnit<G, V, N, T, DW, S>
{
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            pass,
            cost,
            terms,
            frames,
            children,
            waiting,
            state,
            counter,
            cur,
            at_root,
            slack,
            arena_top,
            cur_leaf_cost,
            cur_classify,
            cur_children,
            cur_stride,
            cur_new_top,
            children_cost,
            run_base,
            live,
            top_frame,
            depth,
            tried,
            committed,
            then_cur,
            commits,
            waiting_count,
            send_index,
            close_cost,
            close_action,
            passes_q,
            arena_full_q,
            failed
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
    > DramBinningUnit<G, V, N, T, DW, S>
{
    /// The controller over a list pass unit with reads of at most
    /// `max_read_burst` beats and `outstanding` bursts in flight, for a
    /// system of depth `2^log_depth` and `2^log_pipelines` pipelines,
    /// cells above `max_leaf_level` always split.
    pub fn new(
        max_read_burst: usize,
        outstanding: usize,
        log_depth: u32,
        log_pipelines: u32,
        max_leaf_level: Option<u32>,
        waiting_capacity: usize,
    ) -> Self {
        assert!(
            (1..=WAITING_CAPACITY).contains(&waiting_capacity),
            "a waiting memory of 1 to {WAITING_CAPACITY} leaves, not {waiting_capacity}"
        );
        let max_level = max_leaf_level.unwrap_or(0);
        assert!(max_level < 64, "a leaf level of 6 bits, not {max_level}");
        DramBinningUnit {
            clock: Default::default(),
            reset: Default::default(),
            start: Default::default(),
            corner_x: Default::default(),
            corner_y: Default::default(),
            corner_z: Default::default(),
            level: Default::default(),
            list_base: Default::default(),
            list_count: Default::default(),
            arena_start: Default::default(),
            arena_end: Default::default(),
            done: Default::default(),
            error: Default::default(),
            waiting_commits: Default::default(),
            leaf_valid: Default::default(),
            leaf_ready: Default::default(),
            pass_hold: Default::default(),
            leaf_x: Default::default(),
            leaf_y: Default::default(),
            leaf_z: Default::default(),
            leaf_level: Default::default(),
            leaf_base: Default::default(),
            leaf_count: Default::default(),
            passes: Default::default(),
            arena_full: Default::default(),
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
            pass: ListPass::new(max_read_burst, outstanding),
            cost: LeafCost::new(log_depth, log_pipelines),
            terms: SplitTerms::new(DW, max_leaf_level),
            frames: SimpleDualPortRam::new(1 << DRAM_FRAME_ADDRESS_BITS),
            children: SimpleDualPortRam::new(1 << CHILD_ADDRESS_BITS),
            waiting: SimpleDualPortRam::new(WAITING_CAPACITY),
            grid_bits: Constant::new((G as u64).into()),
            lookahead: Constant::new(u64::from(tritri_geom::scene::octree::LOOKAHEAD).into()),
            max_leaf_enable: Constant::new(max_leaf_level.is_some()),
            max_leaf_level: Constant::new(u64::from(max_level).into()),
            octant_number: std::array::from_fn(|o| Constant::new((o as u64).into())),
            octant_bit: std::array::from_fn(|o| Constant::new((1u64 << o).into())),
            waiting_capacity: Constant::new((waiting_capacity as u64).into()),
            state: Default::default(),
            counter: Default::default(),
            cur: Default::default(),
            at_root: Default::default(),
            slack: Default::default(),
            arena_top: Default::default(),
            cur_leaf_cost: Default::default(),
            cur_classify: Default::default(),
            cur_children: Default::default(),
            cur_stride: Default::default(),
            cur_new_top: Default::default(),
            children_cost: Default::default(),
            run_base: Default::default(),
            live: Default::default(),
            top_frame: Default::default(),
            depth: Default::default(),
            tried: Default::default(),
            committed: Default::default(),
            then_cur: Default::default(),
            commits: Default::default(),
            waiting_count: Default::default(),
            send_index: Default::default(),
            close_cost: Default::default(),
            close_action: Default::default(),
            passes_q: Default::default(),
            arena_full_q: Default::default(),
            failed: Default::default(),
            swapped: Default::default(),
            child_a: Default::default(),
            child_b: Default::default(),
            pays: Default::default(),
            frame_forced: Default::default(),
            dropped: Default::default(),
            tried_after: Default::default(),
            frame_tried: Default::default(),
            depth_after: Default::default(),
            lowest: Default::default(),
            octant: Default::default(),
            half: Default::default(),
            leaf_cost_now: Default::default(),
            to_parent: Default::default(),
            give_to_parent: Default::default(),
            wait_write: Default::default(),
            wait_data: Default::default(),
            wait_address: Default::default(),
            out_cell: Default::default(),
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
    > Logic for DramBinningUnit<G, V, N, T, DW, S>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            state,
            counter,
            cur,
            at_root,
            slack,
            arena_top,
            cur_leaf_cost,
            cur_classify,
            cur_new_top,
            children_cost,
            live,
            top_frame,
            depth,
            tried,
            committed,
            then_cur,
            commits,
            waiting_count,
            send_index,
            close_cost,
            close_action,
            passes_q,
            arena_full_q,
            failed
        );
        for k in 0..2 {
            self.cur_children[k].clock.next = self.clock.val();
            self.cur_children[k].d.next = self.cur_children[k].q.val();
            self.cur_stride[k].clock.next = self.clock.val();
            self.cur_stride[k].d.next = self.cur_stride[k].q.val();
            self.run_base[k].clock.next = self.clock.val();
            self.run_base[k].d.next = self.run_base[k].q.val();
        }
        clock!(self, clock, pass, cost, terms, frames, children, waiting);
        self.pass.reset.next = self.reset.val();

        // ---- The port is the pass unit's.
        self.m_axi_arid.next = self.pass.m_axi_arid.val();
        self.m_axi_araddr.next = self.pass.m_axi_araddr.val();
        self.m_axi_arlen.next = self.pass.m_axi_arlen.val();
        self.m_axi_arsize.next = self.pass.m_axi_arsize.val();
        self.m_axi_arburst.next = self.pass.m_axi_arburst.val();
        self.m_axi_arcache.next = self.pass.m_axi_arcache.val();
        self.m_axi_arprot.next = self.pass.m_axi_arprot.val();
        self.m_axi_arvalid.next = self.pass.m_axi_arvalid.val();
        self.pass.m_axi_arready.next = self.m_axi_arready.val();
        self.pass.m_axi_rid.next = self.m_axi_rid.val();
        self.pass.m_axi_rdata.next = self.m_axi_rdata.val();
        self.pass.m_axi_rresp.next = self.m_axi_rresp.val();
        self.pass.m_axi_rlast.next = self.m_axi_rlast.val();
        self.pass.m_axi_rvalid.next = self.m_axi_rvalid.val();
        self.m_axi_rready.next = self.pass.m_axi_rready.val();
        self.m_axi_awid.next = self.pass.m_axi_awid.val();
        self.m_axi_awaddr.next = self.pass.m_axi_awaddr.val();
        self.m_axi_awlen.next = self.pass.m_axi_awlen.val();
        self.m_axi_awsize.next = self.pass.m_axi_awsize.val();
        self.m_axi_awburst.next = self.pass.m_axi_awburst.val();
        self.m_axi_awcache.next = self.pass.m_axi_awcache.val();
        self.m_axi_awprot.next = self.pass.m_axi_awprot.val();
        self.m_axi_awvalid.next = self.pass.m_axi_awvalid.val();
        self.pass.m_axi_awready.next = self.m_axi_awready.val();
        self.m_axi_wdata.next = self.pass.m_axi_wdata.val();
        self.m_axi_wstrb.next = self.pass.m_axi_wstrb.val();
        self.m_axi_wlast.next = self.pass.m_axi_wlast.val();
        self.m_axi_wvalid.next = self.pass.m_axi_wvalid.val();
        self.pass.m_axi_wready.next = self.m_axi_wready.val();
        self.pass.m_axi_bid.next = self.m_axi_bid.val();
        self.pass.m_axi_bresp.next = self.m_axi_bresp.val();
        self.pass.m_axi_bvalid.next = self.m_axi_bvalid.val();
        self.m_axi_bready.next = self.pass.m_axi_bready.val();

        // ---- The split rule's terms for the current cell.
        self.leaf_cost_now.next = self.cost.cost.val();
        self.terms.count_a.next = self.cur.q.val().count_a;
        self.terms.count_b.next = self.cur.q.val().count_b;
        self.terms.level.next = self.cur.q.val().level;
        self.terms.at_root.next = self.at_root.q.val();
        self.terms.leaf_cost.next = self.leaf_cost_now.val();
        self.terms.arena_top.next = self.arena_top.q.val();
        self.terms.arena_end.next = self.arena_end.val();
        // The shorter list goes first: the pass writes the second only to
        // children the first reached.
        self.swapped.next = self.cur.q.val().count_b < self.cur.q.val().count_a;
        self.pays.next =
            self.terms.forced.val() | (self.children_cost.q.val() < self.cur_leaf_cost.q.val());

        // ---- The pass unit, started from Pass at counter 0.
        self.pass.start.next = (self.state.q.val() == DramBinState::Pass)
            & (self.counter.q.val() == 0)
            & !self.pass_hold.val();
        self.pass.corner_x.next = bit_cast::<G, 32>(self.cur.q.val().x);
        self.pass.corner_y.next = bit_cast::<G, 32>(self.cur.q.val().y);
        self.pass.corner_z.next = bit_cast::<G, 32>(self.cur.q.val().z);
        self.pass.level.next = self.cur.q.val().level;
        self.pass.list_base[0].next = self.cur.q.val().base_a;
        self.pass.list_count[0].next = self.cur.q.val().count_a;
        self.pass.list_base[1].next = self.cur.q.val().base_b;
        self.pass.list_count[1].next = self.cur.q.val().count_b;
        self.pass.child_base[0].next = self.cur_children[0].q.val();
        self.pass.child_stride[0].next = self.cur_stride[0].q.val();
        self.pass.child_base[1].next = self.cur_children[1].q.val();
        self.pass.child_stride[1].next = self.cur_stride[1].q.val();
        if self.swapped.val() {
            self.pass.list_base[0].next = self.cur.q.val().base_b;
            self.pass.list_count[0].next = self.cur.q.val().count_b;
            self.pass.list_base[1].next = self.cur.q.val().base_a;
            self.pass.list_count[1].next = self.cur.q.val().count_a;
            self.pass.child_base[0].next = self.cur_children[1].q.val();
            self.pass.child_stride[0].next = self.cur_stride[1].q.val();
            self.pass.child_base[1].next = self.cur_children[0].q.val();
            self.pass.child_stride[1].next = self.cur_stride[0].q.val();
        }
        // Child `counter`'s counts, in object order.
        self.child_a.next = 0.into();
        self.child_b.next = 0.into();
        for o in 0..8 {
            if self.counter.q.val().index() == o {
                self.child_a.next = self.pass.child_count[o].val();
                self.child_b.next = self.pass.child_count[o + 8].val();
                if self.swapped.val() {
                    self.child_a.next = self.pass.child_count[o + 8].val();
                    self.child_b.next = self.pass.child_count[o].val();
                }
            }
        }

        // ---- The leaf cost: the current cell's (from the children memory
        // when it is a child), or child `counter`'s.
        self.cost.a.next = bit_cast::<20, 32>(self.children.read_data.val().count_a);
        self.cost.b.next = bit_cast::<20, 32>(self.children.read_data.val().count_b);
        if self.at_root.q.val() {
            self.cost.a.next = bit_cast::<20, 32>(self.cur.q.val().count_a);
            self.cost.b.next = bit_cast::<20, 32>(self.cur.q.val().count_b);
        }
        if self.state.q.val() == DramBinState::Costs {
            self.cost.a.next = bit_cast::<20, 32>(self.child_a.val());
            self.cost.b.next = bit_cast::<20, 32>(self.child_b.val());
        }

        // ---- The top frame's next child and its close.
        self.lowest.next =
            self.top_frame.q.val().remaining & (!self.top_frame.q.val().remaining + 1);
        self.octant.next = 0.into();
        for o in 0..8 {
            if self.lowest.val().get_bit(o) {
                self.octant.next = self.octant_number[o].val();
            }
        }
        self.half.next = bits::<32>(1) << (self.top_frame.q.val().level - 1);
        self.frame_forced.next =
            self.max_leaf_enable.val() & (self.top_frame.q.val().level > self.max_leaf_level.val());
        // A frame below the last commit was kept: it is tried no more.
        self.frame_tried.next =
            self.top_frame.q.val().tried & ((self.depth.q.val() - 1) >= self.committed.q.val());
        self.dropped.next = self.frame_tried.val()
            & !self.frame_forced.val()
            & (self.top_frame.q.val().subtree >= self.top_frame.q.val().leaf_cost);
        self.tried_after.next = self.tried.q.val();
        if self.frame_tried.val() {
            self.tried_after.next = self.tried.q.val() - 1;
        }

        // ---- Memories: defaults.
        self.frames.write_enable.next = false;
        self.frames.write_address.next = bit_cast::<6, 7>(self.depth.q.val() - 1);
        self.frames.write_data.next = self.top_frame.q.val();
        self.frames.read_enable.next = false;
        self.frames.read_address.next = bit_cast::<6, 7>(self.depth.q.val() - 2);
        self.children.write_enable.next = false;
        self.children.write_address.next = (bit_cast::<9, 7>(self.depth.q.val()) << 3)
            | bit_cast::<9, 4>(self.counter.q.val() & 7);
        self.children.write_data.next.base_a = self.run_base[0].q.val();
        self.children.write_data.next.count_a = self.child_a.val();
        self.children.write_data.next.base_b = self.run_base[1].q.val();
        self.children.write_data.next.count_b = self.child_b.val();
        self.children.read_enable.next = false;
        self.children.read_address.next =
            (bit_cast::<9, 7>(self.depth.q.val() - 1) << 3) | self.octant.val();
        self.waiting.read_enable.next = false;
        self.waiting.read_address.next = bit_cast::<10, 11>(self.send_index.q.val());
        self.wait_write.next = false;
        self.wait_data.next = self.cur.q.val();
        self.wait_address.next = self.waiting_count.q.val();
        self.give_to_parent.next = false;
        self.to_parent.next = self.leaf_cost_now.val();
        self.depth_after.next = self.depth.q.val();

        match self.state.q.val() {
            DramBinState::Query => {
                // Counter 0: a child's lists come from the children memory.
                if (self.counter.q.val() == 0) & !self.at_root.q.val() {
                    self.cur.d.next.base_a = self.children.read_data.val().base_a;
                    self.cur.d.next.count_a = self.children.read_data.val().count_a;
                    self.cur.d.next.base_b = self.children.read_data.val().base_b;
                    self.cur.d.next.count_b = self.children.read_data.val().count_b;
                }
                self.counter.d.next = self.counter.q.val() + 1;
                if self.counter.q.val() == 4 {
                    self.counter.d.next = 0.into();
                    if (self.cur.q.val().level == 0)
                        | self.terms.cannot_pay.val()
                        | !self.terms.fits.val()
                    {
                        if (self.cur.q.val().level != 0)
                            & !self.terms.cannot_pay.val()
                            & !self.terms.fits.val()
                        {
                            self.arena_full_q.d.next = self.arena_full_q.q.val() + 1;
                        }
                        // A leaf: its cost to the parent, out or waiting.
                        self.give_to_parent.next = true;
                        self.to_parent.next = self.leaf_cost_now.val();
                        if self.tried.q.val() != 0 {
                            self.wait_write.next = true;
                            self.state.d.next = DramBinState::Next;
                        } else {
                            self.state.d.next = DramBinState::SendCur;
                        }
                    } else {
                        self.cur_leaf_cost.d.next = self.leaf_cost_now.val();
                        self.cur_classify.d.next = self.terms.classify.val();
                        self.cur_children[0].d.next = self.arena_top.q.val();
                        self.cur_children[1].d.next = self.terms.children_b.val();
                        self.cur_stride[0].d.next = self.terms.stride_a.val();
                        self.cur_stride[1].d.next = self.terms.stride_b.val();
                        self.cur_new_top.d.next = self.terms.new_top.val();
                        self.state.d.next = DramBinState::Pass;
                    }
                }
            }
            DramBinState::Pass => {
                // Counter 0 waits while the pass is held.
                if (self.counter.q.val() != 0) | !self.pass_hold.val() {
                    self.counter.d.next = 1.into();
                }
                // Counter 0 is the start: `done` still holds the last pass's.
                if (self.counter.q.val() == 1) & self.pass.done.val() {
                    self.passes_q.d.next = self.passes_q.q.val() + 1;
                    self.counter.d.next = 0.into();
                    if self.pass.error.val() {
                        self.failed.d.next = true;
                        self.state.d.next = DramBinState::Done;
                    } else {
                        self.run_base[0].d.next = self.cur_children[0].q.val();
                        self.run_base[1].d.next = self.cur_children[1].q.val();
                        self.children_cost.d.next = 0.into();
                        self.live.d.next = 0.into();
                        self.state.d.next = DramBinState::Costs;
                    }
                }
            }
            DramBinState::Costs => {
                self.counter.d.next = self.counter.q.val() + 1;
                if self.counter.q.val() < 8 {
                    // Child `counter`: its cost queried, its places written.
                    self.children.write_enable.next = true;
                    self.run_base[0].d.next = self.run_base[0].q.val() + self.cur_stride[0].q.val();
                    self.run_base[1].d.next = self.run_base[1].q.val() + self.cur_stride[1].q.val();
                    if (self.child_a.val() != 0) & (self.child_b.val() != 0) {
                        for o in 0..8 {
                            if self.counter.q.val().index() == o {
                                self.live.d.next = self.live.q.val() | self.octant_bit[o].val();
                            }
                        }
                    }
                }
                if (self.counter.q.val() >= 4) & (self.counter.q.val() < 12) {
                    self.children_cost.d.next =
                        self.children_cost.q.val() + self.leaf_cost_now.val();
                }
                if self.counter.q.val() == 12 {
                    self.counter.d.next = 0.into();
                    if !self.pays.val() & (self.slack.q.val() == 0) {
                        // Not worth it, and no lookahead left: a leaf.
                        self.give_to_parent.next = true;
                        self.to_parent.next =
                            self.cur_leaf_cost.q.val() + self.cur_classify.q.val();
                        if self.tried.q.val() != 0 {
                            self.wait_write.next = true;
                            self.state.d.next = DramBinState::Next;
                        } else {
                            self.state.d.next = DramBinState::SendCur;
                        }
                    } else {
                        // Push: the old top into the memory, the cell on top.
                        if self.depth.q.val() != 0 {
                            self.frames.write_enable.next = true;
                        }
                        self.top_frame.d.next.x = self.cur.q.val().x;
                        self.top_frame.d.next.y = self.cur.q.val().y;
                        self.top_frame.d.next.z = self.cur.q.val().z;
                        self.top_frame.d.next.level = self.cur.q.val().level;
                        self.top_frame.d.next.base_a = self.cur.q.val().base_a;
                        self.top_frame.d.next.count_a = self.cur.q.val().count_a;
                        self.top_frame.d.next.base_b = self.cur.q.val().base_b;
                        self.top_frame.d.next.count_b = self.cur.q.val().count_b;
                        self.top_frame.d.next.leaf_cost = self.cur_leaf_cost.q.val();
                        self.top_frame.d.next.classify = self.cur_classify.q.val();
                        self.top_frame.d.next.subtree = 0.into();
                        self.top_frame.d.next.tried = !self.pays.val();
                        self.top_frame.d.next.waiting_mark = self.waiting_count.q.val();
                        self.top_frame.d.next.slack_next = self.lookahead.val();
                        if !self.pays.val() {
                            self.top_frame.d.next.slack_next = self.slack.q.val() - 1;
                            self.tried.d.next = self.tried.q.val() + 1;
                        }
                        self.top_frame.d.next.children_top = self.cur_new_top.q.val();
                        self.top_frame.d.next.remaining = self.live.q.val();
                        self.depth.d.next = self.depth.q.val() + 1;
                        self.state.d.next = DramBinState::Next;
                    }
                }
            }
            DramBinState::Next => {
                self.at_root.d.next = false;
                if self.depth.q.val() == 0 {
                    self.state.d.next = DramBinState::Done;
                } else if self.top_frame.q.val().remaining == 0 {
                    // Close: the split's cost to its parent; a tried split
                    // that cost at least the cell as a leaf drops its
                    // subtree's waiting leaves for the cell.
                    self.close_cost.d.next =
                        self.top_frame.q.val().subtree + self.top_frame.q.val().classify;
                    if self.dropped.val() {
                        self.close_cost.d.next =
                            self.top_frame.q.val().leaf_cost + self.top_frame.q.val().classify;
                    }
                    self.tried.d.next = self.tried_after.val();
                    self.cur.d.next.x = self.top_frame.q.val().x;
                    self.cur.d.next.y = self.top_frame.q.val().y;
                    self.cur.d.next.z = self.top_frame.q.val().z;
                    self.cur.d.next.level = self.top_frame.q.val().level;
                    self.cur.d.next.base_a = self.top_frame.q.val().base_a;
                    self.cur.d.next.count_a = self.top_frame.q.val().count_a;
                    self.cur.d.next.base_b = self.top_frame.q.val().base_b;
                    self.cur.d.next.count_b = self.top_frame.q.val().count_b;
                    self.close_action.d.next = 0.into();
                    if self.dropped.val() {
                        self.waiting_count.d.next = self.top_frame.q.val().waiting_mark;
                        if self.tried_after.val() != 0 {
                            self.wait_write.next = true;
                            self.wait_address.next = self.top_frame.q.val().waiting_mark;
                            self.wait_data.next.x = self.top_frame.q.val().x;
                            self.wait_data.next.y = self.top_frame.q.val().y;
                            self.wait_data.next.z = self.top_frame.q.val().z;
                            self.wait_data.next.level = self.top_frame.q.val().level;
                            self.wait_data.next.base_a = self.top_frame.q.val().base_a;
                            self.wait_data.next.count_a = self.top_frame.q.val().count_a;
                            self.wait_data.next.base_b = self.top_frame.q.val().base_b;
                            self.wait_data.next.count_b = self.top_frame.q.val().count_b;
                        } else {
                            self.close_action.d.next = 1.into();
                        }
                    } else if self.frame_tried.val()
                        & (self.tried_after.val() == 0)
                        & (self.waiting_count.q.val() != 0)
                    {
                        self.close_action.d.next = 2.into();
                    }
                    self.send_index.d.next = 0.into();
                    self.frames.read_enable.next = true;
                    self.depth.d.next = self.depth.q.val() - 1;
                    self.depth_after.next = self.depth.q.val() - 1;
                    if self.committed.q.val() > self.depth.q.val() - 1 {
                        self.committed.d.next = self.depth.q.val() - 1;
                    }
                    self.state.d.next = DramBinState::Close;
                } else {
                    // Visit the lowest child left: its lists are read from
                    // the children memory in this clock.
                    self.children.read_enable.next = true;
                    self.top_frame.d.next.remaining =
                        self.top_frame.q.val().remaining & !self.lowest.val();
                    self.cur.d.next.x = self.top_frame.q.val().x;
                    self.cur.d.next.y = self.top_frame.q.val().y;
                    self.cur.d.next.z = self.top_frame.q.val().z;
                    if self.lowest.val().get_bit(1)
                        | self.lowest.val().get_bit(3)
                        | self.lowest.val().get_bit(5)
                        | self.lowest.val().get_bit(7)
                    {
                        self.cur.d.next.x = self.top_frame.q.val().x + self.half.val();
                    }
                    if self.lowest.val().get_bit(2)
                        | self.lowest.val().get_bit(3)
                        | self.lowest.val().get_bit(6)
                        | self.lowest.val().get_bit(7)
                    {
                        self.cur.d.next.y = self.top_frame.q.val().y + self.half.val();
                    }
                    if self.lowest.val().get_bit(4)
                        | self.lowest.val().get_bit(5)
                        | self.lowest.val().get_bit(6)
                        | self.lowest.val().get_bit(7)
                    {
                        self.cur.d.next.z = self.top_frame.q.val().z + self.half.val();
                    }
                    self.cur.d.next.level = self.top_frame.q.val().level - 1;
                    self.slack.d.next = self.top_frame.q.val().slack_next;
                    // Under a tried split the arena's top only rises: the
                    // waiting leaves' lists must survive.
                    self.arena_top.d.next = self.top_frame.q.val().children_top;
                    if (self.tried.q.val() != 0)
                        & (self.arena_top.q.val() > self.top_frame.q.val().children_top)
                    {
                        self.arena_top.d.next = self.arena_top.q.val();
                    }
                    self.counter.d.next = 0.into();
                    self.state.d.next = DramBinState::Query;
                }
            }
            DramBinState::Close => {
                if self.depth.q.val() != 0 {
                    self.top_frame.d.next = self.frames.read_data.val();
                    self.top_frame.d.next.subtree =
                        self.frames.read_data.val().subtree + self.close_cost.q.val();
                }
                self.waiting.read_enable.next = true;
                self.state.d.next = DramBinState::Next;
                if self.close_action.q.val() == 1 {
                    self.state.d.next = DramBinState::SendCur;
                }
                if self.close_action.q.val() >= 2 {
                    self.send_index.d.next = 1.into();
                    self.then_cur.d.next = self.close_action.q.val() == 3;
                    self.state.d.next = DramBinState::SendWaiting;
                }
            }
            DramBinState::SendCur => {
                if self.leaf_ready.val() {
                    self.state.d.next = DramBinState::Next;
                }
            }
            DramBinState::SendWaiting => {
                // The leaf at `send_index - 1` is out; the next is read.
                // Not taken, it stays: the memory's read data holds.
                if self.leaf_ready.val() {
                    self.waiting.read_enable.next = true;
                    self.send_index.d.next = self.send_index.q.val() + 1;
                    if self.send_index.q.val() == self.waiting_count.q.val() {
                        self.waiting_count.d.next = 0.into();
                        self.state.d.next = DramBinState::Next;
                        if self.then_cur.q.val() {
                            self.then_cur.d.next = false;
                            self.state.d.next = DramBinState::SendCur;
                        }
                    }
                }
            }
            _ => {}
        }
        if self.start.val()
            & ((self.state.q.val() == DramBinState::Idle)
                | (self.state.q.val() == DramBinState::Done))
        {
            self.cur.d.next.x = bit_cast::<32, G>(self.corner_x.val());
            self.cur.d.next.y = bit_cast::<32, G>(self.corner_y.val());
            self.cur.d.next.z = bit_cast::<32, G>(self.corner_z.val());
            self.cur.d.next.level = self.level.val();
            self.cur.d.next.base_a = self.list_base[0].val();
            self.cur.d.next.count_a = self.list_count[0].val();
            self.cur.d.next.base_b = self.list_base[1].val();
            self.cur.d.next.count_b = self.list_count[1].val();
            self.at_root.d.next = true;
            self.slack.d.next = self.lookahead.val();
            self.arena_top.d.next = self.arena_start.val();
            self.depth.d.next = 0.into();
            self.tried.d.next = 0.into();
            self.waiting_count.d.next = 0.into();
            self.passes_q.d.next = 0.into();
            self.arena_full_q.d.next = 0.into();
            self.failed.d.next = false;
            self.committed.d.next = 0.into();
            self.then_cur.d.next = false;
            self.commits.d.next = 0.into();
            self.counter.d.next = 0.into();
            // Only the root can lack an object: no child without
            // both is visited.
            if (self.list_count[0].val() != 0) & (self.list_count[1].val() != 0) {
                self.state.d.next = DramBinState::Query;
            } else {
                self.state.d.next = DramBinState::Next;
            }
        }
        if self.give_to_parent.val() & (self.depth.q.val() != 0) {
            self.top_frame.d.next.subtree = self.top_frame.q.val().subtree + self.to_parent.val();
        }
        self.waiting.write_enable.next = false;
        self.waiting.write_address.next = bit_cast::<10, 11>(self.wait_address.val());
        self.waiting.write_data.next = self.wait_data.val();
        if self.wait_write.val() {
            if self.wait_address.val() == self.waiting_capacity.val() {
                // Full: every tried split on the stack is kept; the waiting
                // leaves go out (the first read now), then the leaf.
                self.commits.d.next = self.commits.q.val() + 1;
                self.tried.d.next = 0.into();
                self.committed.d.next = self.depth_after.val();
                if self.state.q.val() == DramBinState::Next {
                    self.close_action.d.next = 3.into();
                } else {
                    self.waiting.read_enable.next = true;
                    self.waiting.read_address.next = 0.into();
                    self.send_index.d.next = 1.into();
                    self.then_cur.d.next = true;
                    self.state.d.next = DramBinState::SendWaiting;
                }
            } else {
                self.waiting.write_enable.next = true;
                self.waiting_count.d.next = self.wait_address.val() + 1;
            }
        }
        if self.reset.val() {
            self.state.d.next = DramBinState::Idle;
        }

        // ---- Outputs.
        self.out_cell.next = self.cur.q.val();
        if self.state.q.val() == DramBinState::SendWaiting {
            self.out_cell.next = self.waiting.read_data.val();
        }
        self.leaf_valid.next = (self.state.q.val() == DramBinState::SendCur)
            | (self.state.q.val() == DramBinState::SendWaiting);
        self.leaf_x.next = bit_cast::<G, 32>(self.out_cell.val().x);
        self.leaf_y.next = bit_cast::<G, 32>(self.out_cell.val().y);
        self.leaf_z.next = bit_cast::<G, 32>(self.out_cell.val().z);
        self.leaf_level.next = self.out_cell.val().level;
        self.leaf_base[0].next = self.out_cell.val().base_a;
        self.leaf_count[0].next = self.out_cell.val().count_a;
        self.leaf_base[1].next = self.out_cell.val().base_b;
        self.leaf_count[1].next = self.out_cell.val().count_b;
        self.done.next = (self.state.q.val() == DramBinState::Done)
            | ((self.state.q.val() == DramBinState::Next) & (self.depth.q.val() == 0));
        self.error.next = self.failed.q.val();
        self.waiting_commits.next = self.commits.q.val();
        self.passes.next = self.passes_q.q.val();
        self.arena_full.next = self.arena_full_q.q.val();
        self.unused_outputs.next = self.pass.busy.val()
            ^ (self.out_cell.val().x >> self.grid_bits.val()).any()
            ^ (self.out_cell.val().y >> self.grid_bits.val()).any()
            ^ (self.out_cell.val().z >> self.grid_bits.val()).any();
    }
}
