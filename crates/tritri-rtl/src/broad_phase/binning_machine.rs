//! The binning unit's cycle-exact model ([`super::binning_unit`]): the
//! depth-first controller, clock by clock, deciding each cell with the
//! broad phase's split rule (`tritri_geom::scene::octree`), so its leaves
//! are the planner's, cell for cell and triangle for triangle, and its
//! cycle count is the hardware's.
//!
//! # How the unit bins
//!
//! * **Memories.** Each object's triangles (their vertices) are written
//!   once, as the host streams them, into a triangle memory per lane.
//!   A *list* of a cell is the indices of the triangles in it; per object
//!   there are eight *list memories*, one per octant, two indices to a word,
//!   append-only: a cell's pass writes the list of its child `o` into
//!   memory `o`, so the eight lists are written side by side, one entry per
//!   lane per clock, and each list is contiguous. A list is `(memory,
//!   first word, count)`; the root's list is every triangle in order.
//! * **A pass** decides which children a cell's triangles meet. Per object
//!   two lanes read a word (two indices) per clock: triangle memory, the
//!   setup unit with the cell's low corner as its origin (so the values at
//!   the corner are zero and the classifier needs no stored values), the
//!   classifier step at the cell's level, and the mask's bits into the
//!   eight list memories. A cell of `a` and `b` triangles takes
//!   `max(ceil(a/2), ceil(b/2))` clocks and [`PASS_DRAIN`] more. The root's
//!   pass is the host's stream, one triangle per clock, through lane 0.
//! * **The decision** (the split rule): the leaf costs of the eight
//!   children and of the cell ([`super::leaf_cost`], one query per clock,
//!   [`COSTS_CLOCKS`]), then one clock: a leaf, or a *frame* pushed on the
//!   stack (the cell, its lists, its cost as a leaf, its classification
//!   cost, the cost of the subtree so far, the slack of the lookahead).
//! * **The children** of the top frame are visited in octant order: read
//!   the child's list counts (1 clock), skip it when one object is absent
//!   (1), else its leaf cost and the decision
//!   ([`super::leaf_cost::LEAF_COST_LATENCY`] clocks)
//!   and either a leaf at once (the rule's "cannot pay", or a unit cell) or
//!   a pass. Each visit returns its cost to the frame (1 clock).
//! * **A frame is finished** after its eighth child: the subtree is kept,
//!   or, when it cost at least the cell as a leaf, the leaves written since
//!   the frame was pushed are dropped (the leaf memory's write pointer goes
//!   back) and the cell is written as one leaf (1 clock, then 1 to bring the
//!   frame below back from the stack's memory).
//! * **Leaves** are `(cell, A list, B list)` descriptors in a leaf memory;
//!   the lists stay where the passes wrote them. After the root's frame, the
//!   unit streams the leaves out: each descriptor, then its A indices, then
//!   its B indices (the batch load the system's cycle model counts); a
//!   leaf with more triangles of one object than the system's memory depth goes
//!   out as tiles of at most the depth per object, every A tile with every B tile,
//!   each under a header of its own.

use super::leaf_cost::{leaf_cost, LEAF_COST_LATENCY};
use crate::octree::cell_classifier::CELL_CLASSIFIER_LATENCY;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::cell::Cell;
use tritri_geom::octree::triangle_cell::{TriangleCellTest, BROAD_PHASE_MARGIN};
use tritri_geom::scene::octree::LOOKAHEAD;

/// Clocks after a pass's last read until its lists and counts are final:
/// list memory (1), triangle memory (1), setup and classifier (the last
/// masks are written into the list memories as they come out), and the
/// packers' flush of a half word (1).
pub const PASS_DRAIN: u64 = 2
    + crate::octree::triangle_setup::TRIANGLE_SETUP_LATENCY as u64
    + CELL_CLASSIFIER_LATENCY as u64
    + 1;
/// Clocks of the cost queries after a pass: the eight children and the
/// cell, one per clock, and the last one's latency.
pub const COSTS_CLOCKS: u64 = 9 + LEAF_COST_LATENCY as u64;
/// The list memory number of the root's list (every triangle in order).
pub const IDENTITY_LIST: u8 = 8;

/// The split rule's parameters, as the system is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BinningParams {
    /// The system's memory depth `depth 2^log_depth` triangles per array.
    pub log_depth: u32,
    /// `P = 2^log_pipelines` pipelines.
    pub log_pipelines: u32,
    /// Cells above this level are always split (local frames).
    pub max_leaf_level: Option<u32>,
}

