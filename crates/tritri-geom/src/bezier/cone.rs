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

use crate::vector::{cross, dot, length};
use super::BezierPatch;
use crate::triangle::Point;

/// `N = d_u × d_v` as a degree (5, 5) Bezier patch: `net[a][b]`, `a` along
/// `u`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalPatch {
    pub net: [[Point; 6]; 6],
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// A Bezier curve of any degree at `t` by De Casteljau: the point and the
/// derivative.
fn curve(points: &[Point], t: f64) -> (Point, Point) {
    let degree = points.len() - 1;
    let mut level: Vec<Point> = points.to_vec();
    let mut derivative = [0.0; 3];
    while level.len() > 1 {
        if level.len() == 2 {
            derivative = [0, 1, 2].map(|k| degree as f64 * (level[1][k] - level[0][k]));
        }
        level = level.windows(2).map(|w| [0, 1, 2].map(|k| w[0][k] + (w[1][k] - w[0][k]) * t)).collect();
    }
    (level[0], derivative)
}

impl NormalPatch {
    pub fn of(patch: &BezierPatch) -> NormalPatch {
        let p = &patch.net;
        let d = |a: Point, b: Point| [0, 1, 2].map(|k| 3.0 * (b[k] - a[k]));
        let mut net = [[[0.0; 3]; 6]; 6];
        for i in 0..3 {
            for j in 0..4 {
                let du = d(p[i][j], p[i + 1][j]);
                for k in 0..4 {
                    for l in 0..3 {
                        let dv = d(p[k][l], p[k][l + 1]);
                        let w = binomial(2, i) * binomial(3, k) / binomial(5, i + k) * binomial(3, j) * binomial(2, l) / binomial(5, j + l);
                        let c = cross(du, dv);
                        for m in 0..3 {
                            net[i + k][j + l][m] += w * c[m];
                        }
                    }
                }
            }
        }
        NormalPatch { net }
    }

    /// `N(u, v)` and its partial derivatives `N_u`, `N_v`.
    pub fn evaluate(&self, u: f64, v: f64) -> (Point, Point, Point) {
        let rows: Vec<(Point, Point)> = self.net.iter().map(|row| curve(row, v)).collect();
        let values: Vec<Point> = rows.iter().map(|r| r.0).collect();
        let slopes: Vec<Point> = rows.iter().map(|r| r.1).collect();
        let (n, nu) = curve(&values, u);
        let (nv, _) = curve(&slopes, u);
        (n, nu, nv)
    }

    /// Where `N(u, v) = 0`, the direction `N` takes as `(u, v)` moves
    /// towards the centre of the parameter square: the directional
    /// derivative `N_u (1/2 - u) + N_v (1/2 - v)`, normalized; `None` if it
    /// vanishes too.
    pub fn limit_direction(&self, u: f64, v: f64) -> Option<Point> {
        let (_, nu, nv) = self.evaluate(u, v);
        let d = [0, 1, 2].map(|k| nu[k] * (0.5 - u) + nv[k] * (0.5 - v));
        let l = length(d);
        (l > 0.0).then(|| d.map(|c| c / l))
    }
}

/// A cone holding every normal direction of a patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalCone {
    /// Unit axis: the mean direction of the normal patch's control vectors.
    pub axis: Point,
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
        let vectors: Vec<Point> = normals.net.iter().flatten().copied().filter(|n| length(*n) > 1e-14 * scale * scale).collect();
        if vectors.is_empty() {
            return None;
        }
        let mut sum = [0.0; 3];
        for n in &vectors {
            let l = length(*n);
            for k in 0..3 {
                sum[k] += n[k] / l;
            }
        }
        let l = length(sum);
        if l < 1e-12 {
            // Directions that cancel: no axis is better than another.
            return Some(NormalCone { axis: vectors[0].map(|c| c / length(vectors[0])), half_angle: std::f64::consts::PI });
        }
        let axis = sum.map(|c| c / l);
        let widest = vectors.iter().map(|n| (dot(axis, *n) / length(*n)).clamp(-1.0, 1.0).acos()).fold(0.0, f64::max);
        // Past 90° the set of directions within the angle is not convex: two
        // control vectors at 100° on either side of the axis combine to one
        // at 180°. Such a cone bounds nothing.
        let half_angle = if widest < std::f64::consts::FRAC_PI_2 { widest } else { std::f64::consts::PI };
        Some(NormalCone { axis, half_angle })
    }

    /// Does the direction lie in the closed cone (to `slack` radians)?
    pub fn contains(&self, direction: Point, slack: f64) -> bool {
        let l = length(direction);
        l == 0.0 || (dot(self.axis, direction) / l).clamp(-1.0, 1.0).acos() <= self.half_angle + slack
    }
}

