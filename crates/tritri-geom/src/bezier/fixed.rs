//! A patch tessellated in fixed point, exactly: what the hardware
//! tessellation unit (`tritri_rtl::bezier::patch_tessellator`) computes.
//!
//! The control points are integers on a grid (a patch quantized into the
//! collision system's frame). With `n = 2^k` steps a side, the sample
//! `S(i/n, j/n)` times `n^6` is an integer: `n^3 B_a(i/n) = C(3, a) i^a
//! (n - i)^(3 - a)`. So the grid
//!
//! `G(i, j) = Σ_a Σ_b (n^3 B_a(i/n)) (n^3 B_b(j/n)) P_ab`
//!
//! is exact, and each vertex is `G(i, j) / n^6` rounded to the nearest grid
//! point (halves up): the only rounding. The hardware reaches the same
//! integers by forward differences (adds and shifts only); this model sums
//! the Bernstein form, so the co-simulation compares two different
//! computations.
//!
//! **Error against the f64 patch.** Rounding the control points moves the
//! surface by at most half a grid step per coordinate (the weights are
//! non-negative and sum to 1), and rounding a vertex by at most half a
//! step more: every vertex is within one grid step, per coordinate, of the
//! f64 surface point at the same parameters.

use super::query::patches_box;
use super::BezierPatch;
use crate::bounding_volume::Aabb;

/// A patch's control points on the grid, `net[row][column][axis]`.
pub type FixedNet = [[[i64; 3]; 4]; 4];

/// Binomial coefficients of the cubic Bernstein basis.
const BINOMIAL: [i128; 4] = [1, 3, 3, 1];

/// `n^3 B_a(t / n)` for `a = 0..3`.
fn scaled_bernstein(t: i128, n: i128) -> [i128; 4] {
    let s = n - t;
    [0, 1, 2, 3].map(|a| BINOMIAL[a] * t.pow(a as u32) * s.pow(3 - a as u32))
}

/// The `(n + 1)^2` vertices, `n = 2^k`, row by row (`i`, the first
/// parameter, outer; `j` inner), exactly rounded (module docs).
pub fn fixed_grid(net: &FixedNet, k: u32) -> Vec<[i64; 3]> {
    let n = 1i128 << k;
    let shift = 6 * k;
    let half = if shift == 0 { 0 } else { 1i128 << (shift - 1) };
    let mut out = Vec::with_capacity(((n + 1) * (n + 1)) as usize);
    for i in 0..=n {
        let bu = scaled_bernstein(i, n);
        for j in 0..=n {
            let bv = scaled_bernstein(j, n);
            let vertex = [0, 1, 2].map(|axis| {
                let g: i128 = (0..4)
                    .flat_map(|a| (0..4).map(move |b| (a, b)))
                    .map(|(a, b)| bu[a] * bv[b] * net[a][b][axis] as i128)
                    .sum();
                (g + half).div_euclid(1i128 << shift) as i64
            });
            out.push(vertex);
        }
    }
    out
}

/// The `2 n^2` triangles of the fixed-point grid, two per cell, cells row
/// by row (`i` outer): `[(i, j), (i + 1, j), (i + 1, j + 1)]` and `[(i, j),
/// (i + 1, j + 1), (i, j + 1)]`, what the hardware assembles
/// (`tritri_rtl::bezier::patch_triangles`).
pub fn fixed_triangles(net: &FixedNet, k: u32) -> Vec<crate::fixed_point::FixedTriangle> {
    let n = 1usize << k;
    let grid = fixed_grid(net, k);
    let at = |i: usize, j: usize| grid[i * (n + 1) + j];
    let mut out = Vec::with_capacity(2 * n * n);
    for i in 0..n {
        for j in 0..n {
            out.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            out.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    out
}

/// A grid for an f64 patch: `step` per grid unit, `origin` at grid 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchFrame {
    pub origin: [f64; 3],
    pub step: f64,
}

impl PatchFrame {
    /// The frame that puts `patches`' control points on a `width`-bit
    /// signed grid, centred, with a bit of margin.
    pub fn fit(patches: &[BezierPatch], width: u32) -> PatchFrame {
        let Aabb { lo, hi } = patches_box(patches).unwrap_or(Aabb {
            lo: [0.0; 3],
            hi: [0.0; 3],
        });
        let extent = (0..3)
            .map(|k| hi[k] - lo[k])
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        let origin = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
        // Half the range less a margin of two steps for the rounding.
        let half_range = ((1i64 << (width - 1)) - 2) as f64;
        PatchFrame {
            origin,
            step: extent / (2.0 * half_range),
        }
    }

    pub fn quantize(&self, patch: &BezierPatch) -> FixedNet {
        patch.net.map(|row| {
            row.map(|p| [0, 1, 2].map(|k| ((p[k] - self.origin[k]) / self.step).round() as i64))
        })
    }

    pub fn dequantize(&self, v: [i64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|k| self.origin[k] + v[k] as f64 * self.step)
    }
}

/// The largest distance, per coordinate and in grid steps, between the
/// fixed-point vertices of `patch` and its f64 surface at the same
/// parameters (at most 1, module docs).
pub fn max_error_in_steps(patch: &BezierPatch, frame: &PatchFrame, k: u32) -> f64 {
    let n = 1usize << k;
    let grid = fixed_grid(&frame.quantize(patch), k);
    let mut worst: f64 = 0.0;
    for i in 0..=n {
        for j in 0..=n {
            let exact = patch.evaluate(i as f64 / n as f64, j as f64 / n as f64);
            let ours = frame.dequantize(grid[i * (n + 1) + j]);
            for axis in 0..3 {
                worst = worst.max((ours[axis] - exact[axis]).abs() / frame.step);
            }
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::super::tests::wavy_patch;
    use super::*;

    /// Corners are control points; a patch whose net is an affine grid
    /// reproduces it exactly; every vertex is within a step of the f64
    /// surface.
    #[test]
    fn fixed_grid_is_exact_up_to_one_rounding() {
        let affine: FixedNet = std::array::from_fn(|a| {
            std::array::from_fn(|b| [30 * a as i64 - 45, 20 * b as i64, 7 * (a + b) as i64])
        });
        for k in 0..=4 {
            let n = 1usize << k;
            let grid = fixed_grid(&affine, k);
            assert_eq!(grid.len(), (n + 1) * (n + 1));
            assert_eq!(grid[0], affine[0][0]);
            assert_eq!(grid[n], affine[0][3]);
            assert_eq!(grid[(n + 1) * (n + 1) - 1], affine[3][3]);
            // S(u, v) = (90 u - 45, 60 v, 21 (u + v)): exact where that is an integer.
            if n <= 2 {
                for i in 0..=n {
                    for j in 0..=n {
                        let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                        let want = [90.0 * u - 45.0, 60.0 * v, 21.0 * (u + v)]
                            .map(|c: f64| (c + 0.5).floor() as i64);
                        assert_eq!(grid[i * (n + 1) + j], want, "k {k} ({i}, {j})");
                    }
                }
            }
        }
        let patch = wavy_patch();
        for width in [12, 16, 24] {
            let frame = PatchFrame::fit(&[patch], width);
            for k in [2, 3, 5] {
                let e = max_error_in_steps(&patch, &frame, k);
                assert!(e <= 1.0, "W {width}, k {k}: {e} steps");
            }
        }
    }
}
