//! The cycle model of the octree builder ([`super::octree_builder`]), the
//! octree engine's voxel → octree conversion: the same state machine, clock
//! edge by clock edge, for one voxel model streamed in (the writer of the
//! nodes always ready).
//!
//! **Order.** The builder reads the grid a *brick* a clock: a level-2 cell
//! of 4×4×4 voxels, one 64-bit word ([`brick_words`]), the bricks in
//! *reverse* Morton order, octant 7 first at every level. It writes each
//! cell's node after its children (postorder). That sequence, reversed, is
//! the canonical preorder of `tritri_geom::octree::tree` (a node, then its
//! children octant 0 first): the node memory is written from its top
//! address down and read from where the writer stopped.
//!
//! **Canonical form on the fly.** A uniform brick is a leaf; a brick that
//! is not is a mixed cell whose eight level-1 cells are written at once
//! (octant 7 first: a uniform one as a leaf, a mixed one as its eight
//! voxels and its mixed node). Above the bricks, a leaf child is not
//! written at once but *held* at its parent's level: a count and a type,
//! while the parent's children so far are leaves of one type. Eight held
//! leaves of one type make the parent a leaf of that type, passed up the
//! same way. The first child that differs, or a mixed brick inside the
//! parent, makes the parent and every ancestor mixed: the held leaves of
//! those levels are written first, outermost level first (in postorder they
//! precede everything inside the current cell), and every later leaf child
//! of a mixed cell is written at once. A mixed cell's node follows its
//! last child.
//!
//! **Clocks.** Each clock does one step: take a brick; write one held leaf
//! (a flush ends with a clock that finds none left); look at one level-1
//! cell of a mixed brick (writing it when it is a leaf); write one voxel of
//! a mixed level-1 cell, or its mixed node; write a leaf child of a mixed
//! cell; write a mixed node; or pass a completed cell's class up one level
//! (writing the parent's mixed node in the same clock when the child was
//! mixed and the parent is complete).

use tritri_geom::octree::tree::Node;

/// The smallest grid the builder takes: one brick, `2^2` voxels a side.
pub const BUILDER_MIN_LEVEL: u32 = 2;

/// The state machine's step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BuilderState {
    /// Waiting for a brick.
    Input,
    /// Writing held leaves of the levels >= `flush_stop`, highest first.
    Flush,
    /// Looking at the next level-1 cell of a mixed brick.
    Cells,
    /// Writing a mixed level-1 cell's voxels, octant 7 to 0.
    Voxels,
    /// Writing a mixed level-1 cell's node.
    Closed,
    /// Writing the leaf child that made its parent mixed.
    Leaf,
    /// Writing the mixed node of the cell at `cell_level`.
    Mixed,
    /// The cell at `cell_level` is complete: pass its class to its parent.
    Cascade,
}

/// What the builder wrote for one model: its nodes in the order written
/// (reverse preorder), the edge each was taken at (counted from 0, the edge
/// the first brick is offered at), and the edges until it is idle.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BuilderRun {
    pub nodes: Vec<Node>,
    pub edges: Vec<u64>,
    pub cycles: u64,
}

impl BuilderRun {
    /// The nodes in preorder (the node memory read from the last write).
    pub fn preorder(&self) -> Vec<Node> {
        self.nodes.iter().rev().copied().collect()
    }
}

/// The `2^level` grid's bricks (level >= 2) in the builder's order:
/// reverse Morton order, octant 7 first at every level. Bit `8 c + o` of a
/// brick is voxel `o` of its level-1 cell `c` (bit `k` of an octant: the
/// upper half along axis `k`).
pub fn brick_words(level: u32, voxel: impl Fn([usize; 3]) -> bool) -> Vec<u64> {
    let bricks = 1usize << (3 * (level - 2));
    (0..bricks)
        .map(|i| {
            let morton = bricks - 1 - i;
            // De-interleave the Morton code: bit 3j + k is bit j of axis k.
            let mut lo = [0usize; 3];
            for j in 0..(level as usize - 2) {
                for (k, c) in lo.iter_mut().enumerate() {
                    *c |= (morton >> (3 * j + k) & 1) << j;
                }
            }
            let mut word = 0u64;
            for c in 0..8 {
                for o in 0..8 {
                    let p = [0, 1, 2].map(|k| 4 * lo[k] + 2 * (c >> k & 1) + (o >> k & 1));
                    word |= u64::from(voxel(p)) << (8 * c + o);
                }
            }
            word
        })
        .collect()
}

