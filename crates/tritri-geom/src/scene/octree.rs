//! The octree broad phase: the common box subdivided with the octree
//! engine's triangle–cell classifier until each leaf's arrays fit the
//! memories and splitting no longer lowers the system's cycle count; one
//! batch per leaf that holds triangles of both objects.
//!
//! # Why no pair is lost
//!
//! Work on the scene's integer grid. If the quantized triangles `a` and `b`
//! share a point `p`, then `p` lies in the integer common box (see
//! [`super::prepare`]), which the root cell covers. The leaves' closed cells
//! cover the root, so some leaf `L` holds `p`; `a` and `b` both meet the
//! closed cell of `L` at `p`, the classifier is exact, so both are in `L`'s
//! arrays and the pair is tested there, whole (a leaf tests its triangles,
//! not their parts inside the cell), or, with [`LocalFrames`], decided by
//! the host when one of them does not fit `L`'s window. A cell with no
//! triangle of one object is never scheduled, and loses nothing: no pair
//! has a point there.
//!
//! # One owner per pair
//!
//! Two triangles may share several leaves and be tested in each. Leaves are
//! numbered in the order they are scheduled (depth first, octant order),
//! and a pair is reported only by its *owner*: the first leaf that holds
//! both ([`OctreeSchedule::owner`]). Every intersecting pair has at least
//! one common leaf (above), so it is reported exactly once.
//!
//! # When to split
//!
//! A leaf costs what the system's cycle model says a batch of its sizes
//! costs ([`BatchCost`]), its arrays cut into tiles of at most the memory
//! depth (so an array that does not fit costs its tiles). A cell is split
//! when its children, scheduled as leaves, cost less. A subtree also costs
//! the binning unit's classification of every cell in it that is split or
//! looked into ([`BatchCost::classify_cycles`]), so a split must save more
//! narrow-phase cycles than its children take to classify. Splitting that does
//! not pay at once is still tried [`LOOKAHEAD`] levels deeper (a triangle
//! straddling the centre planes only separates one level down), and kept
//! only if the subtree is cheaper. A binner that sends leaves on as it
//! decides them ([`BatchCost::streams_leaves`]) keeps every split that
//! paid at once (its children as leaves cost less) without looking back;
//! only the subtrees it tries on lookahead are compared after the fact,
//! and their leaves wait until then. A leaf over the memory depth does not
//! force a split: triangles that overlap over an area (coplanar, or many
//! sharing a point) stay in every cell around them however deep the tree
//! goes, so forcing would multiply cells without end; such a leaf is tiled
//! instead. (Only [`LocalFrames`] force splits, down to a fixed level.)

use super::TaggedTriangle;
use crate::bounding_volume::Aabb;
use crate::octree::cell::Cell;
use crate::octree::triangle_cell::{CellValues, TriangleCellTest, BROAD_PHASE_MARGIN};
use std::collections::HashMap;
use std::ops::Range;

/// How many levels a split that does not pay at once is pursued.
pub const LOOKAHEAD: u32 = 2;

/// The cycles one batch of `a` A-triangles and `b` B-triangles adds to a
/// run, from the system's cycle model (implemented by the hardware crate's
/// configuration; arrays already cut to the memory depth).
pub trait BatchCost {
    fn batch_cycles(&self, a: usize, b: usize) -> u64;

    /// The cycles a binning unit spends classifying one cell of `a`
    /// A-triangles and `b` B-triangles into its children (0 when the host
    /// bins).
    fn classify_cycles(&self, _a: usize, _b: usize) -> u64 {
        0
    }

    /// Does the binner send leaves on as it decides them (so a split that
    /// paid at once is never turned back into a leaf)?
    fn streams_leaves(&self) -> bool {
        false
    }
}

/// One scheduled leaf: its cell and its arrays in [`OctreeSchedule::a`] and
/// [`OctreeSchedule::b`], whose coordinates are the grid's minus `offset`
/// (zero without local frames).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Leaf {
    pub cell: Cell,
    pub offset: [i64; 3],
    pub a: Range<usize>,
    pub b: Range<usize>,
}

/// Leaves in frames of their own: the scene is quantized onto one fine
/// grid, and each leaf's triangles are sent to `width`-bit hardware as grid
/// coordinates minus the leaf cell's centre. An exact integer translation
/// changes no verdict, so "exact on the grid" still means one grid, whose
/// step is finer than one W-bit frame over the whole box could give. Cells
/// wider than `2^(width - 2)` steps are always split, so a leaf's cell
/// takes at most a quarter of its window, and every triangle short enough
/// ([`LocalFrames::fits_any_leaf`]) fits the window of every leaf it
/// meets. A longer triangle is not binned at all: the host decides it
/// against every triangle of the other object on the grid
/// ([`OctreeSchedule::host_arrays`]); binning it would force splits around
/// it to no purpose, without end when the grid is much finer than W.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LocalFrames {
    pub width: u32,
}