/// A cell's list of one object's triangles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ListRef {
    /// List memory `0..8`, or [`IDENTITY_LIST`].
    pub memory: u8,
    /// First word (two indices to a word).
    pub start: u32,
    pub count: u32,
}

/// One leaf as the unit writes it: the cell and where its lists are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LeafDescriptor {
    pub cell: Cell,
    pub a: ListRef,
    pub b: ListRef,
}

/// What a run of the unit gives.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct BinningRun {
    pub leaves: Vec<LeafDescriptor>,
    /// Each leaf's A and B triangles (indices into the host's arrays).
    pub leaf_lists: Vec<(Vec<u32>, Vec<u32>)>,
    /// Clocks from the first triangle in to the root's frame finished.
    pub cycles: u64,
    /// Cells passed (classified into their children), the root included.
    pub cells: u64,
    /// Entries classified: the triangles of those cells.
    pub entries: u64,
    /// Words written into each object's eight list memories.
    pub list_words: [[u32; 8]; 2],
    /// Most frames on the stack at once.
    pub peak_frames: usize,
    /// Most leaf descriptors held at once (dropped ones included).
    pub peak_leaves: usize,
}

/// The classification cost the split rule charges a cell of `a` and `b`
/// triangles (`binning_cost::cell_cycles`).
fn classify_cost(a: u64, b: u64) -> u64 {
    super::binning_cost::cell_cycles(a, b)
}

struct Frame {
    cell: Cell,
    lists: [ListRef; 2],
    leaf_cost: u64,
    classify: u64,
    subtree: u64,
    slack_next: u32,
    forced: bool,
    leaf_mark: usize,
    children: [[ListRef; 2]; 8],
}

struct Machine<'t> {
    params: BinningParams,
    tests: [Vec<TriangleCellTest>; 2],
    _triangles: [&'t [FixedTriangle]; 2],
    /// `memories[object][octant]`: words of two indices (`None`: padding).
    memories: [[Vec<[Option<u32>; 2]>; 8]; 2],
    run: BinningRun,
}

