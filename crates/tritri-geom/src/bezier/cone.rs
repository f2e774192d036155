//! The cone of normals (Shirman and Abi-Ezzi, Eurographics 1993; used by
//! `bezier_lod_gpu.txt`, section 3) as a guarantee: every normal of the
//! patch lies inside it.
//!
//! The normal `N(u, v) = d_u × d_v` of a bicubic patch is itself a Bezier
//! patch, of degree 5 × 5 ([`NormalPatch`]): `d_u` is a (2, 3) patch with
//! control vectors `3 (P_{i+1,j} - P_{i,j})`, `d_v` a (3, 2) patch with
//! `3 (P_{i,j+1} - P_{i,j})`, and the product of Bernstein polynomials is
//! `B^2_i B^3_k = C(2,i) C(3,k) / C(5,i+k) B^5_{i+k}`. So `N(u, v)` is a
//! combination of the 36 control vectors with non-negative weights: a cone
//! of half-angle below 90° (hence convex) that holds every control vector
//! holds every normal. Wider spreads give no cone (half-angle π). The cone's axis is the mean of the control vectors'
//! directions; its half-angle the largest angle from the axis to one of
//! them.

use super::BezierPatch;
use nalgebra::{Point3, Vector3};

/// `N = d_u × d_v` as a degree (5, 5) Bezier patch: `net[a][b]`, `a` along
/// `u`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalPatch {
    pub net: [[Vector3<f64>; 6]; 6],
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// A Bezier curve of any degree at `t` by De Casteljau: the point and the
/// derivative.
fn curve(points: &[Vector3<f64>], t: f64) -> (Vector3<f64>, Vector3<f64>) {
    let degree = points.len() - 1;
    let mut level: Vec<Vector3<f64>> = points.to_vec();
    let mut derivative = Vector3::zeros();
    while level.len() > 1 {
        if level.len() == 2 {
            derivative = degree as f64 * (level[1] - level[0]);
        }
        level = level.windows(2).map(|w| w[0] + (w[1] - w[0]) * t).collect();
    }
    (level[0], derivative)
}

impl NormalPatch {
    pub fn of(patch: &BezierPatch) -> NormalPatch {
        let p = &patch.net;
        let d = |a: Point3<f64>, b: Point3<f64>| 3.0 * (b - a);
        let mut net = [[Vector3::zeros(); 6]; 6];
        for i in 0..3 {
            for j in 0..4 {
                let du = d(p[i][j], p[i + 1][j]);
                for k in 0..4 {
                    for l in 0..3 {
                        let dv = d(p[k][l], p[k][l + 1]);
                        let w = binomial(2, i) * binomial(3, k) / binomial(5, i + k)
                            * binomial(3, j)
                            * binomial(2, l)
                            / binomial(5, j + l);
                        net[i + k][j + l] += w * du.cross(&dv);
                    }
                }
            }
        }
        NormalPatch { net }
    }

    /// `N(u, v)` and its partial derivatives `N_u`, `N_v`.
    pub fn evaluate(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let rows: Vec<(Vector3<f64>, Vector3<f64>)> =
            self.net.iter().map(|row| curve(row, v)).collect();
        let values: Vec<Vector3<f64>> = rows.iter().map(|r| r.0).collect();
        let slopes: Vec<Vector3<f64>> = rows.iter().map(|r| r.1).collect();
        let (n, nu) = curve(&values, u);
        let (nv, _) = curve(&slopes, u);
        (n, nu, nv)
    }

    /// Where `N(u, v) = 0`, the direction `N` takes as `(u, v)` moves
    /// towards the centre of the parameter square: the directional
    /// derivative `N_u (1/2 - u) + N_v (1/2 - v)`, normalized; `None` if it
    /// vanishes too.
    pub fn limit_direction(&self, u: f64, v: f64) -> Option<Vector3<f64>> {
        let (_, nu, nv) = self.evaluate(u, v);
        let d = nu * (0.5 - u) + nv * (0.5 - v);
        let l = d.norm();
        (l > 0.0).then(|| d / l)
    }
}