impl LocalFrames {
    /// The largest cell level a leaf may have.
    pub fn max_leaf_level(&self) -> u32 {
        self.width - 2
    }

    /// Can `t` fit the window of every leaf it may meet? A leaf's cell has
    /// side `s <= 2^(W-2)` and its window is centred on it, so a triangle
    /// touching the cell lies within `s/2 + e` of the centre, `e` its
    /// largest extent along an axis: it fits when
    /// `e <= 2^(W-1) - 1 - 2^(W-3)`.
    pub fn fits_any_leaf(&self, t: &TaggedTriangle) -> bool {
        let limit = (1i64 << (self.width - 1)) - 1 - (1i64 << (self.width - 3));
        (0..3).all(|k| {
            let (lo, hi) = t.triangle.iter().fold((i64::MAX, i64::MIN), |(lo, hi), p| {
                (lo.min(p[k]), hi.max(p[k]))
            });
            hi - lo <= limit
        })
    }

    /// Is every coordinate of `t - offset` a W-bit integer?
    fn fits(&self, t: &TaggedTriangle, offset: [i64; 3]) -> bool {
        let half = 1i64 << (self.width - 1);
        t.triangle
            .iter()
            .all(|p| (0..3).all(|k| (-half..half).contains(&(p[k] - offset[k]))))
    }
}

/// The leaves of the octree broad phase, with everything worth reporting.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct OctreeSchedule {
    pub root: Option<Cell>,
    /// Leaves holding triangles of both objects, in schedule order.
    pub leaves: Vec<Leaf>,
    /// Every leaf's A-array, concatenated in leaf order (a triangle in
    /// several leaves appears once per leaf).
    pub a: Vec<TaggedTriangle>,
    pub b: Vec<TaggedTriangle>,
    /// Cells the classifier visited (each classifies its triangles into
    /// its eight children).
    pub cells_visited: u64,
    /// Triangle–cell classifications: the sum over visited cells of the
    /// triangles in them (each one classified into the eight children).
    pub classifications: u64,
    /// The binning unit's cycles for those classifications
    /// ([`BatchCost::classify_cycles`] summed over the visited cells).
    pub classify_cycles: u64,
    /// Triangles binned: the entries the root starts with (A's and B's
    /// triangles that touch the root and fit a leaf).
    pub binned: u64,
    /// What the host decides on the grid ([`LocalFrames`]), as pairs of
    /// arrays, every pair of each: A's long triangles against all of B's,
    /// and A's binned triangles against B's long ones. Grid coordinates.
    pub host_arrays: Vec<(Vec<TaggedTriangle>, Vec<TaggedTriangle>)>,
    /// Largest depth of a scheduled leaf below the root.
    pub tree_depth: u32,
    /// Leaves whose arrays still exceed the memory depth (splitting them
    /// further would not lower the cycle count); they are tiled like the
    /// flat system's arrays.
    pub oversized_leaves: usize,
    /// `leaves_of_a[id]`: the scheduled leaves holding A's triangle `id`, ascending.
    leaves_of_a: HashMap<u32, Vec<u32>>,
    leaves_of_b: HashMap<u32, Vec<u32>>,
}

impl OctreeSchedule {
    /// The leaf that reports the pair: the first that holds both triangles
    /// (`None` if no leaf does, so the pair was never tested).
    pub fn owner(&self, a_id: u32, b_id: u32) -> Option<usize> {
        let (la, lb) = (self.leaves_of_a.get(&a_id)?, self.leaves_of_b.get(&b_id)?);
        let (mut i, mut j) = (0, 0);
        while i < la.len() && j < lb.len() {
            match la[i].cmp(&lb[j]) {
                std::cmp::Ordering::Less => i += 1,
                std::cmp::Ordering::Greater => j += 1,
                std::cmp::Ordering::Equal => return Some(la[i] as usize),
            }
        }
        None
    }

    pub fn leaf_arrays(&self, leaf: &Leaf) -> (&[TaggedTriangle], &[TaggedTriangle]) {
        (&self.a[leaf.a.clone()], &self.b[leaf.b.clone()])
    }
}

/// A triangle on its way down the tree: its test functions' values over
/// the current cell.
struct Item<'t> {
    triangle: &'t TaggedTriangle,
    test: &'t TriangleCellTest,
    values: CellValues,
}

/// A subtree's plan: the leaves it schedules and their cost.
struct Plan<'t> {
    cost: u64,
    leaves: Vec<(Cell, u32, Vec<&'t TaggedTriangle>, Vec<&'t TaggedTriangle>)>,
}

