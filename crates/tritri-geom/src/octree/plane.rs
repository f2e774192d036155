//! Plane classification of an octree, the octree engine's core circuit
//! (`octree_engine.txt`): the signed distance `f(p) = n · p - d` of the
//! cube's corners to the plane; where its signs differ over a cell the cell
//! is split and its children's corner values are interpolated from the
//! parent's (adds and shifts, [`AffineOverBox::child`]); where they agree
//! the cell is uniform and only subdivided (here: filled at once).
//!
//! Results, on the `2^level` voxel grid with integer `n` and `d`:
//!
//! * the voxels the plane crosses: closed unit cells where `f` takes the
//!   value 0 (touching counts);
//! * the half-space solid `f <= 0`, the seed's "deletion by an infinite
//!   plane": a voxel belongs to it when its centre does, decided as
//!   `2 n · p + n · (1,1,1) <= 2 d` at its low corner `p`, exact in integers.
//!   A cell whose whole closed range lies at `f <= 0` holds only solid
//!   voxels and is one full leaf of the result's octree; one at `f > 0`,
//!   an empty leaf. The traversal emits the octree in preorder as it goes;
//!   [`Octree::to_voxels`] writes its full cells into a voxel memory a word
//!   at a time.

use super::affine::AffineOverBox;
use super::cell::Cell;
use super::stack_schedule::StackSchedule;
use super::tree::{collapse_if_uniform, Node, Octree};
use super::voxels::VoxelGrid;

/// What one classification of the grid against a plane found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PlaneClassification {
    /// Voxels the closed plane meets.
    pub crossed_voxels: u64,
    /// Cells whose corner values were interpolated (split cells).
    pub cells_split: u64,
    /// The voxels of the half-space `n · p <= d` (by their centres), as an
    /// octree: the traversal's uniform cells are its leaves.
    pub half_space: Octree,
}

/// Classifies the `2^level` grid against the plane `n · p = d`.
pub fn classify_plane(level: u32, normal: [i64; 3], d: i64) -> PlaneClassification {
    let root = Cell { lo: [0; 3], level };
    let gradient = normal.map(i128::from);
    let f = AffineOverBox::over_cell(gradient, &root);
    let mut nodes = Vec::new();
    let mut counts = (0u64, 0u64);
    // Twice the plane, so voxel centres (half-integers) are integers.
    let centre_offset: i128 = gradient.iter().sum();
    visit(root, f, d as i128, centre_offset, &mut counts, &mut nodes);
    let half_space = Octree::from_canonical(level, nodes);
    PlaneClassification {
        crossed_voxels: counts.0,
        cells_split: counts.1,
        half_space,
    }
}

/// Emits the nodes of `cell` in preorder; counts `(crossed voxels, splits)`.
fn visit(
    cell: Cell,
    f: AffineOverBox,
    d: i128,
    centre_offset: i128,
    counts: &mut (u64, u64),
    nodes: &mut Vec<Node>,
) {
    let (lo, hi) = f.range();
    if hi < d {
        // Wholly inside the open half-space: every centre is inside too.
        nodes.push(Node::Full);
        return;
    }
    if lo > d {
        nodes.push(Node::Empty);
        return;
    }
    if !cell.splittable() {
        counts.0 += 1;
        nodes.push(if 2 * f.at_lo + centre_offset <= 2 * d {
            Node::Full
        } else {
            Node::Empty
        });
        return;
    }
    counts.1 += 1;
    let at = nodes.len();
    nodes.push(Node::Mixed);
    for octant in 0..8 {
        visit(
            cell.child(octant),
            f.child(octant),
            d,
            centre_offset,
            counts,
            nodes,
        );
    }
    // A split cell whose voxels all fall on one side is one leaf.
    collapse_if_uniform(nodes, at);
}

/// One record of the hardware traversal (`tritri_rtl::octree::
/// plane_traversal`): a classified cell and which of its children belong
/// to the half-space as wholes (`full`: entirely below the plane, or, for a
/// level-1 cell, voxels whose centre is) and, for a level-1 cell, which
/// voxels the closed plane crosses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct TraversalRecord {
    pub lo: [i64; 3],
    pub level: u32,
    pub full: u8,
    pub crossed: u8,
}

/// The hardware traversal's run: its records in the order they leave, the
/// clock edge each is taken at (counted from 0, the edge that issues the
/// root; the reader always ready), and the edges the unit is busy.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TraversalRun {
    pub records: Vec<TraversalRecord>,
    pub edges: Vec<u64>,
    pub cycles: u64,
    /// Cells classified (one per issue: the root, then crossing cells).
    pub cells: u64,
    /// The most entries the stack's RAM held (the top register apart).
    pub stack_depth: usize,
}

impl TraversalRun {
    /// The half-space the records describe (full children filled whole).
    pub fn half_space(&self, level: u32) -> VoxelGrid {
        let mut grid = VoxelGrid::empty(level);
        for r in &self.records {
            let cell = Cell {
                lo: r.lo,
                level: r.level,
            };
            for o in (0..8).filter(|o| r.full >> o & 1 == 1) {
                let child = cell.child(o);
                grid.fill_cube(child.lo.map(|c| c as usize), child.level);
            }
        }
        grid
    }

