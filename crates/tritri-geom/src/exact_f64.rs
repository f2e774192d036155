//! The ground truth: Devillers–Guigue on exact predicates over the f64
//! coordinates as given, for every finite input: Shewchuk's adaptive
//! orient2d / orient3d from the `robust` crate, which are exact while their
//! intermediate products neither overflow nor underflow (coordinates inside
//! [`ROBUST_RANGE`](crate::exact_big_integer::ROBUST_RANGE)), and exact big
//! integers ([`crate::exact_big_integer`]) for points outside it (near
//! ±1e308 or 1e-300).
//!
//! Each predicate first tries a static floating-point filter with Shewchuk's
//! first-stage error bound, written so that the calls against one plane
//! share its normal once inlined; only when the rounded value is too close
//! to zero does it call `robust` (on the Shen sets almost never, on
//! coplanar and degenerate pairs always). The filter is sound at every
//! magnitude: an overflow makes its bound infinite or NaN and a tiny bound
//! is refused (`FILTER_MIN_PERMANENT`), so it defers in both cases; the
//! range test sits in the deferred path only, which keeps the fast path as
//! it was.

use crate::devillers_guigue;
use crate::exact_big_integer::{self, within_robust_range};
use crate::kernel::ExactKernel;
use crate::sign::Sign;
use crate::triangle::{Point, Triangle};
use robust::{Coord, Coord3D};
use std::cmp::Ordering;

/// Exact predicates on f64 points.
pub struct ExactF64;

#[inline]
fn c3(p: Point) -> Coord3D<f64> {
    Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

#[inline(always)]
fn sub(a: Point, b: Point) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Filter bound for `t·(u×v)` with `u, v, t` rounded differences from one
/// point: the rounded value has the exact sign when it exceeds this times
/// the permanent `Σ |t_i| (|u_j v_k| + |u_k v_j|)`. Shewchuk's
/// `o3derrboundA = (7 + 56ε)ε` (ε = 2^-53) covers this form (a coordinate of
/// one difference vector times a 2×2 minor of the other two, summed), so
/// 8ε = 2^-50 is a safe upper bound. The same reasoning with
/// `ccwerrboundA = (3 + 16ε)ε` gives 4ε for orient2d.
const ORIENT3D_FILTER: f64 = 8.0 * f64::EPSILON / 2.0;
const ORIENT2D_FILTER: f64 = 4.0 * f64::EPSILON / 2.0;
/// The bounds assume no underflow (as `robust`'s own do). Below this
/// permanent (about 2^-897) the filter defers to `robust` anyway, which
/// covers the common all-tiny case; overflow makes the permanent infinite or
/// NaN, which fails the test and defers as well.
const FILTER_MIN_PERMANENT: f64 = 1e-270;

/// `[a,b,c,d]` by `robust::orient3d` (adaptive, exact): it computes
/// det[a-d, b-d, c-d], which is -[a,b,c,d].
#[cold]
#[inline(never)]
fn orient3d_exact(a: Point, b: Point, c: Point, d: Point) -> Sign {
    if !within_robust_range(&[a, b, c, d]) {
        return exact_big_integer::orient3d(a, b, c, d);
    }
    Sign::of_f64(robust::orient3d(c3(a), c3(b), c3(c), c3(d))).flip()
}

#[cold]
#[inline(never)]
fn orient2d_exact(axis: usize, a: Point, b: Point, c: Point) -> Sign {
    if !within_robust_range(&[a, b, c]) {
        return exact_big_integer::orient2d(axis, a, b, c);
    }
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let p = |v: Point| Coord { x: v[i], y: v[j] };
    Sign::of_f64(robust::orient2d(p(a), p(b), p(c)))
}

impl ExactKernel for ExactF64 {
    type Point = Point;

    #[inline(always)]
    fn orient3d(a: Point, b: Point, c: Point, d: Point) -> Sign {
        // Static filter first (see `ORIENT3D_FILTER`); it is written as
        // (d-a)·((b-a)×(c-a)) so that, inlined, the three calls against one
        // plane share the normal and its partial permanents.
        let (u, v, w) = (sub(b, a), sub(c, a), sub(d, a));
        let products = [
            u[1] * v[2],
            u[2] * v[1],
            u[2] * v[0],
            u[0] * v[2],
            u[0] * v[1],
            u[1] * v[0],
        ];
        let normal = [
            products[0] - products[1],
            products[2] - products[3],
            products[4] - products[5],
        ];
        let det = w[0] * normal[0] + w[1] * normal[1] + w[2] * normal[2];
        let permanent = w[0].abs() * (products[0].abs() + products[1].abs())
            + w[1].abs() * (products[2].abs() + products[3].abs())
            + w[2].abs() * (products[4].abs() + products[5].abs());
        if permanent >= FILTER_MIN_PERMANENT && det.abs() > ORIENT3D_FILTER * permanent {
            return Sign::of_f64(det);
        }
        orient3d_exact(a, b, c, d)
    }

    #[inline(always)]
    fn orient2d(axis: usize, a: Point, b: Point, c: Point) -> Sign {
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        let (u, v) = (sub(b, a), sub(c, a));
        let (p, q) = (u[i] * v[j], u[j] * v[i]);
        let det = p - q;
        let permanent = p.abs() + q.abs();
        if permanent >= FILTER_MIN_PERMANENT && det.abs() > ORIENT2D_FILTER * permanent {
            return Sign::of_f64(det);
        }
        orient2d_exact(axis, a, b, c)
    }

    #[inline]
    fn compare_coordinate(axis: usize, a: Point, b: Point) -> Ordering {
        // `+ 0.0` turns -0.0 into +0.0: the two are one coordinate, but
        // `total_cmp` alone orders -0.0 below +0.0 (input is never NaN).
        (a[axis] + 0.0).total_cmp(&(b[axis] + 0.0))
    }

    fn dominant_normal_axis(a: Point, b: Point, c: Point) -> usize {
        // The float normal picks the largest component; the exact sign makes
        // sure the chosen component is really non-zero. (Near ±1e308 the
        // float normal may overflow and the pick be another non-zero
        // component: the projection dropping it is still one-to-one on the
        // plane, which is all the coplanar test needs.)
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        (0..3)
            .filter(|&k| !Self::orient2d(k, a, b, c).is_zero())
            .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()).then(j.cmp(&i)))
            .expect("dominant_normal_axis is called on non-degenerate triangles only")
    }
}

