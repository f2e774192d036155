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
use super::tree::{Node, Octree};

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
    let half_space = Octree::from_preorder(level, &nodes).expect("the traversal emits one tree of the root's level");
    PlaneClassification { crossed_voxels: counts.0, cells_split: counts.1, half_space }
}

/// Emits the nodes of `cell` in preorder; counts `(crossed voxels, splits)`.
fn visit(cell: Cell, f: AffineOverBox, d: i128, centre_offset: i128, counts: &mut (u64, u64), nodes: &mut Vec<Node>) {
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
        nodes.push(if 2 * f.at_lo + centre_offset <= 2 * d { Node::Full } else { Node::Empty });
        return;
    }
    counts.1 += 1;
    nodes.push(Node::Mixed);
    for octant in 0..8 {
        visit(cell.child(octant), f.child(octant), d, centre_offset, counts, nodes);
    }
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
            let (mut crossed, mut inside) = (0u64, 0u64);
            for z in 0..n {
                for y in 0..n {
                    for x in 0..n {
                        let f = |p: [i64; 3]| normal[0] * p[0] + normal[1] * p[1] + normal[2] * p[2] - d;
                        let corners: Vec<i64> = (0..8).map(|o| f([x + (o & 1), y + (o >> 1 & 1), z + (o >> 2 & 1)])).collect();
                        let is_crossed = corners.iter().any(|&v| v <= 0) && corners.iter().any(|&v| v >= 0);
                        crossed += is_crossed as u64;
                        let centre_inside = 2 * (normal[0] * x + normal[1] * y + normal[2] * z) + normal.iter().sum::<i64>() <= 2 * d;
                        inside += centre_inside as u64;
                        assert_eq!(half_space.get([x as usize, y as usize, z as usize]), centre_inside, "round {round} voxel ({x},{y},{z})");
                    }
                }
            }
            assert_eq!(c.crossed_voxels, crossed, "round {round}: {normal:?} {d}");
            assert_eq!(half_space.count(), inside, "round {round}");
        }
    }
}
