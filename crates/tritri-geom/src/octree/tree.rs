//! Octree models: a `2^level` voxel cube as a tree of empty, full and
//! mixed cells, kept as its nodes in depth-first preorder (a mixed node is
//! followed by its eight children, octant `o` having bit `k` set for the
//! upper half along axis `k`, as [`super::cell::Cell::child`]).
//!
//! Preorder is what the octree engine's host link streams (the seed keeps
//! voxels in the engine and octrees on the wire, for compression), and it
//! lets set operations run as one pass over both operands, a node at a
//! time, as the hardware's set-operation unit does.
//!
//! Every tree here is *canonical*: no mixed node has eight children that
//! are all empty or all full leaves, and unit cells are never mixed. Two
//! canonical trees of one level are equal iff their voxels are, so
//! equality of models is equality of node lists.
//!
//! The file format is `docs/octree-format.md`: [`Octree::to_bytes`] and
//! [`Octree::from_bytes`].

use super::cell::Cell;
use super::voxels::VoxelGrid;

/// One node of a preorder list.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Node {
    Empty = 0,
    Full = 1,
    /// Followed by its eight children.
    Mixed = 2,
}

impl Node {
    fn leaf(full: bool) -> Node {
        if full {
            Node::Full
        } else {
            Node::Empty
        }
    }

    fn complement(self) -> Node {
        match self {
            Node::Empty => Node::Full,
            Node::Full => Node::Empty,
            Node::Mixed => Node::Mixed,
        }
    }
}

/// A canonical octree model of the `2^level` cube.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Octree {
    level: u32,
    nodes: Vec<Node>,
}

/// The three set operations on solids.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SetOperation {
    Union,
    Intersection,
    /// `a \ b`.
    Difference,
}

impl SetOperation {
    /// The operation on one voxel.
    pub fn apply(self, a: bool, b: bool) -> bool {
        match self {
            SetOperation::Union => a | b,
            SetOperation::Intersection => a & b,
            SetOperation::Difference => a & !b,
        }
    }
}

/// Why bytes are not an octree file.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum OctreeFormatError {
    #[error("not a tritri octree (the file does not start with the magic bytes TRIOCT1)")]
    Magic,
    #[error("the file ends inside its {0}")]
    Truncated(&'static str),
    #[error("level {0} is larger than 10 (a 1024^3 grid), the largest this model keeps")]
    Level(u8),
    #[error("node {index}: code 3 is not a node (0 empty, 1 full, 2 mixed)")]
    Code { index: u64 },
    #[error("node {index}: a unit voxel (level 0) cannot be mixed")]
    MixedVoxel { index: u64 },
    #[error("node {index}: a mixed node whose eight children are all {kind} (the file is not canonical)")]
    NotCanonical { index: u64, kind: &'static str },
    #[error("the header says {declared} nodes but the tree has {actual}")]
    Count { declared: u64, actual: u64 },
    #[error(
        "the origin or the voxel size is not a finite number (the size must be positive), \
         or the tree's far corner, origin + 2^level * size, is not"
    )]
    Placement,
    #[error("{0} bytes after the tree")]
    Trailing(usize),
    #[error("the last byte's {0} unused bits after the tree's last node are not zero")]
    Padding(u32),
}

/// The file's first bytes.
pub const MAGIC: &[u8; 8] = b"TRIOCT1\n";
/// Levels the model keeps (as [`VoxelGrid`]).
pub const MAX_LEVEL: u32 = 10;
/// Magic, level, origin, voxel size, node count.
const HEADER_BYTES: usize = 8 + 1 + 4 * 8 + 8;

impl Octree {
    pub fn empty(level: u32) -> Octree {
        Octree {
            level,
            nodes: vec![Node::Empty],
        }
    }

    pub fn full(level: u32) -> Octree {
        Octree {
            level,
            nodes: vec![Node::Full],
        }
    }

    /// The side is `2^level` voxels.
    pub fn level(&self) -> u32 {
        self.level
    }

