//! orient3d and orient2d of f64 points in exact big-integer arithmetic: the
//! fallback of [`crate::exact_f64`]'s predicates where Shewchuk's adaptive
//! predicates are not exact, because their products overflow (coordinates
//! near ±1e308) or underflow (coordinates near 1e-300).
//!
//! Every finite f64 is `m · 2^e` with an integer `m` and `-1074 <= e <= 971`,
//! so the coordinates of one predicate, written on the grid of the smallest
//! `e` among them, are integers of at most about 2,100 bits, and the
//! determinants are exact integer polynomials of them. Slow (products of
//! thousands of bits), which is why it only runs outside [`ROBUST_RANGE`].

use crate::sign::Sign;
use crate::triangle::Point;
use num_bigint::BigInt;

/// Magnitudes inside which `robust`'s expansions are exact: with every
/// non-zero coordinate in `[2^-240, 2^240]`, every exact term of a degree-3
/// predicate is a multiple of `2^(-3·292)` (a coordinate's last bit is at
/// least `2^-292`) and below `2^730`, far from both ends of the f64 range.
pub const ROBUST_RANGE: (f64, f64) = (power_of_two(-240), power_of_two(240));

/// `2^k` for a normal exponent `k`, as a constant.
const fn power_of_two(k: i32) -> f64 {
    f64::from_bits(((1023 + k) as u64) << 52)
}

/// True when every coordinate of `points` is zero or inside [`ROBUST_RANGE`]
/// in magnitude.
#[inline]
pub fn within_robust_range(points: &[Point]) -> bool {
    points
        .iter()
        .all(|p| p.iter().all(|&x| coordinate_within_robust_range(x)))
}

/// Zero, or a magnitude in `[2^-240, 2^240]`: a biased exponent in
/// `[1023 - 240, 1023 + 239]`, or exactly `2^240` (integer tests on the
/// bits, no branches).
#[inline(always)]
fn coordinate_within_robust_range(x: f64) -> bool {
    const LOWEST: u64 = 1023 - 240;
    const HIGHEST: u64 = 1023 + 240;
    let magnitude = x.to_bits() & !(1u64 << 63);
    let exponent = magnitude >> 52;
    (magnitude == 0)
        | (exponent.wrapping_sub(LOWEST) < HIGHEST - LOWEST)
        | (magnitude == (HIGHEST << 52))
}

/// `x = m · 2^e` exactly (subnormals included; zero is `(0, 0)`).
fn mantissa_exponent(x: f64) -> (i64, i32) {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let fraction = (bits & ((1u64 << 52) - 1)) as i64;
    let (m, e) = if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1i64 << 52), biased - 1075)
    };
    if m == 0 {
        (0, 0)
    } else if bits >> 63 == 1 {
        (-m, e)
    } else {
        (m, e)
    }
}

/// The coordinates as integers on one common grid `2^e_min` (a positive
/// common factor, which no sign depends on).
fn on_common_grid<const N: usize>(xs: [f64; N]) -> [BigInt; N] {
    let parts = xs.map(mantissa_exponent);
    let e_min = parts
        .iter()
        .filter(|(m, _)| *m != 0)
        .map(|&(_, e)| e)
        .min()
        .unwrap_or(0);
    parts.map(|(m, e)| BigInt::from(m) << (e - e_min) as usize)
}

fn sign_of(v: &BigInt) -> Sign {
    match v.sign() {
        num_bigint::Sign::Minus => Sign::Negative,
        num_bigint::Sign::NoSign => Sign::Zero,
        num_bigint::Sign::Plus => Sign::Positive,
    }
}

/// Sign of `[a,b,c,d] = (d-a)·((b-a)×(c-a))`.
#[inline(never)]
pub fn orient3d(a: Point, b: Point, c: Point, d: Point) -> Sign {
    let g = on_common_grid([
        a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2], d[0], d[1], d[2],
    ]);
    let difference = |p: usize| [0, 1, 2].map(|k| &g[3 * p + k] - &g[k]);
    let (u, v, w) = (difference(1), difference(2), difference(3));
    let normal = [
        &u[1] * &v[2] - &u[2] * &v[1],
        &u[2] * &v[0] - &u[0] * &v[2],
        &u[0] * &v[1] - &u[1] * &v[0],
    ];
    sign_of(&(&w[0] * &normal[0] + &w[1] * &normal[1] + &w[2] * &normal[2]))
}