impl Machine<'_> {
    fn list(&self, object: usize, list: ListRef) -> Vec<u32> {
        if list.memory == IDENTITY_LIST {
            return (0..list.count).collect();
        }
        let words = &self.memories[object][list.memory as usize][list.start as usize..];
        words
            .iter()
            .flatten()
            .flatten()
            .copied()
            .take(list.count as usize)
            .collect()
    }

    /// One pass over `cell`'s lists: the children's lists appended to the
    /// list memories, side by side. Returns the eight children's lists.
    fn pass(&mut self, cell: Cell, lists: [ListRef; 2]) -> [[ListRef; 2]; 8] {
        let mut children = [[ListRef::default(); 2]; 8];
        for object in 0..2 {
            let entries = self.list(object, lists[object]);
            let mut per_child: [Vec<u32>; 8] = Default::default();
            for &index in &entries {
                // A unit cell has no children (the root may be one; it is then a leaf).
                let mask = if cell.splittable() {
                    self.tests[object][index as usize].children_of_cell(&cell)
                } else {
                    0
                };
                for (o, child) in per_child.iter_mut().enumerate() {
                    if mask >> o & 1 == 1 {
                        child.push(index);
                    }
                }
            }
            for (o, child) in per_child.into_iter().enumerate() {
                let memory = &mut self.memories[object][o];
                children[o][object] = ListRef {
                    memory: o as u8,
                    start: memory.len() as u32,
                    count: child.len() as u32,
                };
                memory.extend(
                    child
                        .chunks(2)
                        .map(|pair| [Some(pair[0]), pair.get(1).copied()]),
                );
            }
            self.run.entries += entries.len() as u64;
        }
        self.run.cells += 1;
        children
    }

    fn leaf_cost(&self, lists: [ListRef; 2]) -> u64 {
        leaf_cost(
            lists[0].count as u64,
            lists[1].count as u64,
            self.params.log_depth,
            self.params.log_pipelines,
        )
    }

    fn forced(&self, cell: &Cell) -> bool {
        self.params.max_leaf_level.is_some_and(|m| cell.level > m)
    }

    fn emit(&mut self, cell: Cell, lists: [ListRef; 2]) {
        self.run.leaves.push(LeafDescriptor {
            cell,
            a: lists[0],
            b: lists[1],
        });
        self.run.peak_leaves = self.run.peak_leaves.max(self.run.leaves.len());
    }

    /// After a cell's pass: its costs, then the decision (1 clock). Returns
    /// the frame to push, or the cell's cost when it is a leaf.
    fn decide(
        &mut self,
        cell: Cell,
        lists: [ListRef; 2],
        children: [[ListRef; 2]; 8],
        classify: u64,
        slack: u32,
    ) -> Result<Frame, u64> {
        self.run.cycles += COSTS_CLOCKS + 1;
        let leaf_cost = self.leaf_cost(lists);
        if lists[0].count == 0 || lists[1].count == 0 {
            return Err(0);
        }
        let children_cost: u64 = children.iter().map(|c| self.leaf_cost(*c)).sum();
        let forced = self.forced(&cell);
        let improving = forced || children_cost < leaf_cost;
        if !cell.splittable() || (!improving && slack == 0) {
            self.emit(cell, lists);
            return Err(leaf_cost + classify);
        }
        let slack_next = if improving { LOOKAHEAD } else { slack - 1 };
        Ok(Frame {
            cell,
            lists,
            leaf_cost,
            classify,
            subtree: 0,
            slack_next,
            forced,
            leaf_mark: self.run.leaves.len(),
            children,
        })
    }

    /// Visits child `octant` of the top frame; returns its cost or the
    /// frame its pass pushes.
    fn visit(&mut self, top: &Frame, octant: usize) -> Result<Frame, u64> {
        // Read the child's lists (1), look at the counts (1).
        self.run.cycles += 2;
        let lists = top.children[octant];
        let (a, b) = (lists[0].count as u64, lists[1].count as u64);
        if a == 0 || b == 0 {
            return Err(0);
        }
        // Its leaf cost (queried as the counts are looked at), then the
        // decision before a pass (1).
        self.run.cycles += LEAF_COST_LATENCY as u64;
        let cell = top.cell.child(octant);
        let classify = classify_cost(a, b);
        let leaf_cost = self.leaf_cost(lists);
        let cannot_pay = !self.forced(&cell) && leaf_cost <= a + b + 1 + classify;
        if !cell.splittable() || cannot_pay {
            self.emit(cell, lists);
            return Err(leaf_cost);
        }
        self.run.cycles += a.div_ceil(2).max(b.div_ceil(2)) + PASS_DRAIN;
        let children = self.pass(cell, lists);
        self.decide(cell, lists, children, classify, top.slack_next)
    }

    fn bin(&mut self, root: Cell) {
        let counts = [
            self._triangles[0].len() as u32,
            self._triangles[1].len() as u32,
        ];
        let lists = counts.map(|count| ListRef {
            memory: IDENTITY_LIST,
            start: 0,
            count,
        });
        // The root's pass is the stream.
        self.run.cycles += (counts[0] + counts[1]) as u64 + PASS_DRAIN;
        let children = self.pass(root, lists);
        // Frames and the octant each visits next.
        let mut stack: Vec<(Frame, usize)> = Vec::new();
        let mut returned = match self.decide(root, lists, children, classify_cost(0, 0), LOOKAHEAD)
        {
            Ok(frame) => {
                stack.push((frame, 0));
                None
            }
            Err(cost) => Some(cost),
        };
        loop {
            self.run.peak_frames = self.run.peak_frames.max(stack.len());
            if let Some(cost) = returned.take() {
                // The cost goes to the top frame (1).
                self.run.cycles += 1;
                let Some((top, next)) = stack.last_mut() else {
                    break;
                };
                top.subtree += cost;
                *next += 1;
                if *next < 8 {
                    continue;
                }
                // Finish the frame (1), bring the one below back (1).
                self.run.cycles += 2;
                let (frame, _) = stack.pop().expect("a top frame");
                let cost = if !frame.forced && frame.subtree >= frame.leaf_cost {
                    self.run.leaves.truncate(frame.leaf_mark);
                    self.emit(frame.cell, frame.lists);
                    frame.leaf_cost + frame.classify
                } else {
                    frame.subtree + frame.classify
                };
                returned = Some(cost);
                continue;
            }
            let (top, next) = stack.last().expect("a frame to visit");
            match self.visit(top, *next) {
                Ok(frame) => stack.push((frame, 0)),
                Err(cost) => returned = Some(cost),
            }
        }
    }
}