    /// The nodes in preorder.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// Builds a tree from preorder nodes that may not be canonical
    /// (collapses uniform mixed nodes); `None` if the list is not a tree of
    /// that level.
    pub fn from_preorder(level: u32, nodes: &[Node]) -> Option<Octree> {
        let mut out = Vec::with_capacity(nodes.len());
        let end = copy_canonical(nodes, 0, level, &mut out)?;
        (end == nodes.len()).then_some(Octree { level, nodes: out })
    }

    /// A tree from preorder nodes its builder kept canonical (by
    /// [`collapse_if_uniform`] after each mixed node's children).
    pub(crate) fn from_canonical(level: u32, nodes: Vec<Node>) -> Octree {
        debug_assert_eq!(
            Octree::from_preorder(level, &nodes).map(|t| t.nodes),
            Some(nodes.clone()),
            "not one canonical tree"
        );
        Octree { level, nodes }
    }

    /// The tree of a voxel model.
    pub fn from_voxels(grid: &VoxelGrid) -> Octree {
        let mut nodes = Vec::new();
        push_from_voxels(
            grid,
            Cell {
                lo: [0; 3],
                level: grid.level(),
            },
            &mut nodes,
        );
        Octree {
            level: grid.level(),
            nodes,
        }
    }

    /// The voxel model of the tree: full cells written whole.
    pub fn to_voxels(&self) -> VoxelGrid {
        let mut grid = VoxelGrid::empty(self.level);
        self.for_each_leaf(|cell, node| {
            if node == Node::Full {
                grid.fill_cube(cell.lo.map(|c| c as usize), cell.level);
            }
        });
        grid
    }

    /// Calls `f` with every leaf (empty or full) and its cell, in preorder.
    pub fn for_each_leaf(&self, mut f: impl FnMut(Cell, Node)) {
        let mut stack = vec![Cell {
            lo: [0; 3],
            level: self.level,
        }];
        for &node in &self.nodes {
            let Some(cell) = stack.pop() else { break };
            match node {
                Node::Mixed => stack.extend((0..8).rev().map(|o| cell.child(o))),
                leaf => f(cell, leaf),
            }
        }
    }

    /// The full leaves as fill records for a voxel memory (the form the
    /// hardware's voxel fill takes, `tritri_rtl::octree::voxel_fill`): the
    /// full children of each mixed node, one record per mixed node that
    /// has any, and for a full root its eight children. In preorder.
    pub fn fill_records(&self) -> Vec<super::plane::TraversalRecord> {
        let mut out = Vec::new();
        if self.nodes == [Node::Full] {
            if self.level >= 1 {
                out.push(super::plane::TraversalRecord {
                    lo: [0; 3],
                    level: self.level,
                    full: 0xFF,
                    crossed: 0,
                });
            }
            return out;
        }
        // Walk mixed nodes with the index of their first child.
        let mut stack = vec![(
            Cell {
                lo: [0; 3],
                level: self.level,
            },
            0usize,
        )];
        while let Some((cell, at)) = stack.pop() {
            if self.nodes[at] != Node::Mixed {
                continue;
            }
            let mut child_at = at + 1;
            let mut full = 0u8;
            let mut children = Vec::new();
            for o in 0..8 {
                match self.nodes[child_at] {
                    Node::Full => full |= 1 << o,
                    Node::Mixed => children.push((cell.child(o), child_at)),
                    Node::Empty => {}
                }
                child_at = skip_subtree(&self.nodes, child_at);
            }
            if full != 0 {
                out.push(super::plane::TraversalRecord {
                    lo: cell.lo,
                    level: cell.level,
                    full,
                    crossed: 0,
                });
            }
            stack.extend(children.into_iter().rev());
        }
        out
    }

    /// Voxels inside the solid.
    pub fn voxel_count(&self) -> u64 {
        let mut count = 0u64;
        self.for_each_leaf(|cell, node| {
            if node == Node::Full {
                count += 1u64 << (3 * cell.level);
            }
        });
        count
    }

