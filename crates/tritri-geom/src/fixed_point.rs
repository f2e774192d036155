//! The bit-exact model of the hardware: Devillers–Guigue on W-bit signed
//! integer coordinates with exact integer predicates.
//!
//! Every predicate is computed exactly (in i128, enough for W <= 32, whose
//! orient3d needs 3W + 2 = 98 bits, see [`crate::widths`]), so the verdict is
//! the exact answer for the quantized triangles, which is what the hardware
//! must reproduce bit for bit.
//!
//! Two kernels compute the same exact signs, at different speeds:
//!
//! * [`FixedPoint`]: any coordinates of up to 32 bits, everything in i128
//!   (the normal's components need 65 bits at W = 32).
//! * [`FixedPointNarrow`]: coordinates of up to 31 bits
//!   (`[-2^30, 2^30 - 1]`). Differences then have at most 32 bits, each
//!   product of two at most 62, a normal component (2W + 1 <= 63 bits) fits
//!   in i64 with no check, and the dot product is three 64×64→128 products.
//!
//! [`intersects`] checks the range of the pair's coordinates and picks the
//! narrow kernel when it applies; the verdict is the same either way.

use crate::devillers_guigue;
use crate::kernel::ExactKernel;
use crate::sign::Sign;
use std::cmp::Ordering;

/// A point with integer coordinates (each fits in W bits).
pub type FixedPoint3 = [i64; 3];
/// A triangle with integer coordinates.
pub type FixedTriangle = [FixedPoint3; 3];

/// Exact integer predicates for coordinates of up to 32 bits.
pub struct FixedPoint;

/// Exact integer predicates for coordinates in `[NARROW_MIN, NARROW_MAX]`
/// (31-bit), without overflow checks.
pub struct FixedPointNarrow;

/// Range of coordinates [`FixedPointNarrow`] accepts: W = 31.
pub const NARROW_MIN: i64 = -(1 << 30);
pub const NARROW_MAX: i64 = (1 << 30) - 1;

