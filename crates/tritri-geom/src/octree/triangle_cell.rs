//! Does a closed triangle meet a closed cell? The octree engine's
//! triangle classifier, decided exactly on the integer grid.
//!
//! Two convex sets are disjoint iff an axis separates them. For a triangle
//! (or its degenerate forms, a segment or a point) and a box it suffices to
//! try the box's three axes, the triangle's normal, and the nine cross
//! products of a triangle edge with a box axis (zero axes separate nothing
//! and are skipped). Along an axis `g` the triangle projects to
//! `[min g·v, max g·v]` over its vertices; the box projects to the range of
//! the affine function `g · p` over it, which [`AffineOverBox`] tracks by
//! interpolation. So the test is thirteen affine functions, each asked
//! whether it reaches the triangle's interval somewhere on the cell:
//!
//! * `x`, `y`, `z`: the cell against the triangle's bounding box;
//! * the plane `n · p` with `n = (v1 - v0) × (v2 - v1)`: the seed's plane
//!   classification, the cell meets the plane of the triangle;
//! * `(e × u_k) · p` for each edge `e` and axis `u_k`: the edge functions of
//!   the triangle's projection along `u_k`, whose interval spans from the
//!   edge's line to the opposite vertex.
//!
//! Magnitudes: coordinates of cells and triangles stay below `2^34` for
//! `W <= 32`, a normal component below `2^66`, so every value fits an i128.

use super::affine::AffineOverBox;
use super::cell::Cell;
use crate::bounding_volume::Aabb;
use crate::fixed_point::FixedTriangle;

/// The most test functions one triangle needs.
pub const MAX_AXES: usize = 13;

/// How far, in grid steps and in every direction, the broad phase grows a
/// quantized triangle before classifying it ([`TriangleCellTest::widened`]).
/// Quantization moves every point of a triangle by at most half a step
/// (plus f64 rounding far below a step, docs/certificates.md), so two
/// original triangles that touch at `p` have quantized images within half
/// a step of `p`, and both meet the leaf holding `p` once grown by one step:
/// the pair is tested and its verdict's certificate decides whether the
/// host looks again. Exact voxelization uses [`TriangleCellTest::new`].
pub const BROAD_PHASE_MARGIN: i128 = 1;

/// One affine test function and the triangle's interval along it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
struct Axis {
    gradient: [i128; 3],
    low: i128,
    high: i128,
}

/// The triangle's test functions, built once per triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TriangleCellTest {
    axes: [Axis; MAX_AXES],
    count: usize,
}

/// The test functions' values at one cell's low corner. Over a cube of
/// side `2^level` a function's increments along the edges are its gradient
/// shifted by the level, so the corner values and the level are all a cell
/// needs to carry (a quarter of [`AffineOverBox`]'s size).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellValues {
    at_lo: [i128; MAX_AXES],
    level: u32,
}

impl CellValues {
    /// The values at the cell's low corner, zero for padded functions.
    pub fn at_lo(&self) -> [i128; MAX_AXES] {
        self.at_lo
    }

    pub fn level(&self) -> u32 {
        self.level
    }
}

impl TriangleCellTest {
    pub fn new(t: &FixedTriangle) -> TriangleCellTest {
        TriangleCellTest::widened(t, 0)
    }