    /// A set operation, in one preorder pass over both trees (neither is
    /// expanded to voxels). Both must have the same level.
    pub fn combine(&self, op: SetOperation, other: &Octree) -> Octree {
        assert_eq!(
            self.level, other.level,
            "set operations need models of one grid"
        );
        let mut nodes = Vec::with_capacity(self.nodes.len().max(other.nodes.len()));
        let (mut i, mut j) = (0, 0);
        combine_at(&self.nodes, &mut i, &other.nodes, &mut j, op, &mut nodes);
        Octree {
            level: self.level,
            nodes,
        }
    }

    /// The complement within the cube.
    pub fn complement(&self) -> Octree {
        Octree {
            level: self.level,
            nodes: self.nodes.iter().map(|n| n.complement()).collect(),
        }
    }
}

/// Where a model's grid sits in the user's coordinates: voxel `(i, j, k)`
/// is the cube from `origin + voxel_size · (i, j, k)` with side
/// `voxel_size`. Kept with a model in its file, so a model voxelized from a
/// mesh comes back out (as a boundary mesh, a `.binvox`) in the mesh's
/// units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub origin: [f64; 3],
    pub voxel_size: f64,
}

impl Default for Placement {
    /// The grid's own units.
    fn default() -> Placement {
        Placement {
            origin: [0.0; 3],
            voxel_size: 1.0,
        }
    }
}

/// An octree model with its placement: the file format.
#[derive(Clone, Debug, PartialEq)]
pub struct OctreeFile {
    pub tree: Octree,
    pub placement: Placement,
}

