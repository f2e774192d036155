//! Boundary representation to voxels, exactly (`octree_engine.txt`,
//! function 3): a triangle mesh into the `2^level` voxel grid.
//!
//! **Frame.** The mesh's bounding box is scaled uniformly so that its
//! longest side spans the grid, its low corner at the grid's origin, and
//! every vertex is rounded to a *fine* grid of `2^SUB_BITS` steps per voxel
//! ([`VoxelFrame`]). Everything after the rounding is exact integer
//! arithmetic: voxel `(i, j, k)` is the closed fine-grid cube
//! `[i S, (i + 1) S] × …` with `S = 2^SUB_BITS`, and its centre
//! `(i S + S/2, …)` is a fine grid point.
//!
//! **Surface** ([`surface`]): every voxel whose closed cube a closed
//! triangle meets, by the octree engine's triangle–cell classifier
//! ([`TriangleCellTest`]) descending from the root cell by interpolation.
//! A face on a voxel face, edge or corner marks the voxels on both sides.
//!
//! **Solid** ([`solid`]): every voxel whose centre is inside the closed
//! mesh or on it. The mesh must be closed: every edge (between distinct
//! rounded vertices) must be used by an even number of triangles, or the
//! answer is an error naming an edge that is not ([`OpenEdge`]). Inside is
//! decided by the parity of the triangles a ray from the centre along `+z`
//! crosses. A ray through a vertex or an edge is the case voxelizers get
//! wrong; here the ray's foot is moved by a symbolic perturbation
//! `(x + ε, y + ε²)` (Simulation of Simplicity), so it lies strictly inside
//! or strictly outside every triangle's projection and the parity is the
//! same as for a ray moved by a tiny real amount, well defined on a closed
//! mesh. Centres on the surface itself count as inside, found by solving
//! each triangle's plane for a centre along its dominant axis.

use super::cell::Cell;
use super::tree::Placement;
use super::triangle_cell::TriangleCellTest;
use super::voxels::VoxelGrid;
use crate::fixed_point::{FixedPoint3, FixedTriangle};
use crate::triangle::{Point, Triangle};
use std::collections::HashMap;

/// Fine grid steps per voxel, as a power of two: vertices are rounded to
/// 1/65536 of a voxel.
pub const SUB_BITS: u32 = 16;

/// The map from mesh coordinates to the fine grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VoxelFrame {
    /// The grid is `2^level` voxels on a side.
    pub level: u32,
    /// Mesh coordinates of the grid's origin.
    pub origin: Point,
    /// The side of one voxel in mesh units.
    pub voxel_size: f64,
}

/// Why a mesh cannot be voxelized.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VoxelizeError {
    #[error("resolution {0} is not a power of two from 2 to 1024")]
    Resolution(u64),
    #[error("triangle {triangle} has a coordinate that is not finite ({value})")]
    NotFinite { triangle: usize, value: f64 },
    #[error("the mesh has no triangles")]
    Empty,
    #[error(transparent)]
    Open(#[from] OpenEdge),
}

/// An edge of a mesh that is not closed, in mesh coordinates (after
/// rounding to the fine grid) and with a triangle that uses it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "the mesh is not closed: the edge from ({:.6}, {:.6}, {:.6}) to ({:.6}, {:.6}, {:.6}) is used by {uses} triangle(s), triangle {triangle} among them (solid voxelization needs every edge used an even number of times)",
    from[0], from[1], from[2], to[0], to[1], to[2]
)]
pub struct OpenEdge {
    pub from: Point,
    pub to: Point,
    pub uses: u32,
    pub triangle: usize,
}

/// The level of a resolution `n = 2^level`, 2 to 1024.
pub fn level_of_resolution(n: u64) -> Result<u32, VoxelizeError> {
    if n.is_power_of_two() && (2..=1024).contains(&n) {
        Ok(n.trailing_zeros())
    } else {
        Err(VoxelizeError::Resolution(n))
    }
}