    /// The test of the triangle grown by `margin` grid steps in every
    /// direction (its Minkowski sum with the cube `[-margin, margin]^3`),
    /// conservatively: each function's interval grows by `margin |g|_1`, so
    /// a cell the grown triangle meets is never rejected (a cell may be
    /// kept that only the grown intervals reach).
    pub fn widened(t: &FixedTriangle, margin: i128) -> TriangleCellTest {
        let p = t.map(|v| v.map(i128::from));
        let sub = |a: [i128; 3], b: [i128; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let cross = |u: [i128; 3], v: [i128; 3]| {
            [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ]
        };
        let unit = |k: usize| {
            let mut e = [0i128; 3];
            e[k] = 1;
            e
        };
        let edges = [sub(p[1], p[0]), sub(p[2], p[1]), sub(p[0], p[2])];
        let mut test = TriangleCellTest {
            axes: [Axis::default(); MAX_AXES],
            count: 0,
        };
        let mut add = |gradient: [i128; 3]| {
            // Not `== [0; 3]`: an array compare of i128s is a memcmp call,
            // which was most of this function's time on the host.
            if gradient.iter().all(|&g| g == 0) {
                return;
            }
            let projections =
                p.map(|v| gradient[0] * v[0] + gradient[1] * v[1] + gradient[2] * v[2]);
            let grow = margin * gradient.iter().map(|g| g.abs()).sum::<i128>();
            let low = projections.into_iter().min().unwrap_or(0) - grow;
            let high = projections.into_iter().max().unwrap_or(0) + grow;
            test.axes[test.count] = Axis {
                gradient,
                low,
                high,
            };
            test.count += 1;
        };
        for k in 0..3 {
            add(unit(k));
        }
        add(cross(edges[0], edges[1]));
        for e in edges {
            for k in 0..3 {
                add(cross(e, unit(k)));
            }
        }
        test
    }

    /// Every test function as `(gradient, low, high)`, padded to
    /// [`MAX_AXES`] with the zero function and `[0, 0]`, which meets every
    /// cell (what a fixed-width hardware classifier takes).
    pub fn padded_axes(&self) -> [([i128; 3], i128, i128); MAX_AXES] {
        self.axes.map(|a| (a.gradient, a.low, a.high))
    }

    /// The test functions at the low corner of `cell` (multiplications:
    /// done once per root, or per cell when cells are visited directly).
    pub fn values(&self, cell: &Cell) -> CellValues {
        let mut at_lo = [0i128; MAX_AXES];
        for (v, axis) in at_lo.iter_mut().zip(&self.axes[..self.count]) {
            *v = AffineOverBox::over_cell(axis.gradient, cell).at_lo;
        }
        CellValues {
            at_lo,
            level: cell.level,
        }
    }

    /// Test function `i` over the cell whose values these are.
    #[inline]
    fn function(&self, values: &CellValues, i: usize) -> AffineOverBox {
        AffineOverBox {
            at_lo: values.at_lo[i],
            along: self.axes[i].gradient.map(|g| g << values.level),
        }
    }

    /// Does the closed triangle meet the closed cell whose values these are?
    #[inline]
    pub fn touches(&self, values: &CellValues) -> bool {
        (0..self.count).all(|i| {
            self.function(values, i)
                .meets(self.axes[i].low, self.axes[i].high)
        })
    }

    /// The values over child `octant` of a cell of side >= 2: adds and shifts.
    #[inline]
    pub fn child(&self, parent: &CellValues, octant: usize) -> CellValues {
        let mut child = CellValues {
            at_lo: [0; MAX_AXES],
            level: parent.level - 1,
        };
        for i in 0..self.count {
            child.at_lo[i] = self.function(parent, i).child(octant).at_lo;
        }
        child
    }

    /// Does the closed triangle meet the closed box `b` (any box, not only
    /// a cell)?
    pub fn touches_box(&self, b: &Aabb<i64>) -> bool {
        self.axes[..self.count]
            .iter()
            .all(|axis| AffineOverBox::over_box(axis.gradient, b).meets(axis.low, axis.high))
    }

    /// The classifier's step: the children of a cell of side >= 2 that the
    /// triangle meets, as a mask (bit `o` for octant `o`), from the
    /// parent's values by interpolation.
    pub fn children_touched(&self, parent: &CellValues) -> u8 {
        (0..8)
            .filter(|&octant| self.touches(&self.child(parent, octant)))
            .fold(0u8, |mask, octant| mask | 1 << octant)
    }

    /// [`Self::children_touched`]'s mask for a cell given directly.
    pub fn children_of_cell(&self, cell: &Cell) -> u8 {
        self.children_touched(&self.values(cell))
    }
}

/// One triangle's test functions as the hardware setup unit delivers them
/// to the classifier (`tritri_rtl::octree::triangle_setup`): in fixed
/// positions (x, y, z; the normal; the nine edge-axis products, edge by
/// edge), zero gradients kept (their interval `[0, 0]` meets every cell),
/// and relative to the root cell's low corner `lo`: the functions are
/// `g · (p - lo)`, so every value at the root's low corner is zero and the
/// classifier starts from nothing but the level. The masks are the same as
/// [`TriangleCellTest`]'s, since moving a function by a constant moves the
/// triangle's interval with it. `margin` grows the triangle as
/// [`TriangleCellTest::widened`] does (the hardware's is
/// [`BROAD_PHASE_MARGIN`]).
pub fn root_relative_axes(
    t: &FixedTriangle,
    lo: [i64; 3],
    margin: i128,
) -> [([i128; 3], i128, i128); MAX_AXES] {
    let p = t.map(|v| [0, 1, 2].map(|k| v[k] as i128 - lo[k] as i128));
    let sub = |a: [i128; 3], b: [i128; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |u: [i128; 3], v: [i128; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let unit = |k: usize| [0, 1, 2].map(|j| i128::from(j == k));
    let edges = [sub(p[1], p[0]), sub(p[2], p[1]), sub(p[0], p[2])];
    let mut gradients = vec![unit(0), unit(1), unit(2), cross(edges[0], edges[1])];
    for e in edges {
        gradients.extend((0..3).map(|k| cross(e, unit(k))));
    }
    let mut axes = [([0i128; 3], 0i128, 0i128); MAX_AXES];
    for (axis, g) in axes.iter_mut().zip(gradients) {
        let projections = p.map(|v| g[0] * v[0] + g[1] * v[1] + g[2] * v[2]);
        let grow = margin * g.iter().map(|x| x.abs()).sum::<i128>();
        *axis = (
            g,
            projections.into_iter().min().unwrap_or(0) - grow,
            projections.into_iter().max().unwrap_or(0) + grow,
        );
    }
    axes
}

#[cfg(test)]
mod tests {
    use super::*;

    // Single decisions (a corner cut by the plane, a segment beside an edge)
    // are tested through `bounding_volume::triangle_touches_box`, which
    // calls this classifier; the independent oracle is in
    // tests/octree_classifier.rs.

    /// The interpolated children's mask equals testing each child directly.
    #[test]
    fn children_by_interpolation_equal_direct_tests() {
        let cell = Cell {
            lo: [-8, -8, -8],
            level: 4,
        };
        let triangles = [
            [[-8, -8, -8], [8, 8, 8], [8, -8, 0]],
            [[0, 0, 0], [0, 0, 0], [0, 0, 0]],
            [[-3, 5, 100], [7, 1, -50], [2, 2, 2]],
            [[1, 1, 1], [3, 1, 1], [1, 3, 1]],
        ];
        for t in triangles {
            let test = TriangleCellTest::new(&t);
            let direct: u8 = (0..8)
                .filter(|&o| test.touches_box(&cell.child(o).as_box()))
                .map(|o| 1u8 << o)
                .sum();
            assert_eq!(test.children_of_cell(&cell), direct, "{t:?}");
        }
    }

    /// The root-relative axes decide every cell under the root as the
    /// triangle's own test does.
    #[test]
    fn root_relative_axes_decide_as_the_test_does() {
        let root = Cell {
            lo: [-8, -3, 5],
            level: 4,
        };
        let triangles = [
            [[-8, -3, 5], [8, 13, 21], [8, -3, 13]],
            [[0, 0, 9], [0, 0, 9], [0, 0, 9]],
            [[-3, 5, 100], [7, 1, -50], [2, 2, 2]],
            [[1, 1, 6], [3, 1, 6], [1, 3, 6]],
            [[2, 2, 7], [6, 6, 11], [4, 4, 9]],
        ];
        for (t, margin) in triangles
            .iter()
            .flat_map(|t| [(*t, 0), (*t, BROAD_PHASE_MARGIN)])
        {
            let test = TriangleCellTest::widened(&t, margin);
            let axes = root_relative_axes(&t, root.lo, margin);
            for level in 0..=2 {
                let side = 1i64 << level;
                for i in 0..(16 / side) {
                    for j in 0..(16 / side) {
                        for k in [0, 16 / side - 1] {
                            let cell = Cell {
                                lo: [
                                    root.lo[0] + i * side,
                                    root.lo[1] + j * side,
                                    root.lo[2] + k * side,
                                ],
                                level: level as u32,
                            };
                            let relative = Cell {
                                lo: [0, 1, 2].map(|a| cell.lo[a] - root.lo[a]),
                                level: cell.level,
                            };
                            let hardware = axes.iter().all(|&(g, low, high)| {
                                AffineOverBox::over_cell(g, &relative).meets(low, high)
                            });
                            assert_eq!(
                                hardware,
                                test.touches_box(&cell.as_box()),
                                "{t:?} {cell:?} margin {margin}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// The widened test keeps every cell that a point within one step of
    /// the triangle lies in (here: cells touching the triangle's vertices
    /// moved by one step), and keeps more cells than the exact test.
    #[test]
    fn widened_test_keeps_cells_within_a_step() {
        let t = [[3, 3, 3], [9, 4, 3], [4, 9, 5]];
        let (exact, widened) = (
            TriangleCellTest::new(&t),
            TriangleCellTest::widened(&t, BROAD_PHASE_MARGIN),
        );
        let mut extra = 0;
        for x in -2..14 {
            for y in -2..14 {
                for z in -2..10 {
                    let cell = Cell {
                        lo: [x, y, z],
                        level: 0,
                    }
                    .as_box();
                    let near = t
                        .iter()
                        .any(|v| (0..3).all(|k| v[k] + 1 >= cell.lo[k] && v[k] - 1 <= cell.hi[k]));
                    assert!(!near || widened.touches_box(&cell), "{cell:?}");
                    assert!(!exact.touches_box(&cell) || widened.touches_box(&cell));
                    extra += (widened.touches_box(&cell) && !exact.touches_box(&cell)) as usize;
                }
            }
        }
        assert!(extra > 0);
    }
}
