//! The octree engine's voxel → octree conversion (`octree_engine.txt`,
//! function 2): a voxel model's bricks streamed in (a 64-bit word of 4×4×4
//! voxels a clock), its canonical octree's nodes streamed out.
//!
//! The order, the holding of leaf children that keeps the tree canonical on
//! the fly, and the clock-by-clock steps are those of the cycle model,
//! [`super::octree_builder_machine`] (module docs there): bricks in reverse
//! Morton order, nodes out in postorder, which a node memory written from
//! its top address down turns into the preorder of
//! `tritri_geom::octree::tree::Octree`.
//!
//! Per level of the grid above the bricks (3 to 10) the unit keeps three things: the cell
//! is known mixed (a bit), the leaves held (a count of 0 to 7) and their
//! type (a bit). Reads of one level are multiplexers, writes one-hot
//! decodes of the level; the cell's position among its siblings comes from
//! the count of bricks taken, shifted by three bits a level. A brick that
//! is not uniform sits in a register shifted a byte a step, its level-1
//! cell on view in the top byte.
//!
//! The whole unit stalls while a node waits for `out_ready`.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Largest grid level (1024 voxels a side).
pub const BUILDER_MAX_LEVEL: u32 = 10;
/// Levels with a held-leaf counter: 3 to 10.
const HELD_LEVELS: usize = 8;
/// Bits of the count of bricks (8^8 at 1024^3).
pub const BRICK_COUNT_BITS: usize = 24;

/// The node codes on `out_node` (`tritri_geom::octree::tree::Node`).
pub const NODE_EMPTY: u64 = 0;
pub const NODE_FULL: u64 = 1;
pub const NODE_MIXED: u64 = 2;

/// The steps of [`super::octree_builder_machine::BuilderState`].
#[derive(Copy, Clone, PartialEq, Eq, Debug, LogicState)]
pub enum BuildState {
    Input,
    Flush,
    Cells,
    Voxels,
    Closed,
    Leaf,
    Mixed,
    Cascade,
}

#[derive(LogicBlock)]
pub struct OctreeBuilder {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: waiting for a model's first cell.
    pub reset: Signal<In, Bit>,
    /// The grid is `2^level` voxels a side (2 to 10); held.
    pub level: Signal<In, Bits<4>>,
    // Bricks in (valid/ready), reverse Morton order: bit `8 c + o` is voxel
    // `o` of the brick's level-1 cell `c` (bit `k` of an octant: the upper
    // half along axis `k`).
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_brick: Signal<In, Bits<64>>,
    /// A model is under way or a node waits.
    pub busy: Signal<Out, Bit>,
    // Nodes out (valid/ready), postorder: 0 empty, 1 full, 2 mixed.
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_node: Signal<Out, Bits<2>>,
    state: DFF<BuildState>,
    /// Bit `l`: the current cell of level `l` is known mixed; the type of
    /// the leaves it holds (1: full).
    mixed: DFF<Bits<16>>,
    full: DFF<Bits<16>>,
    /// Leaves held by the current cell of level `i + 3`.
    held: [DFF<Bits<3>>; HELD_LEVELS],
    count: DFF<Bits<BRICK_COUNT_BITS>>,
    cell_level: DFF<Bits<4>>,
    probe: DFF<Bits<BRICK_COUNT_BITS>>,
    cell_full: DFF<Bit>,
    cell_mixed: DFF<Bit>,
    flush_stop: DFF<Bits<4>>,
    after_flush: DFF<BuildState>,
    /// A brick that is not uniform, its current level-1 cell in the top
    /// byte; the cells left after it.
    brick: DFF<Bits<64>>,
    cells_left: DFF<Bits<3>>,
    mask: DFF<Bits<8>>,
    voxel: DFF<Bits<3>>,
    out_valid_q: DFF<Bit>,
    out_node_q: DFF<Bits<2>>,
    /// The level of counter `i`.
    level_of: [Constant<Bits<4>>; HELD_LEVELS],
    // Combinational.
    advance: Signal<Local, Bit>,
    complete: Signal<Local, Bit>,
    parent: Signal<Local, Bits<4>>,
    /// One-hot: the parent's level, the cell's level.
    parent_bit: Signal<Local, Bits<16>>,
    cell_bit: Signal<Local, Bits<16>>,
    /// Levels >= the parent.
    from_parent: Signal<Local, Bits<16>>,
    parent_held: Signal<Local, Bits<3>>,
    /// The highest level >= `flush_stop` holding leaves.
    highest: Signal<Local, Bits<4>>,
    highest_found: Signal<Local, Bit>,
    /// The type of its leaves.
    highest_full: Signal<Local, Bit>,
    shifted: Signal<Local, Bits<BRICK_COUNT_BITS>>,
    /// The brick's next level-1 cell moved to the top byte.
    brick_next: Signal<Local, Bits<64>>,
    cell: Signal<Local, Bits<8>>,
    emit: Signal<Local, Bit>,
    node: Signal<Local, Bits<2>>,
}

