//! Evaluating a bicubic patch (`bezier_lod_gpu.txt`, equations 2.1 and
//! 2.2): the point `S(u, v)` and the derivatives `d_u`, `d_v`, by De
//! Casteljau's algorithm at one parameter pair and by forward differencing
//! over a uniform grid; and the normal `d_u × d_v`, defined also where a
//! row of the net collapses to a point (the teapot's lid and bottom),
//! where `d_u × d_v` vanishes.

use super::BezierPatch;
use nalgebra::{Point3, Vector3};

/// A cubic Bezier curve at `t` by De Casteljau: the point and its
/// derivative `3 (b^2_1 - b^2_0)`. On coordinate vectors, so that the
/// same steps serve the control points and the derivative rows.
fn cubic_coordinates(b: [Vector3<f64>; 4], t: f64) -> (Vector3<f64>, Vector3<f64>) {
    let lerp = |a: Vector3<f64>, b: Vector3<f64>| a + (b - a) * t;
    let l1 = [lerp(b[0], b[1]), lerp(b[1], b[2]), lerp(b[2], b[3])];
    let l2 = [lerp(l1[0], l1[1]), lerp(l1[1], l1[2])];
    (lerp(l2[0], l2[1]), 3.0 * (l2[1] - l2[0]))
}

/// A cubic Bezier curve at `t` by De Casteljau: the point and its
/// derivative.
pub fn cubic(b: [Point3<f64>; 4], t: f64) -> (Point3<f64>, Vector3<f64>) {
    let (p, d) = cubic_coordinates(b.map(|p| p.coords), t);
    (Point3::from(p), d)
}

/// A point of the surface with its partial derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    pub point: Point3<f64>,
    pub du: Vector3<f64>,
    pub dv: Vector3<f64>,
}

impl BezierPatch {
    /// `S(u, v)`, `d_u`, `d_v` by De Casteljau: each row of the net (fixed
    /// `i`, along `v`) at `v`, then the four results along `u`.
    pub fn evaluate_with_derivatives(&self, u: f64, v: f64) -> SurfacePoint {
        let rows = self
            .net
            .map(|row| cubic_coordinates(row.map(|p| p.coords), v));
        let (point, du) = cubic_coordinates(rows.map(|r| r.0), u);
        let (dv, _) = cubic_coordinates(rows.map(|r| r.1), u);
        SurfacePoint {
            point: Point3::from(point),
            du,
            dv,
        }
    }

    /// The unit normal at `(u, v)`: `d_u × d_v` normalized, or, where it
    /// vanishes (a collapsed row or column of the net), its limit from
    /// inside the patch, the direction of the normal patch's derivative
    /// towards the parameter square's centre (`super::cone::NormalPatch`).
    /// `None` only where that vanishes too.
    pub fn normal(&self, u: f64, v: f64) -> Option<Vector3<f64>> {
        let s = self.evaluate_with_derivatives(u, v);
        let n = s.du.cross(&s.dv);
        let scale = self.size();
        if n.norm() > 1e-12 * scale * scale {
            return Some(n / n.norm());
        }
        super::cone::NormalPatch::of(self).limit_direction(u, v)
    }

    /// The diagonal of the net's bounding box (a length scale).
    pub fn size(&self) -> f64 {
        let bounds = super::query::net_box(self);
        (Vector3::from(bounds.hi) - Vector3::from(bounds.lo)).norm()
    }

    /// `S` on the `(n + 1)^2` grid `u = i / n`, `v = j / n` (`[i][j]`), by
    /// forward differencing: each row of the net is stepped along `v` with
    /// three adds per step, and each column of the results along `u` the
    /// same way; no multiplication inside the loops (the hardware
    /// tessellation's scheme). Agrees with [`Self::evaluate`] to rounding.
    pub fn grid_by_forward_differences(&self, n: usize) -> Vec<Vec<Point3<f64>>> {
        let n = n.max(1);
        // Samples of the four row curves at every v_j.
        let rows: Vec<Vec<[f64; 3]>> = self
            .net
            .iter()
            .map(|row| forward_differences(row.map(Into::into), n))
            .collect();
        let mut grid = vec![vec![Point3::origin(); n + 1]; n + 1];
        for j in 0..=n {
            let column = [rows[0][j], rows[1][j], rows[2][j], rows[3][j]];
            for (i, p) in forward_differences(column, n).into_iter().enumerate() {
                grid[i][j] = Point3::from(p);
            }
        }
        grid
    }
}