/// Do the closed triangles intersect? Exact on the f64 coordinates.
///
/// Not inlined: the whole algorithm with the filtered predicates is large,
/// and inlined into a caller's loop it measured about 40 % slower.
#[inline(never)]
pub fn intersects(t1: &Triangle, t2: &Triangle) -> bool {
    devillers_guigue::intersects::<ExactF64>(*t1, *t2)
}

#[cfg(test)]
mod filter_tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn nudge(x: f64, ulps: i64) -> f64 {
        if x == 0.0 {
            return ulps as f64 * f64::MIN_POSITIVE;
        }
        f64::from_bits((x.to_bits() as i64 + ulps) as u64)
    }

    /// The predicates give the exact signs (big integers) on points that are
    /// nearly coplanar / collinear (a few ulps off) or exactly so, at scales
    /// from 1e-310 (subnormal) to 1e300, with large offsets; and inside
    /// `ROBUST_RANGE`, robust's signs are those exact signs too.
    #[test]
    fn filter_agrees_with_exact_signs_near_degeneracy() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut degenerate = 0;
        let mut robust_checked = 0;
        for scale in [
            1e-310, 1e-300, 1e-200, 1e-150, 1e-5, 1.0, 1e6, 1e150, 1e200, 1e300,
        ] {
            for _ in 0..14_000 {
                let offset = if rng.gen_bool(0.3) { 1e3 * scale } else { 0.0 };
                let mut p =
                    || -> Point { [0; 3].map(|_| offset + scale * rng.gen_range(-1.0..1.0)) };
                let (mut a, mut b, mut c) = (p(), p(), p());
                let (s, t): (f64, f64) = (rng.gen_range(-1.0..2.0), rng.gen_range(-1.0..2.0));
                let mut d = [0, 1, 2].map(|k| a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]));
                let k = rng.gen_range(0..3);
                d[k] = nudge(d[k], rng.gen_range(-3..=3));
                if rng.gen_bool(0.1) {
                    // Exactly coplanar: small integers on a power-of-two grid near `scale`.
                    let unit = 2f64.powi(scale.log2().round() as i32);
                    let mut g = || -> [i64; 3] { [0; 3].map(|_| rng.gen_range(-8..=8)) };
                    let (ga, gb, gc) = (g(), g(), g());
                    let (gs, gt) = (rng.gen_range(-2..=2), rng.gen_range(-2..=2));
                    let on_grid = |v: [i64; 3]| v.map(|x| x as f64 * unit);
                    (a, b, c) = (on_grid(ga), on_grid(gb), on_grid(gc));
                    d = on_grid(
                        [0, 1, 2].map(|k| ga[k] + gs * (gb[k] - ga[k]) + gt * (gc[k] - ga[k])),
                    );
                }
                let want = exact_big_integer::orient3d(a, b, c, d);
                assert_eq!(
                    ExactF64::orient3d(a, b, c, d),
                    want,
                    "{a:?} {b:?} {c:?} {d:?}"
                );
                degenerate += usize::from(want.is_zero());
                if within_robust_range(&[a, b, c, d]) {
                    assert_eq!(
                        Sign::of_f64(robust::orient3d(c3(a), c3(b), c3(c), c3(d))).flip(),
                        want
                    );
                    robust_checked += 1;
                }
                // Nearly collinear in the projection dropping `axis`.
                let mut e = [0, 1, 2].map(|k| a[k] + s * (b[k] - a[k]));
                e[k] = nudge(e[k], rng.gen_range(-3..=3));
                for axis in 0..3 {
                    let want = exact_big_integer::orient2d(axis, a, b, e);
                    assert_eq!(
                        ExactF64::orient2d(axis, a, b, e),
                        want,
                        "{a:?} {b:?} {e:?} axis {axis}"
                    );
                    degenerate += usize::from(want.is_zero());
                    if within_robust_range(&[a, b, e]) {
                        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
                        let q = |v: Point| Coord { x: v[i], y: v[j] };
                        assert_eq!(Sign::of_f64(robust::orient2d(q(a), q(b), q(e))), want);
                    }
                }
            }
        }
        assert!(
            degenerate > 0,
            "the test must reach exactly degenerate configurations"
        );
        assert!(
            robust_checked > 10_000,
            "and compare robust with the exact signs inside its range"
        );
    }
}