impl crate::unit::Unit for OctreeBuilder {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            state,
            mixed,
            full,
            held,
            count,
            cell_level,
            probe,
            cell_full,
            cell_mixed,
            flush_stop,
            after_flush,
            brick,
            cells_left,
            mask,
            voxel,
            out_valid_q,
            out_node_q
        );
    }
}

impl Default for OctreeBuilder {
    fn default() -> Self {
        OctreeBuilder {
            clock: Default::default(),
            reset: Default::default(),
            level: Default::default(),
            in_valid: Default::default(),
            in_ready: Default::default(),
            in_brick: Default::default(),
            busy: Default::default(),
            out_valid: Default::default(),
            out_ready: Default::default(),
            out_node: Default::default(),
            state: Default::default(),
            mixed: Default::default(),
            full: Default::default(),
            held: Default::default(),
            count: Default::default(),
            cell_level: Default::default(),
            probe: Default::default(),
            cell_full: Default::default(),
            cell_mixed: Default::default(),
            flush_stop: Default::default(),
            after_flush: Default::default(),
            brick: Default::default(),
            cells_left: Default::default(),
            mask: Default::default(),
            voxel: Default::default(),
            out_valid_q: Default::default(),
            out_node_q: Default::default(),
            level_of: std::array::from_fn(|i| Constant::new(Bits::<4>::from(i as u64 + 3))),
            advance: Default::default(),
            complete: Default::default(),
            parent: Default::default(),
            parent_bit: Default::default(),
            cell_bit: Default::default(),
            from_parent: Default::default(),
            parent_held: Default::default(),
            highest: Default::default(),
            highest_found: Default::default(),
            highest_full: Default::default(),
            shifted: Default::default(),
            brick_next: Default::default(),
            cell: Default::default(),
            emit: Default::default(),
            node: Default::default(),
        }
    }
}

