//! Levels of detail for a patch (`bezier_lod_gpu.txt`, section 3.3): the
//! paper's four distance levels, and a level driven by an error bound.
//!
//! **Error bound.** A patch sampled on the uniform `n × n` grid and drawn
//! as two triangles per cell deviates from the surface by at most
//! `(M_uu + 2 M_uv + M_vv) / (8 n^2)` (Filip, Magedson and Markot, 1986),
//! with `M` bounds on the second derivatives' lengths. For a bicubic patch
//! those are bounded by the net's second differences: `|S_uu| <= 6 max
//! |P_{i+2,j} - 2 P_{i+1,j} + P_{i,j}|`, `|S_uv| <= 9 max |P_{i+1,j+1} -
//! P_{i+1,j} - P_{i,j+1} + P_{i,j}|`, `|S_vv|` likewise: each derivative is
//! a Bernstein combination of those differences, whose weights sum to 1.

use super::BezierPatch;
use nalgebra::{Point3, Vector3};

/// The paper's samples per side, by distance: 5, 10, 15, 20.
pub const DISTANCE_LEVELS: [usize; 4] = [5, 10, 15, 20];

/// Samples per side for a patch at `distance` from the eye: 20 nearer than
/// `near`, 15 to `2 near`, 10 to `4 near`, 5 beyond (the paper fixes the
/// four levels, not the distances).
pub fn distance_level(distance: f64, near: f64) -> usize {
    let steps = [1.0, 2.0, 4.0];
    let far = steps.iter().filter(|&&s| distance >= s * near).count();
    DISTANCE_LEVELS[3 - far]
}

/// Bounds on `|S_uu|`, `|S_uv|`, `|S_vv|` over the patch.
pub fn second_derivative_bounds(patch: &BezierPatch) -> [f64; 3] {
    let p = &patch.net;
    let (mut uu, mut uv, mut vv) = (0.0f64, 0.0f64, 0.0f64);
    let comb = |a: Point3<f64>,
                b: Point3<f64>,
                c: Point3<f64>,
                d: Point3<f64>,
                wa: f64,
                wb: f64,
                wc: f64,
                wd: f64| {
        Vector3::from([0, 1, 2].map(|k| wa * a[k] + wb * b[k] + wc * c[k] + wd * d[k])).norm()
    };
    for i in 0..4 {
        for j in 0..4 {
            if i + 2 < 4 {
                uu = uu.max(comb(
                    p[i + 2][j],
                    p[i + 1][j],
                    p[i][j],
                    p[i][j],
                    1.0,
                    -2.0,
                    1.0,
                    0.0,
                ));
            }
            if j + 2 < 4 {
                vv = vv.max(comb(
                    p[i][j + 2],
                    p[i][j + 1],
                    p[i][j],
                    p[i][j],
                    1.0,
                    -2.0,
                    1.0,
                    0.0,
                ));
            }
            if i + 1 < 4 && j + 1 < 4 {
                uv = uv.max(comb(
                    p[i + 1][j + 1],
                    p[i + 1][j],
                    p[i][j + 1],
                    p[i][j],
                    1.0,
                    -1.0,
                    -1.0,
                    1.0,
                ));
            }
        }
    }
    [6.0 * uu, 9.0 * uv, 6.0 * vv]
}

/// The bound on the deviation of the `n × n` tessellation from the patch.
pub fn deviation_bound(patch: &BezierPatch, n: usize) -> f64 {
    let [uu, uv, vv] = second_derivative_bounds(patch);
    (uu + 2.0 * uv + vv) / (8.0 * (n.max(1) * n.max(1)) as f64)
}

/// The fewest samples per side whose tessellation stays within
/// `tolerance` of the patch (at most `max`; `max` if none does).
pub fn error_level(patch: &BezierPatch, tolerance: f64, max: usize) -> usize {
    let [uu, uv, vv] = second_derivative_bounds(patch);
    let needed = ((uu + 2.0 * uv + vv) / (8.0 * tolerance)).sqrt().ceil();
    if needed.is_finite() {
        (needed as usize).clamp(1, max.max(1))
    } else {
        max.max(1)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::wavy_patch;
    use super::*;

    #[test]
    fn distance_levels_step_down_with_distance() {
        assert_eq!(
            [0.5, 1.0, 3.0, 4.0, 100.0].map(|d| distance_level(d, 1.0)),
            [20, 15, 10, 5, 5]
        );
    }

    /// The measured deviation (densely sampled, against the triangles of
    /// the tessellation) stays below the bound, and the error level meets
    /// its tolerance with one sample fewer failing the bound.
    #[test]
    fn the_bound_holds_and_the_level_is_the_least() {
        let p = wavy_patch();
        for n in [1, 2, 4, 8] {
            let bound = deviation_bound(&p, n);
            let mut worst = 0.0f64;
            let m = 8;
            for ci in 0..n {
                for cj in 0..n {
                    let corner =
                        |a: usize, b: usize| p.evaluate(a as f64 / n as f64, b as f64 / n as f64);
                    let (c00, c10, c11, c01) = (
                        corner(ci, cj),
                        corner(ci + 1, cj),
                        corner(ci + 1, cj + 1),
                        corner(ci, cj + 1),
                    );
                    for a in 0..=m {
                        for b in 0..=m {
                            let (s, t) = (a as f64 / m as f64, b as f64 / m as f64);
                            // The point of the cell's two triangles over (s, t).
                            let flat = if t <= s {
                                c00 + s * (c10 - c00) + t * (c11 - c10)
                            } else {
                                c00 + t * (c01 - c00) + s * (c11 - c01)
                            };
                            let on =
                                p.evaluate((ci as f64 + s) / n as f64, (cj as f64 + t) / n as f64);
                            worst = worst.max((on - flat).norm());
                        }
                    }
                }
            }
            assert!(
                worst <= bound,
                "n {n}: deviation {worst} above the bound {bound}"
            );
        }
        let tolerance = deviation_bound(&p, 6) * 1.01;
        assert_eq!(error_level(&p, tolerance, 64), 6);
        assert!(deviation_bound(&p, 5) > tolerance);
    }
}