impl OctreeFile {
    /// The file: [`MAGIC`]; the level (1 byte); the origin (3 f64) and the
    /// voxel size (f64); the node count (u64); then the nodes' 2-bit codes
    /// packed four to a byte, the first node in the lowest bits, the last
    /// byte padded with zeros. Numbers are little endian.
    pub fn to_bytes(&self) -> Vec<u8> {
        let nodes = &self.tree.nodes;
        let mut bytes = Vec::with_capacity(HEADER_BYTES + nodes.len().div_ceil(4));
        bytes.extend_from_slice(MAGIC);
        bytes.push(self.tree.level as u8);
        for v in self
            .placement
            .origin
            .iter()
            .chain([&self.placement.voxel_size])
        {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        bytes.extend_from_slice(&(nodes.len() as u64).to_le_bytes());
        for chunk in nodes.chunks(4) {
            bytes.push(
                chunk
                    .iter()
                    .enumerate()
                    .fold(0u8, |b, (k, &n)| b | (n as u8) << (2 * k)),
            );
        }
        bytes
    }

    /// Reads [`Self::to_bytes`]'s format, checking that the nodes form one
    /// canonical tree and nothing follows it.
    pub fn from_bytes(bytes: &[u8]) -> Result<OctreeFile, OctreeFormatError> {
        if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
            return Err(OctreeFormatError::Magic);
        }
        if bytes.len() < HEADER_BYTES {
            return Err(OctreeFormatError::Truncated("header"));
        }
        let level = bytes[MAGIC.len()];
        if u32::from(level) > MAX_LEVEL {
            return Err(OctreeFormatError::Level(level));
        }
        let word = |k: usize| -> [u8; 8] {
            let at = MAGIC.len() + 1 + 8 * k;
            let mut w = [0u8; 8];
            w.copy_from_slice(&bytes[at..at + 8]);
            w
        };
        let [x, y, z, size] = [0, 1, 2, 3].map(|k| f64::from_le_bytes(word(k)));
        // Every corner a converter writes lies between the origin and the
        // far corner: both finite, or the OBJ and binvox files get `inf`.
        let side = size * f64::from(1u32 << level);
        let far_corner_finite = [x, y, z].iter().all(|v| (v + side).is_finite());
        if ![x, y, z].iter().all(|v| v.is_finite())
            || !(size.is_finite() && size > 0.0)
            || !far_corner_finite
        {
            return Err(OctreeFormatError::Placement);
        }
        let declared = u64::from_le_bytes(word(4));
        let packed = &bytes[HEADER_BYTES..];
        let available = packed.len() as u64 * 4;
        // Decode lazily: the tree decides how many nodes it has.
        let code = |index: u64| -> Result<Node, OctreeFormatError> {
            if index >= available {
                return Err(OctreeFormatError::Truncated("nodes"));
            }
            match packed[(index / 4) as usize] >> (2 * (index % 4)) & 3 {
                0 => Ok(Node::Empty),
                1 => Ok(Node::Full),
                2 => Ok(Node::Mixed),
                _ => Err(OctreeFormatError::Code { index }),
            }
        };
        let mut nodes = Vec::new();
        // The level of each node still to read.
        let mut pending: Vec<u32> = vec![u32::from(level)];
        while let Some(node_level) = pending.pop() {
            let index = nodes.len() as u64;
            let node = code(index)?;
            if node == Node::Mixed {
                if node_level == 0 {
                    return Err(OctreeFormatError::MixedVoxel { index });
                }
                pending.extend(std::iter::repeat(node_level - 1).take(8));
            }
            nodes.push(node);
        }
        let actual = nodes.len() as u64;
        if declared != actual {
            return Err(OctreeFormatError::Count { declared, actual });
        }
        let used = nodes.len().div_ceil(4);
        if packed.len() > used {
            return Err(OctreeFormatError::Trailing(packed.len() - used));
        }
        // The bits after the last node pad its byte with zeros: a file
        // reads back to one set of bytes only.
        let nodes_in_last = nodes.len() % 4;
        if nodes_in_last != 0 && packed[used - 1] >> (2 * nodes_in_last) != 0 {
            return Err(OctreeFormatError::Padding(8 - 2 * nodes_in_last as u32));
        }
        // Canonical: no mixed node with eight equal leaves.
        for (index, window) in nodes.windows(9).enumerate() {
            if window[0] == Node::Mixed
                && window[1] != Node::Mixed
                && window[1..].iter().all(|&n| n == window[1])
            {
                let kind = if window[1] == Node::Full {
                    "full"
                } else {
                    "empty"
                };
                return Err(OctreeFormatError::NotCanonical {
                    index: index as u64,
                    kind,
                });
            }
        }
        let tree = Octree {
            level: u32::from(level),
            nodes,
        };
        Ok(OctreeFile {
            tree,
            placement: Placement {
                origin: [x, y, z],
                voxel_size: size,
            },
        })
    }
}

/// Pushes the canonical nodes of `cell` of `grid`.
fn push_from_voxels(grid: &VoxelGrid, cell: Cell, out: &mut Vec<Node>) {
    if cell.level == 0 {
        out.push(Node::leaf(grid.get(cell.lo.map(|c| c as usize))));
        return;
    }
    let at = out.len();
    out.push(Node::Mixed);
    for o in 0..8 {
        push_from_voxels(grid, cell.child(o), out);
    }
    collapse_if_uniform(out, at);
}

/// If the mixed node at `at` has just its eight children after it and they
/// are equal leaves, replaces the nine nodes by that leaf.
pub(crate) fn collapse_if_uniform(out: &mut Vec<Node>, at: usize) {
    if out.len() == at + 9
        && out[at + 1] != Node::Mixed
        && out[at + 2..].iter().all(|&n| n == out[at + 1])
    {
        let leaf = out[at + 1];
        out.truncate(at);
        out.push(leaf);
    }
}

/// The index after the subtree starting at `i`.
pub(crate) fn skip_subtree(nodes: &[Node], mut i: usize) -> usize {
    let mut open = 1usize;
    while open > 0 {
        if nodes[i] == Node::Mixed {
            open += 8;
        }
        open -= 1;
        i += 1;
    }
    i
}