impl Logic for OctreeBuilder {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            state,
            mixed,
            full,
            count,
            cell_level,
            probe,
            cell_full,
            cell_mixed,
            flush_stop,
            after_flush,
            brick,
            cells_left,
            mask,
            voxel,
            out_valid_q,
            out_node_q
        );
        for i in 0..8 {
            self.held[i].clock.next = self.clock.val();
            self.held[i].d.next = self.held[i].q.val();
        }
        // Everything moves unless a node waits at the output.
        self.advance.next = !self.out_valid_q.q.val() | self.out_ready.val();
        self.out_valid.next = self.out_valid_q.q.val();
        self.out_node.next = self.out_node_q.q.val();
        self.in_ready.next = (self.state.q.val() == BuildState::Input) & self.advance.val();
        self.busy.next = (self.state.q.val() != BuildState::Input)
            | (self.count.q.val() != 0)
            | self.out_valid_q.q.val();

        // The cell being passed up is its parent's last child (octant 0,
        // the last in reverse order) when its position's low bits are 7.
        self.complete.next = self.probe.q.val().get_bits::<3>(0) == 7;
        self.parent.next = self.cell_level.q.val() + 1;
        self.parent_bit.next = bits::<16>(1) << self.parent.val();
        self.cell_bit.next = bits::<16>(1) << self.cell_level.q.val();
        self.from_parent.next = bits::<16>(0xffff) << self.parent.val();
        self.shifted.next = self.probe.q.val() >> 3;
        self.brick_next.next = self.brick.q.val() << 8;
        self.cell.next = self.brick.q.val().get_bits::<8>(56);
        self.parent_held.next = 0.into();
        self.highest.next = 0.into();
        self.highest_found.next = false;
        self.highest_full.next = false;
        for i in 0..8 {
            if self.level_of[i].val() == self.parent.val() {
                self.parent_held.next = self.held[i].q.val();
            }
            // Later (higher) levels win.
            if (self.held[i].q.val() != 0) & (self.level_of[i].val() >= self.flush_stop.q.val()) {
                self.highest.next = self.level_of[i].val();
                self.highest_found.next = true;
                self.highest_full.next = self.full.q.val().get_bit(self.level_of[i].val().index());
            }
        }

        self.emit.next = false;
        self.node.next = 0.into();
        if self.advance.val() {
            match self.state.q.val() {
                BuildState::Input => {
                    if self.in_valid.val() {
                        self.probe.d.next = self.count.q.val();
                        self.count.d.next = self.count.q.val() + 1;
                        self.cell_level.d.next = 2.into();
                        if (self.in_brick.val() == 0) | self.in_brick.val().all() {
                            self.cell_full.d.next = self.in_brick.val().all();
                            self.cell_mixed.d.next = false;
                            self.state.d.next = BuildState::Cascade;
                        } else {
                            self.brick.d.next = self.in_brick.val();
                            self.cells_left.d.next = 7.into();
                            // Every ancestor is mixed: flush their leaves.
                            self.mixed.d.next = self.mixed.q.val() | bits::<16>(0xfff8);
                            self.flush_stop.d.next = 3.into();
                            self.after_flush.d.next = BuildState::Cells;
                            self.state.d.next = BuildState::Flush;
                        }
                    }
                }
                BuildState::Flush => {
                    if self.highest_found.val() {
                        self.emit.next = true;
                        self.node.next = 0.into();
                        if self.highest_full.val() {
                            self.node.next = 1.into();
                        }
                        for i in 0..8 {
                            if self.level_of[i].val() == self.highest.val() {
                                self.held[i].d.next = self.held[i].q.val() - 1;
                            }
                        }
                    } else {
                        self.state.d.next = self.after_flush.q.val();
                    }
                }
                BuildState::Cells => {
                    if (self.cell.val() == 0) | (self.cell.val() == 0xff) {
                        // A uniform level-1 cell of a mixed brick: a leaf.
                        self.emit.next = true;
                        self.node.next = 0.into();
                        if self.cell.val() == 0xff {
                            self.node.next = 1.into();
                        }
                        self.brick.d.next = self.brick_next.val();
                        self.cells_left.d.next = self.cells_left.q.val() - 1;
                        if self.cells_left.q.val() == 0 {
                            self.state.d.next = BuildState::Mixed;
                        }
                    } else {
                        self.mask.d.next = self.cell.val();
                        self.voxel.d.next = 7.into();
                        self.state.d.next = BuildState::Voxels;
                    }
                }
                BuildState::Voxels => {
                    self.emit.next = true;
                    self.node.next = 0.into();
                    if self.mask.q.val().get_bit(self.voxel.q.val().index()) {
                        self.node.next = 1.into();
                    }
                    if self.voxel.q.val() == 0 {
                        self.state.d.next = BuildState::Closed;
                    } else {
                        self.voxel.d.next = self.voxel.q.val() - 1;
                    }
                }
                BuildState::Closed => {
                    // A mixed level-1 cell's node, after its voxels.
                    self.emit.next = true;
                    self.node.next = 2.into();
                    self.brick.d.next = self.brick_next.val();
                    self.cells_left.d.next = self.cells_left.q.val() - 1;
                    self.state.d.next = BuildState::Cells;
                    if self.cells_left.q.val() == 0 {
                        self.state.d.next = BuildState::Mixed;
                    }
                }
                BuildState::Leaf => {
                    self.emit.next = true;
                    self.node.next = 0.into();
                    if self.cell_full.q.val() {
                        self.node.next = 1.into();
                    }
                    if self.complete.val() {
                        self.cell_level.d.next = self.parent.val();
                        self.probe.d.next = self.shifted.val();
                        self.state.d.next = BuildState::Mixed;
                    } else {
                        self.state.d.next = BuildState::Input;
                    }
                }
                BuildState::Mixed => {
                    self.emit.next = true;
                    self.node.next = 2.into();
                    self.mixed.d.next = self.mixed.q.val() & !self.cell_bit.val();
                    for i in 0..8 {
                        if self.level_of[i].val() == self.cell_level.q.val() {
                            self.held[i].d.next = 0.into();
                        }
                    }
                    self.cell_mixed.d.next = true;
                    self.state.d.next = BuildState::Cascade;
                }
                BuildState::Cascade => {
                    if self.cell_level.q.val() == self.level.val() {
                        // The root: a leaf root is the whole tree.
                        self.emit.next = !self.cell_mixed.q.val();
                        self.node.next = 0.into();
                        if self.cell_full.q.val() {
                            self.node.next = 1.into();
                        }
                        self.count.d.next = 0.into();
                        self.state.d.next = BuildState::Input;
                    } else if self.cell_mixed.q.val() {
                        self.state.d.next = BuildState::Input;
                        if self.complete.val() {
                            self.emit.next = true;
                            self.node.next = 2.into();
                            self.mixed.d.next = self.mixed.q.val() & !self.parent_bit.val();
                            for i in 0..8 {
                                if self.level_of[i].val() == self.parent.val() {
                                    self.held[i].d.next = 0.into();
                                }
                            }
                            self.cell_level.d.next = self.parent.val();
                            self.probe.d.next = self.shifted.val();
                            self.state.d.next = BuildState::Cascade;
                        }
                    } else if (self.mixed.q.val() & self.parent_bit.val()) != 0 {
                        // A leaf of a mixed cell is written at once.
                        self.emit.next = true;
                        self.node.next = 0.into();
                        if self.cell_full.q.val() {
                            self.node.next = 1.into();
                        }
                        if self.complete.val() {
                            self.cell_level.d.next = self.parent.val();
                            self.probe.d.next = self.shifted.val();
                            self.state.d.next = BuildState::Mixed;
                        } else {
                            self.state.d.next = BuildState::Input;
                        }
                    } else if (self.parent_held.val() == 0)
                        | (((self.full.q.val() & self.parent_bit.val()) != 0)
                            == self.cell_full.q.val())
                    {
                        // Held: a leaf like its siblings so far.
                        self.full.d.next = self.full.q.val() & !self.parent_bit.val();
                        if self.cell_full.q.val() {
                            self.full.d.next = self.full.q.val() | self.parent_bit.val();
                        }
                        if self.complete.val() {
                            // Eight leaves of one type: the parent is one.
                            self.mixed.d.next = self.mixed.q.val() & !self.parent_bit.val();
                            for i in 0..8 {
                                if self.level_of[i].val() == self.parent.val() {
                                    self.held[i].d.next = 0.into();
                                }
                            }
                            self.cell_level.d.next = self.parent.val();
                            self.probe.d.next = self.shifted.val();
                        } else {
                            for i in 0..8 {
                                if self.level_of[i].val() == self.parent.val() {
                                    self.held[i].d.next = self.held[i].q.val() + 1;
                                }
                            }
                            self.state.d.next = BuildState::Input;
                        }
                    } else {
                        // The first leaf that differs: the parent and its
                        // ancestors are mixed; their held leaves go first.
                        self.mixed.d.next = self.mixed.q.val() | self.from_parent.val();
                        self.flush_stop.d.next = self.parent.val();
                        self.after_flush.d.next = BuildState::Leaf;
                        self.state.d.next = BuildState::Flush;
                    }
                }
            }
            self.out_valid_q.d.next = self.emit.val();
            self.out_node_q.d.next = self.node.val();
        }
        if self.reset.val() {
            self.state.d.next = BuildState::Input;
            self.mixed.d.next = 0.into();
            self.count.d.next = 0.into();
            self.out_valid_q.d.next = false;
            for i in 0..8 {
                self.held[i].d.next = 0.into();
            }
        }
    }
}

// The loops over the levels are written with a literal.
const _: () = assert!(HELD_LEVELS == 8 && BUILDER_MAX_LEVEL as usize == HELD_LEVELS + 2);