/// A cone holding every normal direction of a patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalCone {
    /// Unit axis: the mean direction of the normal patch's control vectors.
    pub axis: Vector3<f64>,
    /// Half-angle in radians: below π/2, or π when the control vectors
    /// spread 90° or more from the axis (then the cone bounds nothing, and
    /// every test below answers "maybe").
    pub half_angle: f64,
}

impl NormalCone {
    /// The cone of `patch`, or `None` when the patch has no normal at all
    /// (every control vector of `N` vanishes: a curve or a point).
    pub fn of(patch: &BezierPatch) -> Option<NormalCone> {
        let normals = NormalPatch::of(patch);
        let scale = patch.size();
        let vectors: Vec<Vector3<f64>> = normals
            .net
            .iter()
            .flatten()
            .copied()
            .filter(|n| n.norm() > 1e-14 * scale * scale)
            .collect();
        if vectors.is_empty() {
            return None;
        }
        let mut sum = Vector3::zeros();
        for n in &vectors {
            sum += n / n.norm();
        }
        let l = sum.norm();
        if l < 1e-12 {
            // Directions that cancel: no axis is better than another.
            return Some(NormalCone {
                axis: vectors[0] / vectors[0].norm(),
                half_angle: std::f64::consts::PI,
            });
        }
        let axis = sum / l;
        let widest = vectors
            .iter()
            .map(|n| (axis.dot(n) / n.norm()).clamp(-1.0, 1.0).acos())
            .fold(0.0, f64::max);
        // Past 90° the set of directions within the angle is not convex: two
        // control vectors at 100° on either side of the axis combine to one
        // at 180°. Such a cone bounds nothing.
        let half_angle = if widest < std::f64::consts::FRAC_PI_2 {
            widest
        } else {
            std::f64::consts::PI
        };
        Some(NormalCone { axis, half_angle })
    }

    /// Does the direction lie in the closed cone (to `slack` radians)?
    pub fn contains(&self, direction: Vector3<f64>, slack: f64) -> bool {
        let l = direction.norm();
        l == 0.0
            || (self.axis.dot(&direction) / l).clamp(-1.0, 1.0).acos() <= self.half_angle + slack
    }
}

/// The unit vector from `eye` to `p`; zero when they coincide.
fn unit_from(eye: Point3<f64>, p: Point3<f64>) -> Vector3<f64> {
    crate::raster::unit(p - eye)
}

/// The paper's back-facing test, equation (3.1), as it states it: `E_i`
/// the unit vectors from the eye to the patch's four corners, `N` the
/// cone's axis, the patch culled when `N · E_i < sin α` for all four.
///
/// Read with `N` the mean of `d_u × d_v` (pointing out of the surface
/// when the net is ordered counter-clockwise seen from outside), a point
/// faces the eye when `n · E < 0`, and the test culls patches that face
/// the eye: it is the mirror of the guarantee. Read with inward normals it
/// is the right shape but not conservative: it should be `< -sin α`, and
/// four corners do not bound the directions to the rest of the patch.
/// Kept to measure what it would cull; [`back_facing`] is the guarantee.
pub fn paper_back_facing(cone: &NormalCone, patch: &BezierPatch, eye: Point3<f64>) -> bool {
    corners(patch)
        .iter()
        .all(|&c| cone.axis.dot(&unit_from(eye, c)) < cone.half_angle.sin())
}

/// The paper's silhouette test, equation (3.2): some corner has
/// `|N · E_i| < sin α`.
pub fn paper_silhouette(cone: &NormalCone, patch: &BezierPatch, eye: Point3<f64>) -> bool {
    corners(patch)
        .iter()
        .any(|&c| cone.axis.dot(&unit_from(eye, c)).abs() < cone.half_angle.sin())
}