#[cfg(test)]
mod range_tests {
    use super::intersects;

    /// -0.0 and +0.0 are the same coordinate: two point-triangles at the
    /// origin, one written with negative zeros, touch.
    #[test]
    fn signed_zeros_are_one_coordinate() {
        let plus = [[0.0; 3]; 3];
        let minus = [[-0.0; 3]; 3];
        assert!(intersects(&plus, &minus));
        let t = [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0]];
        assert!(intersects(&t, &[[0.0, -0.0, -0.0]; 3]));
    }

    /// Pairs at the ends of the f64 range, where f64 products overflow or
    /// underflow, get exact answers (and no panic).
    #[test]
    fn extreme_magnitudes_are_exact() {
        let max = f64::MAX;
        let left = [[-max, 0.0, 0.0], [-0.9 * max, 0.0, 0.0], [-max, 1e307, 0.0]];
        let right = left.map(|p| [-p[0], p[1], p[2]]);
        assert!(!intersects(&left, &right), "far apart, both in z = 0");
        let big = [[-max, -max, 0.0], [max, -max, 0.0], [0.0, max, 0.0]];
        let needle = [[0.0, 0.0, -5e-324], [0.0, 0.0, 5e-324], [0.0, 0.0, 5e-324]];
        assert!(intersects(&big, &needle), "a segment through the plane");
        let above = [
            [0.0, 0.0, 5e-324],
            [1e-300, 0.0, 5e-324],
            [0.0, 1e-300, 1e-323],
        ];
        assert!(
            !intersects(&big, &above),
            "a tiny triangle just above the plane"
        );
    }
}
