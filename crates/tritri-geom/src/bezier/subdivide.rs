//! De Casteljau subdivision: a patch cut at `u = 1/2` or `v = 1/2` into two
//! patches that trace the same surface, and the teapot's 32 patches into
//! 64 to 512 (`bezier_lod_gpu.txt`, section 4).

use super::BezierPatch;
use nalgebra::Point3;

fn mid(a: Point3<f64>, b: Point3<f64>) -> Point3<f64> {
    Point3::from(0.5 * (a.coords + b.coords))
}

/// A cubic cut at `t = 1/2`: the control points of both halves.
fn split_cubic(b: [Point3<f64>; 4]) -> ([Point3<f64>; 4], [Point3<f64>; 4]) {
    let l1 = [mid(b[0], b[1]), mid(b[1], b[2]), mid(b[2], b[3])];
    let l2 = [mid(l1[0], l1[1]), mid(l1[1], l1[2])];
    let m = mid(l2[0], l2[1]);
    ([b[0], l1[0], l2[0], m], [m, l2[1], l1[2], b[3]])
}

impl BezierPatch {
    /// The halves `u <= 1/2` and `u >= 1/2` (each column of the net cut).
    pub fn split_u(&self) -> (BezierPatch, BezierPatch) {
        let (mut a, mut b) = (self.net, self.net);
        for j in 0..4 {
            let (low, high) = split_cubic([0, 1, 2, 3].map(|i| self.net[i][j]));
            for i in 0..4 {
                a[i][j] = low[i];
                b[i][j] = high[i];
            }
        }
        (BezierPatch { net: a }, BezierPatch { net: b })
    }

    /// The halves `v <= 1/2` and `v >= 1/2` (each row cut).
    pub fn split_v(&self) -> (BezierPatch, BezierPatch) {
        let (mut a, mut b) = (self.net, self.net);
        for i in 0..4 {
            let (low, high) = split_cubic(self.net[i]);
            a[i] = low;
            b[i] = high;
        }
        (BezierPatch { net: a }, BezierPatch { net: b })
    }
}

/// Every patch cut in two `times` times, alternately along `u` and `v`
/// (so 32 patches become 64, 128, 256, 512 for `times` 1 to 4).
pub fn subdivide(patches: &[BezierPatch], times: u32) -> Vec<BezierPatch> {
    let mut out = patches.to_vec();
    for step in 0..times {
        out = out
            .iter()
            .flat_map(|p| {
                let (a, b) = if step % 2 == 0 {
                    p.split_u()
                } else {
                    p.split_v()
                };
                [a, b]
            })
            .collect();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::tests::wavy_patch;
    use super::*;

    /// The halves trace the parent: a half's `(s, t)` is the parent's
    /// `(s/2, t)` or `(1/2 + s/2, t)`.
    #[test]
    fn halves_trace_the_parent() {
        let p = wavy_patch();
        let ((ua, ub), (va, vb)) = (p.split_u(), p.split_v());
        for (s, t) in [(0.0, 0.3), (0.25, 0.75), (1.0, 1.0), (0.6, 0.1)] {
            assert!((ua.evaluate(s, t) - p.evaluate(s / 2.0, t)).norm() < 1e-12);
            assert!((ub.evaluate(s, t) - p.evaluate(0.5 + s / 2.0, t)).norm() < 1e-12);
            assert!((va.evaluate(t, s) - p.evaluate(t, s / 2.0)).norm() < 1e-12);
            assert!((vb.evaluate(t, s) - p.evaluate(t, 0.5 + s / 2.0)).norm() < 1e-12);
        }
        assert_eq!(subdivide(&[p], 4).len(), 16);
    }
}