/// Copies the subtree at `i`, complemented or not; returns the index after it.
fn copy_subtree(nodes: &[Node], i: usize, complement: bool, out: &mut Vec<Node>) -> usize {
    let end = skip_subtree(nodes, i);
    out.extend(
        nodes[i..end]
            .iter()
            .map(|&n| if complement { n.complement() } else { n }),
    );
    end
}

/// Copies the subtree at `i` collapsing uniform mixed nodes; `None` if the
/// list ends early or a unit cell is mixed.
fn copy_canonical(nodes: &[Node], i: usize, level: u32, out: &mut Vec<Node>) -> Option<usize> {
    let node = *nodes.get(i)?;
    if node != Node::Mixed {
        out.push(node);
        return Some(i + 1);
    }
    if level == 0 {
        return None;
    }
    let at = out.len();
    out.push(Node::Mixed);
    let mut next = i + 1;
    for _ in 0..8 {
        next = copy_canonical(nodes, next, level - 1, out)?;
    }
    collapse_if_uniform(out, at);
    Some(next)
}

/// One node of `op(a, b)` from the subtrees at `*i` and `*j`, advancing both.
fn combine_at(
    a: &[Node],
    i: &mut usize,
    b: &[Node],
    j: &mut usize,
    op: SetOperation,
    out: &mut Vec<Node>,
) {
    match (a[*i], b[*j]) {
        (Node::Mixed, Node::Mixed) => {
            *i += 1;
            *j += 1;
            let at = out.len();
            out.push(Node::Mixed);
            for _ in 0..8 {
                combine_at(a, i, b, j, op, out);
            }
            collapse_if_uniform(out, at);
        }
        (Node::Mixed, leaf) => {
            let value = leaf == Node::Full;
            *i = apply_to_subtree(a, *i, |x| op.apply(x, value), out);
            *j += 1;
        }
        (leaf, Node::Mixed) => {
            let value = leaf == Node::Full;
            *j = apply_to_subtree(b, *j, |y| op.apply(value, y), out);
            *i += 1;
        }
        (x, y) => {
            out.push(Node::leaf(op.apply(x == Node::Full, y == Node::Full)));
            *i += 1;
            *j += 1;
        }
    }
}