fn unit_from(eye: Point, p: Point) -> Point {
    let d = [p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]];
    let l = length(d);
    if l == 0.0 {
        d
    } else {
        d.map(|c| c / l)
    }
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
pub fn paper_back_facing(cone: &NormalCone, patch: &BezierPatch, eye: Point) -> bool {
    corners(patch).iter().all(|&c| dot(cone.axis, unit_from(eye, c)) < cone.half_angle.sin())
}

/// The paper's silhouette test, equation (3.2): some corner has
/// `|N · E_i| < sin α`.
pub fn paper_silhouette(cone: &NormalCone, patch: &BezierPatch, eye: Point) -> bool {
    corners(patch).iter().any(|&c| dot(cone.axis, unit_from(eye, c)).abs() < cone.half_angle.sin())
}

fn corners(patch: &BezierPatch) -> [Point; 4] {
    [patch.net[0][0], patch.net[0][3], patch.net[3][0], patch.net[3][3]]
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
pub fn back_facing(cone: &NormalCone, patch: &BezierPatch, eye: Point) -> bool {
    let (sin, limit) = (cone.half_angle.sin(), std::f64::consts::FRAC_PI_2);
    cone.half_angle < limit && patch.net.iter().flatten().all(|&c| length(unit_from(eye, c)) > 0.0 && dot(cone.axis, unit_from(eye, c)) > sin)
}

/// The mirror of [`back_facing`]: every point faces the eye.
pub fn front_facing(cone: &NormalCone, patch: &BezierPatch, eye: Point) -> bool {
    let flipped = NormalCone { axis: cone.axis.map(|c| -c), half_angle: cone.half_angle };
    back_facing(&flipped, patch, eye)
}

/// May the patch hold a silhouette (a point whose normal is perpendicular
/// to its view direction)? Conservatively: unless it is wholly back- or
/// front-facing by the guarantees above.
pub fn may_hold_silhouette(cone: &NormalCone, patch: &BezierPatch, eye: Point) -> bool {
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
                let n = cross(s.du, s.dv);
                let (m, _, _) = normals.evaluate(u, v);
                assert!(length([n[0] - m[0], n[1] - m[1], n[2] - m[2]]) < 1e-9 * (1.0 + length(n)), "({u}, {v})");
                assert!(cone.contains(n, 1e-12), "({u}, {v})");
            }
        }
    }

    /// A flat patch: a cone of angle 0 along its normal; culled from
    /// behind, kept from in front, neither when the eye is in its plane.
    #[test]
    fn a_flat_patch_faces_one_way() {
        let mut net = [[[0.0; 3]; 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                net[i][j] = [i as f64, j as f64, 0.0];
            }
        }
        let p = BezierPatch { net };
        let cone = NormalCone::of(&p).unwrap();
        assert!(cone.half_angle < 1e-9 && (cone.axis[2] - 1.0).abs() < 1e-12);
        // d_u × d_v = +z: a point faces away from an eye below it.
        assert!(back_facing(&cone, &p, [1.5, 1.5, -5.0]));
        assert!(!back_facing(&cone, &p, [1.5, 1.5, 5.0]) && front_facing(&cone, &p, [1.5, 1.5, 5.0]));
        assert!(may_hold_silhouette(&cone, &p, [10.0, 1.5, 0.0]));
        // The paper's test as stated culls the patch seen from the front.
        assert!(paper_back_facing(&cone, &p, [1.5, 1.5, 5.0]));
    }
}