    /// Word writes a memory-side unit needs to put the records' full
    /// children into a voxel memory of `word_bits`-voxel words along x
    /// (the layout of [`VoxelGrid`]): a cube of side `s` is `s^2` rows of
    /// `ceil(s / word_bits)` words (a row shorter than a word is one
    /// masked write).
    pub fn fill_words(&self, word_bits: u64) -> u64 {
        self.records
            .iter()
            .map(|r| {
                let side = 1u64 << r.level.saturating_sub(1);
                let per_child = side * side * side.div_ceil(word_bits);
                r.full.count_ones() as u64 * per_child
            })
            .sum()
    }

    /// Voxels the closed plane crosses.
    pub fn crossed_voxels(&self) -> u64 {
        self.records
            .iter()
            .map(|r| r.crossed.count_ones() as u64)
            .sum()
    }
}

/// Clock edges from an issue to its result in the hardware.
pub const TRAVERSAL_LATENCY: u64 = 5;

/// The cycle model of the hardware traversal: the same schedule, clock
/// edge by clock edge ([`StackSchedule`]): the root issued at edge 0, each
/// result taken [`TRAVERSAL_LATENCY`] edges after its issue, and a cell of
/// level >= 2 pushed with its crossing children. The masks are decided
/// here by [`AffineOverBox`] over each child directly.
pub fn traversal_schedule(level: u32, normal: [i64; 3], d: i64) -> TraversalRun {
    let gradient = normal.map(i128::from);
    let d = d as i128;
    let centre_offset: i128 = gradient.iter().sum();
    // A cell's record and the crossing children to descend into.
    let classify = |cell: Cell| -> (TraversalRecord, u8) {
        let f = AffineOverBox::over_cell(gradient, &cell);
        let (mut full, mut crossing) = (0u8, 0u8);
        for o in 0..8 {
            let child = f.child(o);
            let (lo, hi) = child.range();
            if lo <= d && d <= hi {
                crossing |= 1 << o;
                // A voxel by its centre: 2 f(lo) + Σn <= 2d.
                if cell.level == 1 && 2 * child.at_lo + centre_offset <= 2 * d {
                    full |= 1 << o;
                }
            } else if hi < d {
                full |= 1 << o;
            }
        }
        let crossed = if cell.level == 1 { crossing } else { 0 };
        let descend = if cell.level >= 2 { crossing } else { 0 };
        (
            TraversalRecord {
                lo: cell.lo,
                level: cell.level,
                full,
                crossed,
            },
            descend,
        )
    };
    let mut run = TraversalRun::default();
    let mut machine = StackSchedule::new(TRAVERSAL_LATENCY);
    machine.start(Cell { lo: [0; 3], level });
    // A record shown after the previous edge (taken at this one).
    let mut shown = false;
    let mut edge = 0u64;
    while machine.busy() || shown {
        let result = machine.edge(edge, classify);
        shown = false;
        if let Some(record) = result {
            if record.full != 0 || record.crossed != 0 {
                run.records.push(record);
                // Shown after this edge, taken (the reader ready) at the next.
                run.edges.push(edge + 1);
                shown = true;
            }
        }
        edge += 1;
    }
    run.cycles = edge;
    run.cells = machine.cells;
    run.stack_depth = machine.stack_depth;
    run
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Every voxel of 16^3 and 32^3 grids checked directly: crossed iff the
    /// plane's values at its 8 corners are not all of one strict sign;
    /// in the half-space iff its centre is. Planes through voxel corners,
    /// along edges and faces included (small integer normals, zeros too).
    #[test]
    fn equals_brute_force_on_every_voxel() {
        let mut rng = ChaCha8Rng::seed_from_u64(1995);
        for round in 0..60 {
            let level = if round % 3 == 0 { 5 } else { 4 };
            let n = 1i64 << level;
            let normal = [0; 3].map(|_: i64| rng.gen_range(-3..=3));
            let normal = if normal == [0; 3] { [1, 0, 0] } else { normal };
            let d = rng.gen_range(-n..=4 * n);
            let c = classify_plane(level, normal, d);
            let half_space = c.half_space.to_voxels();
            // Built canonical in one pass: equal to the tree of its voxels.
            assert_eq!(
                c.half_space,
                Octree::from_voxels(&half_space),
                "round {round}: canonical"
            );
            let (mut crossed, mut inside) = (0u64, 0u64);
            for z in 0..n {
                for y in 0..n {
                    for x in 0..n {
                        let f = |p: [i64; 3]| {
                            normal[0] * p[0] + normal[1] * p[1] + normal[2] * p[2] - d
                        };
                        let corners: Vec<i64> = (0..8)
                            .map(|o| f([x + (o & 1), y + (o >> 1 & 1), z + (o >> 2 & 1)]))
                            .collect();
                        let is_crossed =
                            corners.iter().any(|&v| v <= 0) && corners.iter().any(|&v| v >= 0);
                        crossed += is_crossed as u64;
                        let centre_inside = 2 * (normal[0] * x + normal[1] * y + normal[2] * z)
                            + normal.iter().sum::<i64>()
                            <= 2 * d;
                        inside += centre_inside as u64;
                        assert_eq!(
                            half_space.get([x as usize, y as usize, z as usize]),
                            centre_inside,
                            "round {round} voxel ({x},{y},{z})"
                        );
                    }
                }
            }
            assert_eq!(c.crossed_voxels, crossed, "round {round}: {normal:?} {d}");
            // The hardware's schedule describes the same half-space.
            let run = traversal_schedule(level, normal, d);
            assert_eq!(run.half_space(level), half_space, "round {round}: schedule");
            assert_eq!(run.crossed_voxels(), crossed, "round {round}: schedule");
            assert_eq!(half_space.count(), inside, "round {round}");
        }
    }
}