/// Subdivides `root_box` (the integer common box) over the arrays `a` and
/// `b` (triangles that touch it) as the module documentation says.
/// With `local_frames`, leaves are sent in frames of their own
/// ([`LocalFrames`]).
pub fn schedule(
    a: &[TaggedTriangle],
    b: &[TaggedTriangle],
    root_box: &Aabb<i64>,
    memory_depth: usize,
    cost: &dyn BatchCost,
    local_frames: Option<LocalFrames>,
) -> OctreeSchedule {
    let root = Cell::covering(root_box);
    let mut out = OctreeSchedule {
        root: Some(root),
        ..Default::default()
    };
    if a.is_empty() || b.is_empty() {
        return out;
    }
    // Triangles too long for any leaf's window go to the host.
    let b_all = b;
    let (a, a_long): (Vec<TaggedTriangle>, Vec<TaggedTriangle>) = a
        .iter()
        .partition(|t| local_frames.is_none_or(|l| l.fits_any_leaf(t)));
    let (b, b_long): (Vec<TaggedTriangle>, Vec<TaggedTriangle>) = b
        .iter()
        .partition(|t| local_frames.is_none_or(|l| l.fits_any_leaf(t)));
    if !a_long.is_empty() {
        out.host_arrays.push((a_long, b_all.to_vec()));
    }
    if !b_long.is_empty() && !a.is_empty() {
        out.host_arrays.push((a.clone(), b_long));
    }
    let (a, b) = (&a[..], &b[..]);
    let tests_a: Vec<TriangleCellTest> = a
        .iter()
        .map(|t| TriangleCellTest::widened(&t.triangle, BROAD_PHASE_MARGIN))
        .collect();
    let tests_b: Vec<TriangleCellTest> = b
        .iter()
        .map(|t| TriangleCellTest::widened(&t.triangle, BROAD_PHASE_MARGIN))
        .collect();
    // The root's values take multiplications; every cell below, adds and shifts.
    let planner = Planner {
        memory_depth,
        cost,
        max_leaf_level: local_frames.map(|l| l.max_leaf_level()),
    };
    let mut work = Work::default();
    let plan = planner.plan(
        root,
        0,
        root_items(a, &tests_a, &root),
        root_items(b, &tests_b, &root),
        LOOKAHEAD,
        &mut work,
    );
    out.cells_visited = work.cells;
    out.classifications = work.classifications;
    out.classify_cycles = work.classify_cycles;
    out.binned = (a.len() + b.len()) as u64;
    for (index, (cell, level, la, lb)) in plan.leaves.into_iter().enumerate() {
        let start = (out.a.len(), out.b.len());
        for t in &la {
            out.leaves_of_a.entry(t.id).or_default().push(index as u32);
        }
        for t in &lb {
            out.leaves_of_b.entry(t.id).or_default().push(index as u32);
        }
        let offset = match local_frames {
            Some(_) => cell.lo.map(|v| v + cell.size() / 2),
            None => [0; 3],
        };
        let translate = |t: &&TaggedTriangle| {
            // Never fails: every binned triangle fits every leaf's window.
            assert!(
                local_frames.is_none_or(|l| l.fits(t, offset)),
                "triangle {} outside the window of leaf {cell:?}",
                t.id
            );
            TaggedTriangle {
                id: t.id,
                triangle: t.triangle.map(|p| [0, 1, 2].map(|k| p[k] - offset[k])),
            }
        };
        out.a.extend(la.iter().map(translate));
        out.b.extend(lb.iter().map(translate));
        let leaf = Leaf {
            cell,
            offset,
            a: start.0..out.a.len(),
            b: start.1..out.b.len(),
        };
        if leaf.a.len() > memory_depth || leaf.b.len() > memory_depth {
            out.oversized_leaves += 1;
        }
        out.tree_depth = out.tree_depth.max(level);
        out.leaves.push(leaf);
    }
    out
}

/// What the planner did, for the report.
#[derive(Default)]
struct Work {
    cells: u64,
    classifications: u64,
    classify_cycles: u64,
}

struct Planner<'c> {
    /// Triangles per array the memories hold.
    memory_depth: usize,
    cost: &'c dyn BatchCost,
    /// Cells above this level must be split ([`LocalFrames`]).
    max_leaf_level: Option<u32>,
}