/// A cubic with control points `b` at `t = k / n`, `k = 0..=n`, by forward
/// differences: the value and its first three differences at `t = 0`, then
/// three adds per step. On plain arrays, component by component, as the
/// hardware's fixed-point unit will step them.
fn forward_differences(b: [[f64; 3]; 4], n: usize) -> Vec<[f64; 3]> {
    let h = 1.0 / n as f64;
    // Power basis: p(t) = a0 + a1 t + a2 t^2 + a3 t^3.
    let a0 = b[0];
    let a1 = [0, 1, 2].map(|k| 3.0 * (b[1][k] - b[0][k]));
    let a2 = [0, 1, 2].map(|k| 3.0 * (b[2][k] - 2.0 * b[1][k] + b[0][k]));
    let a3 = [0, 1, 2].map(|k| b[3][k] - 3.0 * b[2][k] + 3.0 * b[1][k] - b[0][k]);
    let mut p = a0;
    let mut d1 = [0, 1, 2].map(|k| a1[k] * h + a2[k] * h * h + a3[k] * h * h * h);
    let mut d2 = [0, 1, 2].map(|k| 2.0 * a2[k] * h * h + 6.0 * a3[k] * h * h * h);
    let d3 = [0, 1, 2].map(|k| 6.0 * a3[k] * h * h * h);
    let mut out = Vec::with_capacity(n + 1);
    for _ in 0..=n {
        out.push(p);
        for k in 0..3 {
            p[k] += d1[k];
            d1[k] += d2[k];
            d2[k] += d3[k];
        }
    }
    // The last sample is the end point exactly (no accumulated rounding).
    if let Some(last) = out.last_mut() {
        *last = b[3];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::tests::wavy_patch;
    use super::*;

    /// De Casteljau's derivatives equal central differences of `evaluate`,
    /// and its point equals the Bernstein form.
    #[test]
    fn derivatives_match_finite_differences() {
        let p = wavy_patch();
        for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.5), (0.5, 1.0)] {
            let s = p.evaluate_with_derivatives(u, v);
            let e = p.evaluate(u, v);
            assert!((s.point - e).norm() < 1e-12);
            let h = 1e-6;
            let (u0, u1) = ((u - h).max(0.0), (u + h).min(1.0));
            let (v0, v1) = ((v - h).max(0.0), (v + h).min(1.0));
            let fu = (p.evaluate(u1, v) - p.evaluate(u0, v)) / (u1 - u0);
            let fv = (p.evaluate(u, v1) - p.evaluate(u, v0)) / (v1 - v0);
            assert!(
                (fu - s.du).norm() < 1e-4 && (fv - s.dv).norm() < 1e-4,
                "({u}, {v})"
            );
        }
    }

    #[test]
    fn forward_differences_equal_de_casteljau() {
        let p = wavy_patch();
        for n in [1, 4, 5, 20, 64] {
            let grid = p.grid_by_forward_differences(n);
            for i in 0..=n {
                for j in 0..=n {
                    let e = p.evaluate(i as f64 / n as f64, j as f64 / n as f64);
                    assert!(
                        (grid[i][j] - e).norm() < 1e-10 * p.size(),
                        "n {n} ({i}, {j})"
                    );
                }
            }
        }
    }

    /// A row of the net collapsed to a point: `d_u × d_v` vanishes along
    /// it, the normal is still defined there and is the limit of the
    /// normals next to it.
    #[test]
    fn normals_are_defined_on_a_collapsed_row() {
        let mut p = wavy_patch();
        p.net[0] = [Point3::new(1.0, 1.0, 2.0); 4];
        for v in [0.0, 0.25, 0.5, 1.0] {
            let s = p.evaluate_with_derivatives(0.0, v);
            assert!(s.du.cross(&s.dv).norm() < 1e-12);
            let n = p.normal(0.0, v).expect("a normal on the collapsed row");
            let near = p.normal(1e-5, v).expect("a normal next to it");
            assert!(n.dot(&near) > 0.999, "v {v}: {n:?} against {near:?}");
        }
    }
}
