//! The bit-exact model of the hardware: Devillers–Guigue on W-bit signed
//! integer coordinates with exact integer predicates.
//!
//! Every predicate is computed exactly (in i128, enough for W <= 32, whose
//! orient3d needs 3W + 2 = 98 bits, see [`crate::widths`]), so the verdict is
//! the exact answer for the quantized triangles, which is what the hardware
//! must reproduce bit for bit.

use crate::devillers_guigue;
use crate::kernel::ExactKernel;
use crate::sign::Sign;
use std::cmp::Ordering;

/// A point with integer coordinates (each fits in W bits).
pub type FixedPoint3 = [i64; 3];
/// A triangle with integer coordinates.
pub type FixedTriangle = [FixedPoint3; 3];

/// Exact integer predicates.
pub struct FixedPoint;

#[inline]
fn sub(a: FixedPoint3, b: FixedPoint3) -> [i64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `u × v` exactly; components need 2W + 1 bits, i128 holds them for W <= 32.
#[inline]
pub fn cross(u: [i64; 3], v: [i64; 3]) -> [i128; 3] {
    let m = |a: i64, b: i64| a as i128 * b as i128;
    [m(u[1], v[2]) - m(u[2], v[1]), m(u[2], v[0]) - m(u[0], v[2]), m(u[0], v[1]) - m(u[1], v[0])]
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

/// Do the closed integer triangles intersect? Exact.
pub fn intersects(t1: &FixedTriangle, t2: &FixedTriangle) -> bool {
    devillers_guigue::intersects::<FixedPoint>(*t1, *t2)
}
