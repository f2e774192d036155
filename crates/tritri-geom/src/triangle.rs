//! Points, triangles and pairs of triangles as read from files.

/// A point in 3D with f64 coordinates.
pub type Point = [f64; 3];
/// A triangle: three vertices.
pub type Triangle = [Point; 3];

/// Two triangles to test against each other.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrianglePair {
    pub t1: Triangle,
    pub t2: Triangle,
}

impl TrianglePair {
    pub fn new(t1: Triangle, t2: Triangle) -> Self {
        TrianglePair { t1, t2 }
    }
    pub fn swapped(&self) -> Self {
        TrianglePair {
            t1: self.t2,
            t2: self.t1,
        }
    }
    /// Every coordinate of both triangles, in file order.
    pub fn coordinates(&self) -> impl Iterator<Item = f64> + '_ {
        self.t1.iter().chain(self.t2.iter()).flatten().copied()
    }
}

/// The six permutations of three vertices.
pub const VERTEX_PERMUTATIONS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [1, 2, 0],
    [2, 0, 1],
    [0, 2, 1],
    [2, 1, 0],
    [1, 0, 2],
];

/// Reorders a triangle's vertices.
pub fn permute<P: Copy>(t: [P; 3], perm: [usize; 3]) -> [P; 3] {
    [t[perm[0]], t[perm[1]], t[perm[2]]]
}

/// All 36 vertex orderings of a pair (6 of T1 times 6 of T2), each also with
/// the two triangles swapped: 72 pairs that must all get the same answer.
pub fn all_orderings(pair: &TrianglePair) -> impl Iterator<Item = TrianglePair> + '_ {
    VERTEX_PERMUTATIONS.iter().flat_map(move |&a| {
        VERTEX_PERMUTATIONS.iter().flat_map(move |&b| {
            let p = TrianglePair::new(permute(pair.t1, a), permute(pair.t2, b));
            [p, p.swapped()]
        })
    })
}