impl VoxelFrame {
    /// The frame whose grid of side `2^level` just holds `triangles`.
    pub fn fit(triangles: &[Triangle], level: u32) -> Result<VoxelFrame, VoxelizeError> {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for (triangle, t) in triangles.iter().enumerate() {
            for &value in t.iter().flatten() {
                if !value.is_finite() {
                    return Err(VoxelizeError::NotFinite { triangle, value });
                }
            }
            for p in t {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        if triangles.is_empty() {
            return Err(VoxelizeError::Empty);
        }
        let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        let side = (1u64 << level) as f64;
        let voxel_size = if extent > 0.0 && extent.is_finite() {
            extent / side
        } else {
            1.0
        };
        Ok(VoxelFrame {
            level,
            origin: lo,
            voxel_size,
        })
    }

    /// Fine grid steps per voxel.
    pub fn sub_steps(&self) -> i64 {
        1 << SUB_BITS
    }

    /// The fine grid's step in mesh units: the rounding error of a
    /// coordinate is at most half of it.
    pub fn fine_step(&self) -> f64 {
        self.voxel_size / self.sub_steps() as f64
    }

    /// The fine grid point nearest to `p`, kept inside the grid's cube.
    pub fn quantize_point(&self, p: Point) -> FixedPoint3 {
        let top = (1i64 << (self.level + SUB_BITS)) as f64;
        [0, 1, 2].map(|k| {
            ((p[k] - self.origin[k]) / self.fine_step())
                .round()
                .clamp(0.0, top) as i64
        })
    }

    pub fn quantize(&self, t: &Triangle) -> FixedTriangle {
        t.map(|p| self.quantize_point(p))
    }

    /// The mesh point a fine grid point stands for.
    pub fn dequantize_point(&self, q: FixedPoint3) -> Point {
        [0, 1, 2].map(|k| self.origin[k] + q[k] as f64 * self.fine_step())
    }

    /// Where the voxel grid sits in the mesh's coordinates.
    pub fn placement(&self) -> Placement {
        Placement {
            origin: self.origin,
            voxel_size: self.voxel_size,
        }
    }
}

/// Every voxel a closed triangle meets.
pub fn surface(
    triangles: &[FixedTriangle],
    level: u32,
    progress: &mut dyn FnMut(usize),
) -> VoxelGrid {
    let mut grid = VoxelGrid::empty(level);
    let root = Cell {
        lo: [0; 3],
        level: level + SUB_BITS,
    };
    let mut stack = Vec::new();
    for (index, t) in triangles.iter().enumerate() {
        let test = TriangleCellTest::new(t);
        let values = test.values(&root);
        if !test.touches(&values) {
            continue;
        }
        stack.push((root, values));
        while let Some((cell, values)) = stack.pop() {
            if cell.level == SUB_BITS {
                grid.set(cell.lo.map(|c| (c >> SUB_BITS) as usize));
                continue;
            }
            let mask = test.children_touched(&values);
            for octant in (0..8).filter(|o| mask >> o & 1 == 1) {
                stack.push((cell.child(octant), test.child(&values, octant)));
            }
        }
        if index % 4096 == 4095 {
            progress(index + 1);
        }
    }
    progress(triangles.len());
    grid
}

/// Checks that every edge between distinct vertices is used an even number
/// of times. `frame` turns the offending edge back into mesh coordinates.
pub fn check_closed(triangles: &[FixedTriangle], frame: &VoxelFrame) -> Result<(), OpenEdge> {
    let mut uses: HashMap<(FixedPoint3, FixedPoint3), (u32, usize)> = HashMap::new();
    for (index, t) in triangles.iter().enumerate() {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            if a != b {
                let entry = uses.entry((a.min(b), a.max(b))).or_insert((0, index));
                entry.0 += 1;
            }
        }
    }
    // The first open edge in triangle order, so the message is reproducible.
    let open = uses
        .into_iter()
        .filter(|(_, (count, _))| count % 2 == 1)
        .min_by_key(|(_, (_, first))| *first);
    match open {
        None => Ok(()),
        Some(((a, b), (count, triangle))) => Err(OpenEdge {
            from: frame.dequantize_point(a),
            to: frame.dequantize_point(b),
            uses: count,
            triangle,
        }),
    }
}

/// Every voxel whose centre is inside or on the closed mesh.
pub fn solid(
    triangles: &[FixedTriangle],
    frame: &VoxelFrame,
    progress: &mut dyn FnMut(usize),
) -> Result<VoxelGrid, OpenEdge> {
    check_closed(triangles, frame)?;
    let level = frame.level;
    let n = 1usize << level;
    // Per column (x fastest), the number of voxels from the bottom whose
    // centre lies below each crossing of the ray.
    let mut crossings: Vec<Vec<u16>> = vec![Vec::new(); n * n];
    let mut grid = VoxelGrid::empty(level);
    for (index, t) in triangles.iter().enumerate() {
        let p = t.map(|v| v.map(i128::from));
        let normal = cross(sub(p[1], p[0]), sub(p[2], p[1]));
        if normal[2] != 0 {
            for_columns_under(&p, 0, 1, level, |i, j, centre| {
                if covers_perturbed(&p, centre, normal[2] > 0) {
                    crossings[j * n + i].push(voxels_below(&p[0], normal, centre, level) as u16);
                }
            });
        }
        mark_centres_on(&p, normal, level, &mut grid);
        if index % 4096 == 4095 {
            progress(index + 1);
        }
    }
    for (column, below) in crossings.iter_mut().enumerate() {
        if below.is_empty() {
            continue;
        }
        // Voxel l is inside iff an odd number of crossings lie above its
        // centre, i.e. have more than l voxels below them.
        below.sort_unstable_by(|a, b| b.cmp(a));
        let (i, j) = (column % n, column / n);
        let mut inside = false;
        let mut next = 0;
        for l in (0..n).rev() {
            while next < below.len() && below[next] as usize > l {
                inside = !inside;
                next += 1;
            }
            if inside {
                grid.set([i, j, l]);
            }
        }
    }
    progress(triangles.len());
    Ok(grid)
}

fn sub(a: [i128; 3], b: [i128; 3]) -> [i128; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(u: [i128; 3], v: [i128; 3]) -> [i128; 3] {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

/// Fine coordinate of the centre of voxel `i`.
fn centre_of(i: i128) -> i128 {
    let s = 1i128 << SUB_BITS;
    i * s + s / 2
}

/// The voxel indices `i` in `[0, n)` whose centres lie in `[lo, hi]`.
fn centres_within(lo: i128, hi: i128, level: u32) -> std::ops::Range<usize> {
    let s = 1i128 << SUB_BITS;
    // centre_of(i) >= lo  <=>  i >= (lo - s/2) / s, rounded up.
    let first = (lo - s / 2).div_euclid(s) + i128::from((lo - s / 2).rem_euclid(s) != 0);
    let last = (hi - s / 2).div_euclid(s);
    let n = 1i128 << level;
    let (first, end) = (first.clamp(0, n), (last + 1).clamp(0, n));
    first as usize..end.max(first) as usize
}

/// The voxel indices along axis `k` whose centres lie within the
/// triangle's extent along `k`.
fn centres_under(p: &[[i128; 3]; 3], k: usize, level: u32) -> std::ops::Range<usize> {
    centres_within(
        p.iter().map(|v| v[k]).min().unwrap_or(0),
        p.iter().map(|v| v[k]).max().unwrap_or(0),
        level,
    )
}

/// Calls `f(i, j, centre)` for every column of voxel centres along the
/// third axis whose foot, in axes `a` and `b`, lies in the triangle's
/// projected bounding box.
fn for_columns_under(
    p: &[[i128; 3]; 3],
    a: usize,
    b: usize,
    level: u32,
    mut f: impl FnMut(usize, usize, [i128; 2]),
) {
    let columns = centres_under(p, a, level);
    for j in centres_under(p, b, level) {
        for i in columns.clone() {
            f(i, j, [centre_of(i as i128), centre_of(j as i128)]);
        }
    }
}

/// `(b - a) × (c - a)` in the xy plane.
fn orient_xy(a: [i128; 3], b: [i128; 3], c: [i128; 2]) -> i128 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Is the point `(x + ε, y + ε²)` strictly inside the triangle's xy
/// projection (counter-clockwise when `ccw`)? With the perturbation the
/// orientation of an edge `a → b` is never zero: its sign is that of the
/// exact value, else of `a_y - b_y` (the ε term), else of `b_x - a_x`
/// (the ε² term); an edge of zero length is never part of a triangle with
/// a projection of non-zero area.
fn covers_perturbed(p: &[[i128; 3]; 3], foot: [i128; 2], ccw: bool) -> bool {
    (0..3).all(|e| {
        let (a, b) = (p[e], p[(e + 1) % 3]);
        let exact = orient_xy(a, b, foot);
        let sign = if exact != 0 {
            exact.signum()
        } else if a[1] != b[1] {
            (a[1] - b[1]).signum()
        } else {
            (b[0] - a[0]).signum()
        };
        (sign > 0) == ccw
    })
}

/// How many voxels of the column at `foot` have their centre strictly
/// below the triangle's plane there, `n · (q - v0) = 0` with `n_z != 0`.
fn voxels_below(v0: &[i128; 3], normal: [i128; 3], foot: [i128; 2], level: u32) -> usize {
    // n_z z = n · v0 - n_x x - n_y y = r: the crossing's height is r / n_z.
    let r = normal[0] * (v0[0] - foot[0]) + normal[1] * (v0[1] - foot[1]) + normal[2] * v0[2];
    let (num, den) = if normal[2] > 0 {
        (r, normal[2])
    } else {
        (-r, -normal[2])
    };
    // centre_of(l) < num / den  <=>  l s den < num - (s/2) den.
    let s = 1i128 << SUB_BITS;
    let t = num - s / 2 * den;
    let below = if t <= 0 {
        0
    } else {
        (t + s * den - 1) / (s * den)
    };
    below.min(1i128 << level) as usize
}

/// Marks the voxels whose centre lies on the closed triangle.
fn mark_centres_on(p: &[[i128; 3]; 3], normal: [i128; 3], level: u32, grid: &mut VoxelGrid) {
    if normal == [0; 3] {
        mark_centres_on_segment(p, level, grid);
        return;
    }
    // Solve the plane along its dominant axis d over columns in a and b.
    let d = (0..3).max_by_key(|&k| normal[k].abs()).unwrap_or(2);
    let (a, b) = ((d + 1) % 3, (d + 2) % 3);
    let s = 1i128 << SUB_BITS;
    let orient = |u: [i128; 3], v: [i128; 3], c: [i128; 2]| {
        (v[a] - u[a]) * (c[1] - u[b]) - (v[b] - u[b]) * (c[0] - u[a])
    };
    let columns = centres_under(p, a, level);
    for j in centres_under(p, b, level) {
        for i in columns.clone() {
            let foot = [centre_of(i as i128), centre_of(j as i128)];
            let signs = [
                orient(p[0], p[1], foot),
                orient(p[1], p[2], foot),
                orient(p[2], p[0], foot),
            ];
            if !(signs.iter().all(|&v| v >= 0) || signs.iter().all(|&v| v <= 0)) {
                continue;
            }
            // n_d c = n · v0 - n_a foot_a - n_b foot_b, and c = l s + s/2.
            let r = normal[a] * (p[0][a] - foot[0])
                + normal[b] * (p[0][b] - foot[1])
                + normal[d] * p[0][d];
            let t = r - normal[d] * (s / 2);
            let den = normal[d] * s;
            if t % den == 0 {
                let l = t / den;
                if (0..1i128 << level).contains(&l) {
                    let mut v = [0usize; 3];
                    v[a] = i;
                    v[b] = j;
                    v[d] = l as usize;
                    grid.set(v);
                }
            }
        }
    }
}

/// A triangle of zero area is a segment (or a point): marks the voxel
/// centres on it.
fn mark_centres_on_segment(p: &[[i128; 3]; 3], level: u32, grid: &mut VoxelGrid) {
    // The two vertices farthest apart span the segment.
    let length = |u: [i128; 3], v: [i128; 3]| (0..3).map(|k| (u[k] - v[k]).abs()).sum::<i128>();
    let (from, to) = [(p[0], p[1]), (p[1], p[2]), (p[2], p[0])]
        .into_iter()
        .max_by_key(|&(u, v)| length(u, v))
        .unwrap_or((p[0], p[0]));
    let dir = sub(to, from);
    let d = (0..3).max_by_key(|&k| dir[k].abs()).unwrap_or(0);
    let s = 1i128 << SUB_BITS;
    for l in centres_within(from[d].min(to[d]), from[d].max(to[d]), level) {
        let c_d = centre_of(l as i128);
        // The segment's point at c_d: from + dir (c_d - from_d) / dir_d.
        let mut voxel = [0usize; 3];
        let on = (0..3).all(|k| {
            let (num, den) = if dir[d] == 0 {
                (from[k], 1)
            } else {
                (from[k] * dir[d] + dir[k] * (c_d - from[d]), dir[d])
            };
            if num % den != 0 {
                return false;
            }
            let c = num / den;
            let i = (c - s / 2).div_euclid(s);
            voxel[k] = i as usize;
            (c - s / 2).rem_euclid(s) == 0 && (0..1i128 << level).contains(&i)
        });
        if on {
            grid.set(voxel);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The twelve triangles of the closed box `[lo, hi]` (fine grid).
    pub(crate) fn box_triangles(lo: [i64; 3], hi: [i64; 3]) -> Vec<FixedTriangle> {
        let corner = |o: usize| [0, 1, 2].map(|k| if o >> k & 1 == 1 { hi[k] } else { lo[k] });
        let mut out = Vec::new();
        for k in 0..3 {
            for side in 0..2 {
                let c: Vec<usize> = (0..8).filter(|o| o >> k & 1 == side).collect();
                out.push([corner(c[0]), corner(c[1]), corner(c[3])]);
                out.push([corner(c[0]), corner(c[3]), corner(c[2])]);
            }
        }
        out
    }

    fn frame(level: u32) -> VoxelFrame {
        VoxelFrame {
            level,
            origin: [0.0; 3],
            voxel_size: 1.0,
        }
    }

    fn quiet(_: usize) {}

    /// A cube spanning the whole grid: every voxel solid (8 × 8 × 8, not
    /// 8 × 8 × 7), the boundary layer as surface; at several resolutions.
    #[test]
    fn a_cube_filling_the_grid_has_every_voxel() {
        for level in 1..=5 {
            let n = 1i64 << level;
            let top = n << SUB_BITS;
            let cube = box_triangles([0; 3], [top; 3]);
            let solid = solid(&cube, &frame(level), &mut quiet).unwrap();
            assert_eq!(solid.count(), (n * n * n) as u64, "level {level}");
            let inner = (n - 2).max(0);
            assert_eq!(
                surface(&cube, level, &mut quiet).count(),
                (n * n * n - inner * inner * inner) as u64,
                "level {level}"
            );
        }
    }

    /// Boxes with faces on voxel faces, through voxel centres, and between
    /// them: exact counts.
    #[test]
    fn axis_aligned_boxes_give_exact_counts() {
        let s = 1i64 << SUB_BITS;
        let level = 4;
        // [1, 5] voxels: faces on voxel faces, centres 1.5 .. 4.5: 4 per axis.
        // Surface: voxels 0..=5 touch the closed box; of them only 2 and 3
        // (per axis) miss its boundary.
        let cases = [
            ([s, s, s], [5 * s, 5 * s, 5 * s], 64, 6 * 6 * 6 - 2 * 2 * 2),
            // [1.5, 3.5]: centres 1.5, 2.5, 3.5 all on or inside: 27; the
            // surface misses only voxel (2, 2, 2).
            ([3 * s / 2; 3], [7 * s / 2; 3], 27, 26),
            // [1.25, 3.75] x [2, 2.75] x [0, 16]: centres 1.5..3.5 (3), 2.5 (1), all 16.
            (
                [5 * s / 4, 2 * s, 0],
                [15 * s / 4, 11 * s / 4, 16 * s],
                3 * 16,
                3 * 2 * 16,
            ),
        ];
        for (lo, hi, solid_count, surface_count) in cases {
            let b = box_triangles(lo, hi);
            assert_eq!(
                solid(&b, &frame(level), &mut quiet).unwrap().count(),
                solid_count,
                "{lo:?} {hi:?}"
            );
            assert_eq!(
                surface(&b, level, &mut quiet).count(),
                surface_count,
                "{lo:?} {hi:?}"
            );
        }
    }

    #[test]
    fn an_open_mesh_names_an_edge() {
        let s = 1i64 << SUB_BITS;
        let mut b = box_triangles([0; 3], [s; 3]);
        b.pop();
        let err = solid(&b, &frame(1), &mut quiet).unwrap_err();
        assert_eq!(err.uses, 1);
        assert!(err.to_string().contains("not closed"), "{err}");
    }

    #[test]
    fn resolutions_are_powers_of_two() {
        assert_eq!(level_of_resolution(512), Ok(9));
        assert_eq!(
            level_of_resolution(100),
            Err(VoxelizeError::Resolution(100))
        );
        assert_eq!(
            level_of_resolution(2048),
            Err(VoxelizeError::Resolution(2048))
        );
    }
}
