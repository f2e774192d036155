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
use super::tree::{collapse_if_uniform, skip_subtree, Node, Octree};

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
    let mut pass = Pass {
        lo,
        hi,
        counts: ClipCounts::default(),
        log: None,
    };
    let clipped = pass.run(tree);
    (clipped, pass.counts)
}

/// [`clip`], also listing every octant classified with its class, in the
/// order the pass met them (what a hardware clipper is given).
pub fn clip_logged(
    tree: &Octree,
    lo: [i64; 3],
    hi: [i64; 3],
) -> (Octree, ClipCounts, Vec<(Cell, Side)>) {
    let mut pass = Pass {
        lo,
        hi,
        counts: ClipCounts::default(),
        log: Some(Vec::new()),
    };
    let clipped = pass.run(tree);
    (clipped, pass.counts, pass.log.unwrap_or_default())
}

/// One clipping pass: the box, what it has counted, and optionally its log.
struct Pass {
    lo: [i64; 3],
    hi: [i64; 3],
    counts: ClipCounts,
    log: Option<Vec<(Cell, Side)>>,
}

impl Pass {
    fn run(&mut self, tree: &Octree) -> Octree {
        let mut out = Vec::new();
        let mut i = 0;
        self.clip_at(
            tree.nodes(),
            &mut i,
            Cell {
                lo: [0; 3],
                level: tree.level(),
            },
            &mut out,
        );
        Octree::from_canonical(tree.level(), out)
    }

    /// Classifies `cell`, counting and logging it.
    fn classify(&mut self, cell: Cell) -> Side {
        let side = classify(&cell, self.lo, self.hi);
        match side {
            Side::Inside => self.counts.inside += 1,
            Side::Outside => self.counts.outside += 1,
            Side::Crossing => self.counts.crossing += 1,
        }
        if let Some(log) = self.log.as_mut() {
            log.push((cell, side));
        }
        side
    }

    /// Clips the subtree at `*i` over `cell`, advancing `*i` past it.
    fn clip_at(&mut self, nodes: &[Node], i: &mut usize, cell: Cell, out: &mut Vec<Node>) {
        let node = nodes[*i];
        match self.classify(cell) {
            Side::Inside => {
                let end = skip_subtree(nodes, *i);
                out.extend_from_slice(&nodes[*i..end]);
                *i = end;
            }
            Side::Outside => {
                out.push(Node::Empty);
                *i = skip_subtree(nodes, *i);
            }
            Side::Crossing => {
                *i += 1;
                match node {
                    Node::Empty => out.push(Node::Empty),
                    Node::Full => self.clip_full(cell, out),
                    Node::Mixed => {
                        let at = out.len();
                        out.push(Node::Mixed);
                        for o in 0..8 {
                            self.clip_at(nodes, i, cell.child(o), out);
                        }
                        // Every child may have been clipped away.
                        collapse_if_uniform(out, at);
                    }
                }
            }
        }
    }

    /// A full cell crossing the box: its part inside.
    fn clip_full(&mut self, cell: Cell, out: &mut Vec<Node>) {
        let at = out.len();
        out.push(Node::Mixed);
        for o in 0..8 {
            let child = cell.child(o);
            match self.classify(child) {
                Side::Inside => out.push(Node::Full),
                Side::Outside => out.push(Node::Empty),
                Side::Crossing => self.clip_full(child, out),
            }
        }
        // A box empty along an axis crosses cells but holds no voxel.
        collapse_if_uniform(out, at);
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
        for (lo, hi) in [
            ([1, 2, 3], [9, 9, 13]),
            ([0, 0, 0], [16, 16, 16]),
            ([-4, 5, 7], [30, 6, 8]),
            ([3, 3, 3], [3, 9, 9]),
            ([20, 0, 0], [30, 5, 5]),
        ] {
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
            assert_eq!(
                clipped.to_voxels(),
                model.combine(SetOperation::Intersection, &box_voxels),
                "{lo:?} {hi:?}"
            );
            assert!(counts.octants() >= 1);
            assert_eq!(
                clipped,
                Octree::from_voxels(&clipped.to_voxels()),
                "{lo:?} {hi:?}: canonical"
            );
            let (logged, _, log) = clip_logged(&tree, lo, hi);
            assert_eq!((logged, log.len() as u64), (clipped, counts.octants()));
        }
    }
}