fn corners(patch: &BezierPatch) -> [Point3<f64>; 4] {
    [
        patch.net[0][0],
        patch.net[0][3],
        patch.net[3][0],
        patch.net[3][3],
    ]
}

/// Every point of the patch faces away from the eye (`n · (p - e) > 0`
/// with `n = d_u × d_v`), guaranteed: the cone is narrower than 90° and
/// for every control point `c` (the patch lies in their convex hull),
/// `N · (c - e) / |c - e| > sin α`. Then every `p - e`, a non-negative
/// combination of the `c - e`, lies within `90° - α` of `N`, and every
/// normal within `α`, so their angle is below 90°.
///
/// Edge cases: a cone of half-angle 90° or more never culls; an eye on the
/// hull of the net never culls (some `c - e` is 0 or points anywhere); a
/// patch without normals has no cone and is never culled.
pub fn back_facing(cone: &NormalCone, patch: &BezierPatch, eye: Point3<f64>) -> bool {
    let (sin, limit) = (cone.half_angle.sin(), std::f64::consts::FRAC_PI_2);
    cone.half_angle < limit
        && patch
            .net
            .iter()
            .flatten()
            .all(|&c| c != eye && cone.axis.dot(&unit_from(eye, c)) > sin)
}

/// The mirror of [`back_facing`]: every point faces the eye.
pub fn front_facing(cone: &NormalCone, patch: &BezierPatch, eye: Point3<f64>) -> bool {
    let flipped = NormalCone {
        axis: -cone.axis,
        half_angle: cone.half_angle,
    };
    back_facing(&flipped, patch, eye)
}

/// May the patch hold a silhouette (a point whose normal is perpendicular
/// to its view direction)? Conservatively: unless it is wholly back- or
/// front-facing by the guarantees above.
pub fn may_hold_silhouette(cone: &NormalCone, patch: &BezierPatch, eye: Point3<f64>) -> bool {
    !back_facing(cone, patch, eye) && !front_facing(cone, patch, eye)
}

#[cfg(test)]
mod tests {
    use super::super::tests::wavy_patch;
    use super::*;

    /// The normal patch is `d_u × d_v`, and the cone holds densely sampled
    /// normals.
    #[test]
    fn normal_patch_is_the_cross_product_and_the_cone_holds_it() {
        let p = wavy_patch();
        let normals = NormalPatch::of(&p);
        let cone = NormalCone::of(&p).unwrap();
        for i in 0..=20 {
            for j in 0..=20 {
                let (u, v) = (i as f64 / 20.0, j as f64 / 20.0);
                let s = p.evaluate_with_derivatives(u, v);
                let n = s.du.cross(&s.dv);
                let (m, _, _) = normals.evaluate(u, v);
                assert!((n - m).norm() < 1e-9 * (1.0 + n.norm()), "({u}, {v})");
                assert!(cone.contains(n, 1e-12), "({u}, {v})");
            }
        }
    }

    /// A flat patch: a cone of angle 0 along its normal; culled from
    /// behind, kept from in front, neither when the eye is in its plane.
    #[test]
    fn a_flat_patch_faces_one_way() {
        let mut net = [[Point3::origin(); 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                net[i][j] = Point3::new(i as f64, j as f64, 0.0);
            }
        }
        let p = BezierPatch { net };
        let cone = NormalCone::of(&p).unwrap();
        assert!(cone.half_angle < 1e-9 && (cone.axis[2] - 1.0).abs() < 1e-12);
        // d_u × d_v = +z: a point faces away from an eye below it.
        let (below, above) = (Point3::new(1.5, 1.5, -5.0), Point3::new(1.5, 1.5, 5.0));
        assert!(back_facing(&cone, &p, below));
        assert!(!back_facing(&cone, &p, above) && front_facing(&cone, &p, above));
        assert!(may_hold_silhouette(&cone, &p, Point3::new(10.0, 1.5, 0.0)));
        // The paper's test as stated culls the patch seen from the front.
        assert!(paper_back_facing(&cone, &p, above));
    }
}