/// `f` applied to every voxel of the subtree at `i`: a constant (one leaf),
/// the identity (a copy) or the negation (a complemented copy). Returns the
/// index after the subtree.
fn apply_to_subtree(
    nodes: &[Node],
    i: usize,
    f: impl Fn(bool) -> bool,
    out: &mut Vec<Node>,
) -> usize {
    match (f(false), f(true)) {
        (false, true) => copy_subtree(nodes, i, false, out),
        (true, false) => copy_subtree(nodes, i, true, out),
        (constant, _) => {
            out.push(Node::leaf(constant));
            skip_subtree(nodes, i)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A random model with uniform regions at every scale: random cubes.
    pub(crate) fn random_grid(rng: &mut ChaCha8Rng, level: u32) -> VoxelGrid {
        let mut g = VoxelGrid::empty(level);
        for _ in 0..rng.gen_range(0..12) {
            let l = rng.gen_range(0..level);
            let side = 1usize << l;
            let lo = [0; 3].map(|_: usize| rng.gen_range(0..(1usize << level) / side) * side);
            g.fill_cube(lo, l);
        }
        g
    }

    #[test]
    fn voxels_round_trip_through_trees_and_files() {
        let mut rng = ChaCha8Rng::seed_from_u64(512);
        for round in 0..40 {
            let level = 1 + round % 5;
            let g = random_grid(&mut rng, level);
            let t = Octree::from_voxels(&g);
            assert_eq!(t.to_voxels(), g);
            assert_eq!(t.voxel_count(), g.count());
            let file = OctreeFile {
                tree: t.clone(),
                placement: Placement {
                    origin: [1.5, -2.0, 0.25],
                    voxel_size: 0.125,
                },
            };
            assert_eq!(OctreeFile::from_bytes(&file.to_bytes()), Ok(file));
            // The fill records describe the same voxels.
            let run = super::super::plane::TraversalRun {
                records: t.fill_records(),
                ..Default::default()
            };
            assert_eq!(run.half_space(level), g, "round {round}: fill records");
            assert_eq!(Octree::from_preorder(level, t.nodes()), Some(t));
        }
        assert_eq!(Octree::from_voxels(&VoxelGrid::empty(3)), Octree::empty(3));
    }

    #[test]
    fn set_operations_on_trees_equal_those_on_voxels() {
        let mut rng = ChaCha8Rng::seed_from_u64(95);
        for round in 0..60 {
            let level = 1 + round % 4;
            let (ga, gb) = (random_grid(&mut rng, level), random_grid(&mut rng, level));
            let (ta, tb) = (Octree::from_voxels(&ga), Octree::from_voxels(&gb));
            for op in [
                SetOperation::Union,
                SetOperation::Intersection,
                SetOperation::Difference,
            ] {
                let tree = ta.combine(op, &tb);
                // Canonical, so equal to the tree rebuilt from its voxels.
                assert_eq!(
                    tree,
                    Octree::from_voxels(&ga.combine(op, &gb)),
                    "{op:?} round {round}"
                );
            }
            assert_eq!(ta.complement().to_voxels(), ga.complement());
        }
    }

    #[test]
    fn bad_files_are_named_errors() {
        let t = Octree::from_voxels(&{
            let mut g = VoxelGrid::empty(2);
            g.set([1, 2, 3]);
            g
        });
        let file = |tree: Octree| OctreeFile {
            tree,
            placement: Placement::default(),
        };
        let bytes = file(t).to_bytes();
        let read = |b: &[u8]| OctreeFile::from_bytes(b).map(|f| f.tree);
        assert_eq!(read(b"PLY"), Err(OctreeFormatError::Magic));
        assert_eq!(
            read(&bytes[..bytes.len() - 1]),
            Err(OctreeFormatError::Truncated("nodes"))
        );
        let mut extra = bytes.clone();
        extra.push(0);
        assert_eq!(read(&extra), Err(OctreeFormatError::Trailing(1)));
        // 17 nodes: the last byte holds one node and six bits of padding.
        let mut padding = bytes.clone();
        *padding.last_mut().unwrap() |= 0b0010_0000;
        assert_eq!(read(&padding), Err(OctreeFormatError::Padding(6)));
        let mut count = bytes.clone();
        count[HEADER_BYTES - 8] += 1;
        assert!(matches!(read(&count), Err(OctreeFormatError::Count { .. })));
        let uniform = file(Octree {
            level: 1,
            nodes: [[Node::Mixed].as_slice(), &[Node::Full; 8]].concat(),
        })
        .to_bytes();
        assert_eq!(
            read(&uniform),
            Err(OctreeFormatError::NotCanonical {
                index: 0,
                kind: "full"
            })
        );
        let mut level = bytes.clone();
        level[8] = 11;
        assert_eq!(read(&level), Err(OctreeFormatError::Level(11)));
        let mut size = bytes.clone();
        size[8 + 1 + 24..8 + 1 + 32].copy_from_slice(&(-1.0f64).to_le_bytes());
        assert_eq!(read(&size), Err(OctreeFormatError::Placement));
        // A finite size whose tree reaches past f64's range: the exports
        // would write `inf` coordinates (issue 68, item 7).
        let mut overflow = bytes.clone();
        overflow[8 + 1 + 24..8 + 1 + 32].copy_from_slice(&1e308f64.to_le_bytes());
        assert_eq!(read(&overflow), Err(OctreeFormatError::Placement));
        let mut far = bytes;
        far[8 + 1..8 + 1 + 8].copy_from_slice(&f64::MAX.to_le_bytes());
        far[8 + 1 + 24..8 + 1 + 32].copy_from_slice(&1e300f64.to_le_bytes());
        assert_eq!(read(&far), Err(OctreeFormatError::Placement));
    }
}