/// Bins `a` and `b` (the host's arrays, in the order they are streamed)
/// under `root` as the unit does.
pub fn run_binning(
    a: &[FixedTriangle],
    b: &[FixedTriangle],
    root: Cell,
    params: BinningParams,
) -> BinningRun {
    let mut machine = Machine {
        params,
        tests: [a, b].map(|ts| {
            ts.iter()
                .map(|t| TriangleCellTest::widened(t, BROAD_PHASE_MARGIN))
                .collect()
        }),
        _triangles: [a, b],
        memories: Default::default(),
        run: BinningRun::default(),
    };
    machine.bin(root);
    for object in 0..2 {
        for o in 0..8 {
            machine.run.list_words[object][o] = machine.memories[object][o].len() as u32;
        }
    }
    let lists: Vec<_> = machine
        .run
        .leaves
        .iter()
        .map(|l| (machine.list(0, l.a), machine.list(1, l.b)))
        .collect();
    machine.run.leaf_lists = lists;
    machine.run
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::system::SystemConfig;
    use tritri_geom::bounding_volume::Aabb;
    use tritri_geom::scene::octree::{schedule, LocalFrames};
    use tritri_geom::scene::TaggedTriangle;

    fn scene(seed: u64, n: usize, spread: i64, size: i64) -> Vec<TaggedTriangle> {
        // A small deterministic generator: triangles near a diagonal band.
        let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        let mut next = move |m: i64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % (2 * m as u64 + 1)) as i64 - m
        };
        (0..n)
            .map(|i| {
                let c = [next(spread), next(spread), next(spread)];
                let triangle = [0, 1, 2].map(|_| [0, 1, 2].map(|k| c[k] + next(size)));
                TaggedTriangle {
                    id: i as u32 * 3 + 1,
                    triangle,
                }
            })
            .collect()
    }

    /// The machine's leaves are the planner's, cell for cell and triangle
    /// for triangle, with and without local frames, at several depths.
    #[test]
    fn machine_leaves_equal_the_planner() {
        for (seed, n, spread, size, log_depth, local) in [
            (1, 300, 1000, 60, 3, None),
            (2, 900, 3000, 200, 4, None),
            (3, 400, 200, 40, 8, None),
            (4, 500, 1 << 14, 300, 5, Some(12)),
            (5, 60, 10, 10, 2, None),
        ] {
            let a = scene(seed, n, spread, size);
            let b = scene(seed + 100, n, spread, size);
            let mut config = SystemConfig::new(24, 2).with_pipeline_latency(30);
            config.triangles_per_bank = 1 << log_depth;
            let lo = [0, 1, 2].map(|k| {
                a.iter()
                    .chain(&b)
                    .flat_map(|t| t.triangle.map(|p| p[k]))
                    .min()
                    .unwrap()
            });
            let hi = [0, 1, 2].map(|k| {
                a.iter()
                    .chain(&b)
                    .flat_map(|t| t.triangle.map(|p| p[k]))
                    .max()
                    .unwrap()
            });
            let root_box = Aabb { lo, hi };
            let local_frames = local.map(|width| LocalFrames { width });
            let plan = schedule(
                &a,
                &b,
                &root_box,
                config.triangles_per_bank,
                &config,
                local_frames,
            );
            assert!(plan.host_arrays.is_empty());
            let params = BinningParams {
                log_depth,
                log_pipelines: 1,
                max_leaf_level: local.map(|w: u32| w - 2),
            };
            let run = run_binning(
                &a.iter().map(|t| t.triangle).collect::<Vec<_>>(),
                &b.iter().map(|t| t.triangle).collect::<Vec<_>>(),
                plan.root.unwrap(),
                params,
            );
            // Seed 5 is small enough for the root to stay one leaf, whose
            // lists are the streamed arrays themselves.
            if seed == 5 {
                assert_eq!(
                    (run.leaves.len(), run.leaves[0].a.memory),
                    (1, IDENTITY_LIST)
                );
            } else {
                assert!(
                    plan.leaves.len() > 3,
                    "seed {seed}: {} leaves",
                    plan.leaves.len()
                );
            }
            assert_eq!(run.leaves.len(), plan.leaves.len(), "seed {seed}");
            for ((leaf, (la, lb)), planned) in
                run.leaves.iter().zip(&run.leaf_lists).zip(&plan.leaves)
            {
                assert_eq!(leaf.cell, planned.cell, "seed {seed}");
                let ids = |list: &[u32], all: &[TaggedTriangle]| {
                    list.iter().map(|&i| all[i as usize].id).collect::<Vec<_>>()
                };
                assert_eq!(
                    ids(la, &a),
                    plan.a[planned.a.clone()]
                        .iter()
                        .map(|t| t.id)
                        .collect::<Vec<_>>(),
                    "seed {seed}"
                );
                assert_eq!(
                    ids(lb, &b),
                    plan.b[planned.b.clone()]
                        .iter()
                        .map(|t| t.id)
                        .collect::<Vec<_>>(),
                    "seed {seed}"
                );
            }
            assert_eq!(run.cells, plan.cells_visited, "seed {seed}");
        }
    }
}