/// The builder's registers.
struct Builder {
    level: u32,
    state: BuilderState,
    /// Per level (3 to `level`): the cell is known mixed; leaves held, and
    /// their type (true: full).
    mixed: [bool; 16],
    held: [u8; 16],
    full: [bool; 16],
    /// The bricks taken so far in this model.
    count: u64,
    /// The cell being passed up: its level, its position (bits 2..0: its
    /// octant counted from 7 down, 7 the parent's last), its class.
    cell_level: u32,
    probe: u64,
    cell_full: bool,
    cell_mixed: bool,
    flush_stop: u32,
    /// The state after a flush: `Cells` or `Leaf`.
    after_flush: BuilderState,
    /// A mixed brick, shifted so that the level-1 cell looked at is its top
    /// byte; the level-1 cells left after it.
    brick: u64,
    cells_left: u8,
    mask: u8,
    voxel: u8,
}

impl Builder {
    /// The highest level >= `from` holding leaves.
    fn highest_held(&self, from: u32) -> Option<u32> {
        (from..=self.level)
            .rev()
            .find(|&l| self.held[l as usize] != 0)
    }

    /// Marks `from` and every level above it mixed, and flushes their held
    /// leaves before going to `then`.
    fn mix_from(&mut self, from: u32, then: BuilderState) {
        for l in from..=self.level {
            self.mixed[l as usize] = true;
        }
        self.flush_stop = from;
        self.after_flush = then;
        self.state = BuilderState::Flush;
    }

    fn reset_level(&mut self, l: u32) {
        self.mixed[l as usize] = false;
        self.held[l as usize] = 0;
    }

    /// After a level-1 cell of a mixed brick: the next, or the brick's node.
    fn next_cell(&mut self) {
        self.brick <<= 8;
        if self.cells_left == 0 {
            self.state = BuilderState::Mixed;
        } else {
            self.cells_left -= 1;
            self.state = BuilderState::Cells;
        }
    }

    /// One clock edge with `input` offered; returns the node written and
    /// whether the input was taken.
    fn step(&mut self, input: Option<u64>) -> (Option<Node>, bool) {
        let leaf = |full: bool| if full { Node::Full } else { Node::Empty };
        let complete = self.probe & 7 == 7;
        let parent = self.cell_level + 1;
        match self.state {
            BuilderState::Input => {
                let Some(brick) = input else {
                    return (None, false);
                };
                self.probe = self.count;
                self.count += 1;
                self.cell_level = 2;
                if brick == 0 || brick == u64::MAX {
                    self.cell_full = brick == u64::MAX;
                    self.cell_mixed = false;
                    self.state = BuilderState::Cascade;
                } else {
                    self.brick = brick;
                    self.cells_left = 7;
                    self.mix_from(3, BuilderState::Cells);
                }
                (None, true)
            }
            BuilderState::Flush => match self.highest_held(self.flush_stop) {
                Some(top) => {
                    self.held[top as usize] -= 1;
                    (Some(leaf(self.full[top as usize])), false)
                }
                None => {
                    self.state = self.after_flush;
                    (None, false)
                }
            },
            BuilderState::Cells => {
                let cell = (self.brick >> 56) as u8;
                if cell == 0 || cell == 0xff {
                    self.next_cell();
                    (Some(leaf(cell == 0xff)), false)
                } else {
                    self.mask = cell;
                    self.voxel = 7;
                    self.state = BuilderState::Voxels;
                    (None, false)
                }
            }
            BuilderState::Voxels => {
                let node = leaf(self.mask >> self.voxel & 1 == 1);
                if self.voxel == 0 {
                    self.state = BuilderState::Closed;
                } else {
                    self.voxel -= 1;
                }
                (Some(node), false)
            }
            BuilderState::Closed => {
                self.next_cell();
                (Some(Node::Mixed), false)
            }
            BuilderState::Leaf => {
                if complete {
                    self.cell_level = parent;
                    self.probe >>= 3;
                    self.state = BuilderState::Mixed;
                } else {
                    self.state = BuilderState::Input;
                }
                (Some(leaf(self.cell_full)), false)
            }
            BuilderState::Mixed => {
                self.reset_level(self.cell_level);
                self.cell_mixed = true;
                self.state = BuilderState::Cascade;
                (Some(Node::Mixed), false)
            }
            BuilderState::Cascade => {
                if self.cell_level == self.level {
                    // The root: a leaf root is the whole tree.
                    self.count = 0;
                    self.state = BuilderState::Input;
                    return ((!self.cell_mixed).then(|| leaf(self.cell_full)), false);
                }
                let p = parent as usize;
                if self.cell_mixed {
                    self.state = BuilderState::Input;
                    if complete {
                        self.reset_level(parent);
                        self.cell_level = parent;
                        self.probe >>= 3;
                        self.state = BuilderState::Cascade;
                        return (Some(Node::Mixed), false);
                    }
                    return (None, false);
                }
                if self.mixed[p] {
                    if complete {
                        self.cell_level = parent;
                        self.probe >>= 3;
                        self.state = BuilderState::Mixed;
                    } else {
                        self.state = BuilderState::Input;
                    }
                    return (Some(leaf(self.cell_full)), false);
                }
                if self.held[p] == 0 || self.full[p] == self.cell_full {
                    self.full[p] = self.cell_full;
                    if complete {
                        // Eight leaves of one type: the parent is one.
                        self.reset_level(parent);
                        self.cell_level = parent;
                        self.probe >>= 3;
                    } else {
                        self.held[p] += 1;
                        self.state = BuilderState::Input;
                    }
                    return (None, false);
                }
                self.mix_from(parent, BuilderState::Leaf);
                (None, false)
            }
        }
    }
}