#[inline(always)]
pub(crate) fn sub(a: FixedPoint3, b: FixedPoint3) -> [i64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `u × v` exactly; components need 2W + 1 bits, i128 holds them for W <= 32.
#[inline]
pub fn cross(u: [i64; 3], v: [i64; 3]) -> [i128; 3] {
    let m = |a: i64, b: i64| a as i128 * b as i128;
    [
        m(u[1], v[2]) - m(u[2], v[1]),
        m(u[2], v[0]) - m(u[0], v[2]),
        m(u[0], v[1]) - m(u[1], v[0]),
    ]
}

/// `[a,b,c,d] = (d-a)·((b-a)×(c-a))`, exactly.
#[inline]
pub fn orient3d_value(a: FixedPoint3, b: FixedPoint3, c: FixedPoint3, d: FixedPoint3) -> i128 {
    let n = cross(sub(b, a), sub(c, a));
    let w = sub(d, a);
    w[0] as i128 * n[0] + w[1] as i128 * n[1] + w[2] as i128 * n[2]
}

/// Component `axis` of `(b-a)×(c-a)`, exactly.
#[inline]
pub fn orient2d_value(axis: usize, a: FixedPoint3, b: FixedPoint3, c: FixedPoint3) -> i128 {
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let (u, v) = (sub(b, a), sub(c, a));
    u[i] as i128 * v[j] as i128 - u[j] as i128 * v[i] as i128
}

impl ExactKernel for FixedPoint {
    type Point = FixedPoint3;

    #[inline]
    fn orient3d(a: FixedPoint3, b: FixedPoint3, c: FixedPoint3, d: FixedPoint3) -> Sign {
        Sign::of_i128(orient3d_value(a, b, c, d))
    }

    #[inline]
    fn orient2d(axis: usize, a: FixedPoint3, b: FixedPoint3, c: FixedPoint3) -> Sign {
        Sign::of_i128(orient2d_value(axis, a, b, c))
    }

    #[inline]
    fn compare_coordinate(axis: usize, a: FixedPoint3, b: FixedPoint3) -> Ordering {
        a[axis].cmp(&b[axis])
    }

    /// The largest |component| of the exact normal; ties go to the lowest
    /// axis (the hardware uses the same rule).
    fn dominant_normal_axis(a: FixedPoint3, b: FixedPoint3, c: FixedPoint3) -> usize {
        let n = cross(sub(b, a), sub(c, a)).map(i128::unsigned_abs);
        dominant_axis(n)
    }
}

/// `u × v` for differences of narrow coordinates: `|u|, |v| <= 2^31 - 1`, so
/// each product is below 2^62 and each component below 2^63.
#[inline(always)]
fn cross_narrow(u: [i64; 3], v: [i64; 3]) -> [i64; 3] {
    debug_assert!(u.iter().chain(&v).all(|d| d.unsigned_abs() < 1 << 31));
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

impl ExactKernel for FixedPointNarrow {
    type Point = FixedPoint3;

    #[inline(always)]
    fn orient3d(a: FixedPoint3, b: FixedPoint3, c: FixedPoint3, d: FixedPoint3) -> Sign {
        let n = cross_narrow(sub(b, a), sub(c, a));
        let w = sub(d, a);
        // Each term is below 2^32 * 2^63: the sum of three fits in i128.
        Sign::of_i128(
            w[0] as i128 * n[0] as i128 + w[1] as i128 * n[1] as i128 + w[2] as i128 * n[2] as i128,
        )
    }

    #[inline(always)]
    fn orient2d(axis: usize, a: FixedPoint3, b: FixedPoint3, c: FixedPoint3) -> Sign {
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        let (u, v) = (sub(b, a), sub(c, a));
        Sign::of_i128((u[i] * v[j] - u[j] * v[i]) as i128)
    }

    #[inline]
    fn compare_coordinate(axis: usize, a: FixedPoint3, b: FixedPoint3) -> Ordering {
        a[axis].cmp(&b[axis])
    }

    /// The same rule as [`FixedPoint`]'s.
    fn dominant_normal_axis(a: FixedPoint3, b: FixedPoint3, c: FixedPoint3) -> usize {
        dominant_axis(cross_narrow(sub(b, a), sub(c, a)).map(|v| v.unsigned_abs() as u128))
    }
}

/// Are all coordinates of both triangles in the narrow (31-bit) range?
#[inline(always)]
pub fn fits_narrow(t1: &FixedTriangle, t2: &FixedTriangle) -> bool {
    // `v ^ (v >> 63)` is v for v >= 0 and -v - 1 for v < 0: it is below 2^30
    // exactly for v in [-2^30, 2^30 - 1]. OR-ing them has no dependency chain.
    let mut bits = 0i64;
    for t in [t1, t2] {
        for p in t {
            for &v in p {
                bits |= v ^ (v >> 63);
            }
        }
    }
    bits < 1 << 30
}

/// Index of the largest of three magnitudes, ties to the lowest index.
#[inline]
pub fn dominant_axis(n: [u128; 3]) -> usize {
    if n[0] >= n[1] && n[0] >= n[2] {
        0
    } else if n[1] >= n[2] {
        1
    } else {
        2
    }
}

/// Do the closed integer triangles intersect? Exact for coordinates of up to
/// 32 bits; uses the narrow kernel when every coordinate has at most 31.
#[inline]
pub fn intersects(t1: &FixedTriangle, t2: &FixedTriangle) -> bool {
    if fits_narrow(t1, t2) {
        devillers_guigue::intersects::<FixedPointNarrow>(*t1, *t2)
    } else {
        devillers_guigue::intersects::<FixedPoint>(*t1, *t2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::devillers_guigue;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The extreme narrow configuration: differences of 2^31 - 1 in every
    /// coordinate, the largest normal and orient3d magnitudes, agree between
    /// the kernels and with an independent i128 evaluation.
    #[test]
    fn narrow_extremes_do_not_overflow() {
        let (lo, hi) = (NARROW_MIN, NARROW_MAX);
        let a = [lo, lo, lo];
        let b = [hi, lo, lo];
        let c = [lo, hi, lo];
        for d in [[lo, lo, hi], [hi, hi, hi], [lo, lo, lo], [hi, hi, lo]] {
            let exact = orient3d_value(a, b, c, d);
            assert_eq!(FixedPointNarrow::orient3d(a, b, c, d), Sign::of_i128(exact));
            assert_eq!(FixedPoint::orient3d(a, b, c, d), Sign::of_i128(exact));
        }
        let m = (hi - lo) as i128;
        assert_eq!(orient3d_value(a, b, c, [lo, lo, hi]), m * m * m);
        assert_eq!(orient2d_value(2, a, b, c), m * m);
    }

    /// At W = 32 the normal needs 65 bits (more than i64): the i128
    /// values are exact and such pairs do not take the narrow kernel.
    #[test]
    fn width_32_extremes_are_exact() {
        let (lo, hi) = (-(1i64 << 31), (1i64 << 31) - 1);
        let (a, b, c, d) = ([lo, lo, lo], [hi, lo, lo], [lo, hi, lo], [lo, lo, hi]);
        let m = (hi - lo) as i128;
        assert_eq!(orient3d_value(a, b, c, d), m * m * m);
        assert_eq!(orient2d_value(2, a, b, c), m * m);
        assert_eq!(cross([hi - lo, 0, 0], [0, hi - lo, 0]), [0, 0, m * m]);
        assert!(!fits_narrow(&[a, b, c], &[a, b, c]));
        let (nlo, nhi) = ([NARROW_MIN; 3], [NARROW_MAX; 3]);
        assert!(fits_narrow(&[nlo, nhi, nlo], &[nhi, nhi, nlo]));
        assert!(!fits_narrow(
            &[nlo, nhi, nlo],
            &[nhi, [0, NARROW_MIN - 1, 0], nlo]
        ));
        assert!(!fits_narrow(
            &[nlo, nhi, nlo],
            &[nhi, [0, 0, NARROW_MAX + 1], nlo]
        ));
    }

    /// Both kernels give the same verdict on random small-lattice pairs
    /// (many coplanar and degenerate ones) at several scales.
    #[test]
    fn kernels_agree() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for shift in [0, 20, 27] {
            for _ in 0..3000 {
                let mut t = || -> FixedTriangle {
                    [0; 3].map(|_| [0; 3].map(|_| rng.gen_range(-3i64..=3) << shift))
                };
                let (t1, t2) = (t(), t());
                assert_eq!(
                    devillers_guigue::intersects::<FixedPointNarrow>(t1, t2),
                    devillers_guigue::intersects::<FixedPoint>(t1, t2),
                    "{t1:?} {t2:?}"
                );
            }
        }
    }
}