/// Sign of the 2D orientation of `a, b, c` projected along `axis` (onto the
/// coordinates `(axis + 1) % 3` and `(axis + 2) % 3`): positive when
/// counter-clockwise.
#[inline(never)]
pub fn orient2d(axis: usize, a: Point, b: Point, c: Point) -> Sign {
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let g = on_common_grid([a[i], a[j], b[i], b[j], c[i], c[j]]);
    let (ux, uy, vx, vy) = (&g[2] - &g[0], &g[3] - &g[1], &g[4] - &g[0], &g[5] - &g[1]);
    sign_of(&(ux * vy - uy * vx))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The split is exact: `m · 2^e` gives `x` back, subnormals and the
    /// ends of the range included.
    #[test]
    fn mantissa_exponent_is_exact() {
        for x in [
            0.0,
            -0.0,
            1.0,
            -1.5,
            0.1,
            5e-324,
            -5e-324,
            1e-310,
            f64::MIN_POSITIVE,
            f64::MAX,
            -f64::MAX,
            1e300,
        ] {
            let (m, e) = mantissa_exponent(x);
            // Two half steps: 2^-1074 itself would underflow in powi.
            assert_eq!(
                m as f64 * 2f64.powi(e / 2) * 2f64.powi(e - e / 2),
                x,
                "{x:e}"
            );
        }
    }

    /// The range test on exponent bits is the test on magnitudes.
    #[test]
    fn robust_range_is_two_to_the_plus_minus_240() {
        let (lo, hi) = ROBUST_RANGE;
        assert_eq!((lo, hi), (2f64.powi(-240), 2f64.powi(240)));
        for x in [0.0, -0.0, lo, hi, -lo, -hi, 1.0, 0.1, 1e72, -1e-72] {
            assert!(coordinate_within_robust_range(x), "{x:e}");
        }
        for x in [
            lo.next_down(),
            hi.next_up(),
            -hi.next_up(),
            5e-324,
            f64::MAX,
            1e-300,
            -1e300,
        ] {
            assert!(!coordinate_within_robust_range(x), "{x:e}");
        }
        let t = [[1.0, 2.0, 3.0]; 3];
        assert!(within_robust_range(&t));
        let mut far = t;
        far[2][1] = 1e300;
        assert!(!within_robust_range(&far));
    }

    /// Signs at the ends of the range, where f64 products overflow or underflow.
    #[test]
    fn signs_at_extreme_magnitudes() {
        let max = f64::MAX;
        let (o, x, y) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        for s in [max, 1e300, 1e-300, 5e-324] {
            let sc = |p: Point| p.map(|v| v * s);
            assert_eq!(
                orient3d(sc(o), sc(x), sc(y), [0.0, 0.0, s]),
                Sign::Positive,
                "scale {s:e}"
            );
            assert_eq!(
                orient3d(sc(o), sc(x), sc(y), [0.0, 0.0, -s]),
                Sign::Negative,
                "scale {s:e}"
            );
            assert_eq!(
                orient3d(sc(o), sc(x), sc(y), sc([0.5, 0.25, 0.0])),
                Sign::Zero,
                "scale {s:e}"
            );
            assert_eq!(
                orient2d(2, sc(o), sc(x), sc(y)),
                Sign::Positive,
                "scale {s:e}"
            );
            assert_eq!(
                orient2d(2, sc(o), sc(y), sc(x)),
                Sign::Negative,
                "scale {s:e}"
            );
        }
        // Coordinates of mixed magnitude: a point 5e-324 above a plane through points at ±f64::MAX.
        let tiny = 5e-324;
        assert_eq!(
            orient3d(
                [-max, -max, 0.0],
                [max, -max, 0.0],
                [0.0, max, 0.0],
                [0.0, 0.0, tiny]
            ),
            Sign::Positive
        );
        assert_eq!(
            orient3d(
                [-max, -max, 0.0],
                [max, -max, 0.0],
                [0.0, max, 0.0],
                [1e300, -1e300, 0.0]
            ),
            Sign::Zero
        );
    }
}