/// The builder's nodes and edges for the bricks of one `2^level` model
/// (2 to 10) offered one after another.
pub fn builder_schedule(level: u32, bricks: &[u64]) -> BuilderRun {
    let mut b = Builder {
        level,
        state: BuilderState::Input,
        mixed: [false; 16],
        held: [0; 16],
        full: [false; 16],
        count: 0,
        cell_level: 2,
        probe: 0,
        cell_full: false,
        cell_mixed: false,
        flush_stop: 3,
        after_flush: BuilderState::Input,
        brick: 0,
        cells_left: 0,
        mask: 0,
        voxel: 0,
    };
    let mut run = BuilderRun::default();
    let mut next = 0usize;
    let mut shown = false;
    let mut edge = 0u64;
    while next < bricks.len() || b.state != BuilderState::Input || b.count != 0 || shown {
        let (node, taken) = b.step(bricks.get(next).copied());
        next += usize::from(taken);
        shown = false;
        if let Some(node) = node {
            run.nodes.push(node);
            // Shown after this edge, taken at the next.
            run.edges.push(edge + 1);
            shown = true;
        }
        edge += 1;
    }
    run.cycles = edge;
    run
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use tritri_geom::octree::tree::Octree;
    use tritri_geom::octree::voxels::VoxelGrid;

    /// Random models at every level to 5 (sparse, dense, blocky), and the
    /// empty and full grids: the builder's nodes, reversed, are the
    /// canonical tree's.
    #[test]
    fn reversed_nodes_are_the_canonical_preorder() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for level in BUILDER_MIN_LEVEL..=5u32 {
            for round in 0..12 {
                let mut grid = VoxelGrid::empty(level);
                let n = 1usize << level;
                match round {
                    0 => {}
                    1 => grid.fill_cube([0; 3], level),
                    _ => {
                        let p = [0.02, 0.3, 0.7, 0.98][round % 4];
                        // Blocks of side 2^b, filled with probability p.
                        let b = rng.gen_range(0..level);
                        for z in (0..n).step_by(1 << b) {
                            for y in (0..n).step_by(1 << b) {
                                for x in (0..n).step_by(1 << b) {
                                    if rng.gen_bool(p) {
                                        grid.fill_cube([x, y, z], b);
                                    }
                                }
                            }
                        }
                    }
                }
                let masks = brick_words(level, |p| grid.get(p));
                let run = builder_schedule(level, &masks);
                assert_eq!(
                    run.preorder(),
                    Octree::from_voxels(&grid).nodes(),
                    "level {level} round {round}"
                );
                assert!(
                    run.cycles >= masks.len() as u64 + 1
                        && run.edges.windows(2).all(|w| w[0] < w[1])
                );
            }
        }
    }
}