impl Planner<'_> {
    /// Cost of a leaf with these array sizes, tiled to the memory depth.
    fn leaf_cost(&self, na: usize, nb: usize) -> u64 {
        if na == 0 || nb == 0 {
            return 0;
        }
        let tiles = |n: usize| {
            (0..n.div_ceil(self.memory_depth))
                .map(move |t| (n - t * self.memory_depth).min(self.memory_depth))
        };
        tiles(na)
            .map(|ta| {
                tiles(nb)
                    .map(|tb| self.cost.batch_cycles(ta, tb))
                    .sum::<u64>()
            })
            .sum()
    }

    /// A leaf of these arrays.
    fn leaf<'t>(&self, cell: Cell, level: u32, a: &[Item<'t>], b: &[Item<'t>]) -> Plan<'t> {
        Plan {
            cost: self.leaf_cost(a.len(), b.len()),
            leaves: vec![(
                cell,
                level,
                a.iter().map(|i| i.triangle).collect(),
                b.iter().map(|i| i.triangle).collect(),
            )],
        }
    }

    /// Would classifying the cell (`classify` cycles) cost more than any
    /// split could save? Any subtree writes each of its triangles into some
    /// leaf's batch (at least `a + b + 1` cycles in the system's cycle
    /// model) after classifying the cell; if the cell as one leaf costs no
    /// more than that, it is not worth looking into. Only when classifying costs
    /// cycles (a binning unit, not the host), and never where a split is
    /// forced.
    fn split_cannot_pay(&self, cell: &Cell, a: usize, b: usize, classify: u64) -> bool {
        let forced = self.max_leaf_level.is_some_and(|m| cell.level > m);
        classify > 0 && !forced && self.leaf_cost(a, b) <= (a + b + 1) as u64 + classify
    }

    fn plan<'t>(
        &self,
        cell: Cell,
        level: u32,
        a: Vec<Item<'t>>,
        b: Vec<Item<'t>>,
        slack: u32,
        work: &mut Work,
    ) -> Plan<'t> {
        if a.is_empty() || b.is_empty() {
            return Plan {
                cost: 0,
                leaves: Vec::new(),
            };
        }
        // The root's entries are classified as they stream in from the
        // host: its pass costs no more than an empty cell's, and it is
        // always looked into.
        let classify = if level == 0 {
            self.cost.classify_cycles(0, 0)
        } else {
            self.cost.classify_cycles(a.len(), b.len())
        };
        if !cell.splittable()
            || (level > 0 && self.split_cannot_pay(&cell, a.len(), b.len(), classify))
        {
            return self.leaf(cell, level, &a, &b);
        }
        // The cell's entries are classified.
        let entries = (a.len() + b.len()) as u64;
        work.cells += 1;
        work.classifications += entries;
        work.classify_cycles += classify;
        let mut plan = self.split_or_keep(cell, level, a, b, slack, work);
        // Deciding the cell cost its classification, whatever was decided.
        plan.cost += classify;
        plan
    }

    /// The cheaper of a classified cell as a leaf and its split subtree.
    fn split_or_keep<'t>(
        &self,
        cell: Cell,
        level: u32,
        a: Vec<Item<'t>>,
        b: Vec<Item<'t>>,
        slack: u32,
        work: &mut Work,
    ) -> Plan<'t> {
        let leaf_cost = self.leaf_cost(a.len(), b.len());
        let (children_a, children_b) = (split(&a), split(&b));
        let children_cost: u64 = (0..8)
            .map(|o| self.leaf_cost(children_a[o].len(), children_b[o].len()))
            .sum();
        let forced = self.max_leaf_level.is_some_and(|m| cell.level > m);
        let improving = forced || children_cost < leaf_cost;
        if !improving && slack == 0 {
            return self.leaf(cell, level, &a, &b);
        }
        let next_slack = if improving { LOOKAHEAD } else { slack - 1 };
        let mut subtree = Plan {
            cost: 0,
            leaves: Vec::new(),
        };
        for (o, (ca, cb)) in children_a.into_iter().zip(children_b).enumerate() {
            let child = self.plan(cell.child(o), level + 1, ca, cb, next_slack, work);
            subtree.cost += child.cost;
            subtree.leaves.extend(child.leaves);
        }
        // A streaming binner has sent on the leaves of a split that paid.
        let kept = improving && self.cost.streams_leaves();
        if !forced && !kept && subtree.cost >= leaf_cost {
            self.leaf(cell, level, &a, &b)
        } else {
            subtree
        }
    }
}

fn root_items<'t>(
    ts: &'t [TaggedTriangle],
    tests: &'t [TriangleCellTest],
    root: &Cell,
) -> Vec<Item<'t>> {
    ts.iter()
        .zip(tests)
        .map(|(triangle, test)| Item {
            triangle,
            test,
            values: test.values(root),
        })
        .collect()
}

/// Each item into the children its triangle meets, with its values there.
fn split<'t>(items: &[Item<'t>]) -> [Vec<Item<'t>>; 8] {
    let mut children: [Vec<Item<'t>>; 8] = Default::default();
    for item in items {
        let mask = item.test.children_touched(&item.values);
        for (o, child) in children.iter_mut().enumerate() {
            if mask >> o & 1 == 1 {
                child.push(Item {
                    triangle: item.triangle,
                    test: item.test,
                    values: item.test.child(&item.values, o),
                });
            }
        }
    }
    children
}
