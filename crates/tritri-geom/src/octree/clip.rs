//! 3D clipping of an octree model against an axis-aligned box
//! (`octree_engine.txt`, table 1's second row): every octant is inside the
//! box, outside it, or crossing its boundary. Inside octants are kept
//! whole, outside ones dropped, crossing ones split (a full leaf that
//! crosses is split as eight full children), so the result is the model
//! intersected with the box, built in one preorder pass.
//!
//! The box is given in voxel indices, half-open: `lo <= v < hi` per axis,
//! so its faces lie on voxel faces and each octant test is six integer
//! comparisons of the octant's corners against the box's (the hardware's
//! one octant per clock).

use super::cell::Cell;
use super::tree::{skip_subtree, Node, Octree};

/// How many octants of each class the pass met.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ClipCounts {
    pub inside: u64,
    pub outside: u64,
    pub crossing: u64,
}

impl ClipCounts {
    pub fn octants(&self) -> u64 {
        self.inside + self.outside + self.crossing
    }
}

/// Where an octant lies against the box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    Inside,
    Outside,
    Crossing,
}

/// Classifies the cell against the half-open voxel box `[lo, hi)`.
pub fn classify(cell: &Cell, lo: [i64; 3], hi: [i64; 3]) -> Side {
    let (c_lo, c_hi) = (cell.lo, cell.lo.map(|c| c + cell.size()));
    if (0..3).any(|k| c_hi[k] <= lo[k] || c_lo[k] >= hi[k]) {
        Side::Outside
    } else if (0..3).all(|k| lo[k] <= c_lo[k] && c_hi[k] <= hi[k]) {
        Side::Inside
    } else {
        Side::Crossing
    }
}

/// The model clipped to the box, and the octants of each class.
pub fn clip(tree: &Octree, lo: [i64; 3], hi: [i64; 3]) -> (Octree, ClipCounts) {
    let mut out = Vec::new();
    let mut counts = ClipCounts::default();
    let mut i = 0;
    clip_at(tree.nodes(), &mut i, Cell { lo: [0; 3], level: tree.level() }, lo, hi, &mut counts, &mut out);
    let clipped = Octree::from_preorder(tree.level(), &out).expect("clipping emits one tree of the model's level");
    (clipped, counts)
}

/// Clips the subtree at `*i` over `cell`, advancing `*i` past it. `None`
/// for `node` stands for a full leaf being split (no node to read).
fn clip_at(nodes: &[Node], i: &mut usize, cell: Cell, lo: [i64; 3], hi: [i64; 3], counts: &mut ClipCounts, out: &mut Vec<Node>) {
    let node = nodes[*i];
    match classify(&cell, lo, hi) {
        Side::Inside => {
            counts.inside += 1;
            let end = skip_subtree(nodes, *i);
            out.extend_from_slice(&nodes[*i..end]);
            *i = end;
        }
        Side::Outside => {
            counts.outside += 1;
            out.push(Node::Empty);
            *i = skip_subtree(nodes, *i);
        }
        Side::Crossing => {
            counts.crossing += 1;
            match node {
                Node::Empty => {
                    out.push(Node::Empty);
                    *i += 1;
                }
                Node::Full => {
                    *i += 1;
                    clip_full(cell, lo, hi, counts, out);
                }
                Node::Mixed => {
                    *i += 1;
                    out.push(Node::Mixed);
                    for o in 0..8 {
                        clip_at(nodes, i, cell.child(o), lo, hi, counts, out);
                    }
                }
            }
        }
    }
}

/// A full cell crossing the box: its part inside.
fn clip_full(cell: Cell, lo: [i64; 3], hi: [i64; 3], counts: &mut ClipCounts, out: &mut Vec<Node>) {
    out.push(Node::Mixed);
    for o in 0..8 {
        let child = cell.child(o);
        match classify(&child, lo, hi) {
            Side::Inside => {
                counts.inside += 1;
                out.push(Node::Full);
            }
            Side::Outside => {
                counts.outside += 1;
                out.push(Node::Empty);
            }
            Side::Crossing => {
                counts.crossing += 1;
                clip_full(child, lo, hi, counts, out);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::octree::tree::SetOperation;
    use crate::octree::voxels::VoxelGrid;

    /// Clipping equals intersecting with the box's own voxels, for boxes
    /// inside, across and outside the grid.
    #[test]
    fn clip_equals_intersection_with_the_box() {
        let mut model = VoxelGrid::empty(4);
        model.fill_cube([0, 0, 0], 3);
        model.fill_cube([8, 8, 8], 2);
        model.set([15, 0, 9]);
        let tree = Octree::from_voxels(&model);
        for (lo, hi) in [([1, 2, 3], [9, 9, 13]), ([0, 0, 0], [16, 16, 16]), ([-4, 5, 7], [30, 6, 8]), ([3, 3, 3], [3, 9, 9]), ([20, 0, 0], [30, 5, 5])] {
            let mut box_voxels = VoxelGrid::empty(4);
            for z in 0..16i64 {
                for y in 0..16i64 {
                    for x in 0..16i64 {
                        let p = [x, y, z];
                        if (0..3).all(|k| lo[k] <= p[k] && p[k] < hi[k]) {
                            box_voxels.set(p.map(|c| c as usize));
                        }
                    }
                }
            }
            let (clipped, counts) = clip(&tree, lo, hi);
            assert_eq!(clipped.to_voxels(), model.combine(SetOperation::Intersection, &box_voxels), "{lo:?} {hi:?}");
            assert!(counts.octants() >= 1);
        }
    }
}
