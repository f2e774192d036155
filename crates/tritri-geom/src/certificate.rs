//! A certificate with every fixed-point verdict: is the verdict on the grid
//! provably the verdict on the user's original (f64) coordinates?
//!
//! Quantization ([`crate::quantize::Frame`]) moves every coordinate by at
//! most half a grid step, plus f64 rounding of below `2^-21` steps at
//! W <= 32. Translation and positive scaling keep every orientation sign,
//! so the originals, read in grid units, are the grid points moved by at
//! most `1/2 + 2^-21` per coordinate; a coordinate *difference* moves by at
//! most `e = 1 + 2^-20`.
//!
//! # The bound (docs/certificates.md)
//!
//! An orientation determinant `[a,b,c,d] = det(b - a, c - a, d - a)`.
//! Let every entry of the three rows be at most `M` in magnitude. Moving
//! every entry by at most `e` changes the determinant by at most
//! (multilinearity, six products of three entries)
//!
//! ```text
//! |Δ| <= 6 [(M + e)^3 - M^3] = 6 (3 M^2 e + 3 M e^2 + e^3).
//! ```
//!
//! With `M = 2^m`, `m >= 1` (so `M >= 2`), this is at most
//! `6 (3 + 3/2 + 1/4) M^2 e^3 = 28.5 e^3 M^2 < 2^(2m + 5)`.
//! A sign is *certain* when `|det| > 2^(2m + 5)`: then no admissible move
//! can reach zero, and the sign on the originals is the sign on the grid.
//! (A bound per row, `2^(a + max(a, c) + 5)` with `a` the edges' and `c`
//! the offset's bits, certifies 1.5 % more of random pairs at W = 8, under 1 % more at
//! W = 12, and needs an adder and a shifter per test.)
//!
//! # What the hardware computes
//!
//! Only OR-trees and wiring (no multiplier, no adder):
//!
//! * `m` is the bit length of the OR of `x ^ (x >> 63)` over the nine
//!   entries (the ones' complement magnitude, `|x|` or `|x| - 1`, so every
//!   `|x| <= 2^m`), raised to at least 1. The hardware keeps it as the
//!   thermometer `2^m - 1` (the OR smeared downwards);
//! * the determinant `P` is certain when `(P ^ (P >> 127)) >> (2m + 5)` is
//!   not zero, that is `|P| - [P < 0] >= 2^(2m + 5)`, which implies
//!   `|P| > 2^(2m + 5)`. The mask of the bits below `2m + 5` is the
//!   thermometer with every bit doubled, shifted up by five: wiring.
//!
//! # Which signs a verdict depends on
//!
//! The verdict is certain when one of these holds (each a geometric fact on
//! the originals once its signs are certain, whatever the degeneracies):
//!
//! 1. T1's three vertices are certainly strictly on one side of T2's plane
//!    (the verdict is *no*);
//! 2. the same for T2 against T1's plane;
//! 3. all six plane-side signs are certain (so no triangle is degenerate,
//!    the pair is not coplanar and both alignments are the originals'), and
//!    step (7)'s two determinants are certain, or one of them is certainly
//!    positive (the verdict is *no*).
//!
//! Coplanar and degenerate pairs are never certain: their verdicts rest on
//! zero signs, which half a step can change. [`crate::certificate`]'s users
//! (`tritri classify --certified`, `tritri sim --certified`) decide them
//! again with the exact predicates on the originals.

use crate::devillers_guigue::{align_t1, align_t2};
use crate::fixed_point::{orient3d_value, FixedPoint3, FixedTriangle};
use crate::sign::Sign;

/// A fixed-point verdict and its certificate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CertifiedVerdict {
    /// The exact verdict on the grid (what the hardware's `out_hit` says).
    pub hit: bool,
    /// The verdict on the original coordinates is provably `hit`.
    pub certain: bool,
}

/// Bit length of `x ^ (x >> 63)`: `|x| <= 2^bits`.
#[inline]
pub fn magnitude_bits(x: i64) -> u32 {
    64 - (x ^ (x >> 63)).leading_zeros()
}

/// `m` of the module docs: the bit length of the largest ones' complement
/// magnitude among `entries`, at least 1.
#[inline]
pub fn entry_bits(entries: &[i64]) -> u32 {
    entries
        .iter()
        .fold(1, |bits, &x| bits.max(magnitude_bits(x)))
}

/// `(P ^ (P >> 127)) >> (2m + 5) != 0`: the determinant is clear of every
/// admissible move of entries of at most `m` bits.
#[inline]
pub fn clears_threshold(value: i128, m: u32) -> bool {
    ((value ^ (value >> 127)) >> (2 * m + 5)) != 0
}

/// The sign of `[a,b,c,d]` and whether it is certain.
pub fn orient3d_certified(
    a: FixedPoint3,
    b: FixedPoint3,
    c: FixedPoint3,
    d: FixedPoint3,
) -> (Sign, bool) {
    let value = orient3d_value(a, b, c, d);
    let entries: Vec<i64> = [b, c, d]
        .iter()
        .flat_map(|p| (0..3).map(move |k| p[k] - a[k]))
        .collect();
    (
        Sign::of_i128(value),
        clears_threshold(value, entry_bits(&entries)),
    )
}

/// Signs of `t`'s vertices against `plane`'s plane, and their certainty.
fn plane_side(plane: &FixedTriangle, t: &FixedTriangle) -> ([Sign; 3], bool) {
    let s = t.map(|v| orient3d_certified(plane[0], plane[1], plane[2], v));
    (
        s.map(|(sign, _)| sign),
        s.iter().all(|&(_, certain)| certain),
    )
}

fn strictly_one_side(s: [Sign; 3]) -> bool {
    s[0] == s[1] && s[1] == s[2] && !s[0].is_zero()
}

/// The certificate of the verdict on `(t1, t2)`, by the rules of the module
/// docs; the same bit the hardware's `out_certain` carries.
pub fn certain(t1: &FixedTriangle, t2: &FixedTriangle) -> bool {
    let (d1, all_d1_certain) = plane_side(t2, t1);
    let (d2, all_d2_certain) = plane_side(t1, t2);
    if (all_d1_certain && strictly_one_side(d1)) || (all_d2_certain && strictly_one_side(d2)) {
        return true;
    }
    if !(all_d1_certain && all_d2_certain) {
        return false;
    }
    // Rule 3: the alignment of steps (5)-(6), then step (7)'s operands, as
    // in `devillers_guigue::interval_overlap`.
    let (t1, t2, d2) = align_t1(*t1, *t2, d1, d2);
    let aligned = align_t2(t2, d2);
    let [p1, mut q1, mut r1] = t1;
    if aligned.swap_t1 {
        std::mem::swap(&mut q1, &mut r1);
    }
    let [p2, q2, r2] = aligned.t2;
    let (first, first_certain) = orient3d_certified(q1, p2, p1, q2);
    let (second, second_certain) = orient3d_certified(p1, p2, r1, r2);
    (first_certain && second_certain)
        || (first_certain && first.is_positive())
        || (second_certain && second.is_positive())
}

/// The grid verdict with its certificate.
pub fn certified_intersects(t1: &FixedTriangle, t2: &FixedTriangle) -> CertifiedVerdict {
    CertifiedVerdict {
        hit: crate::fixed_point::intersects(t1, t2),
        certain: certain(t1, t2),
    }
}

/// The answer on the original coordinates from grid verdicts and their
/// certificates.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct CertifiedRun {
    /// Per pair: the grid verdict where certain, else the exact verdict on
    /// the originals.
    pub verdicts: Vec<bool>,
    /// Pairs whose verdict went back to the host.
    pub uncertain: usize,
    /// Of those, pairs whose grid verdict was wrong.
    pub changed: usize,
}

/// Decides every uncertain verdict again with the exact predicates on the
/// original coordinates (`crate::exact_f64`); `grid[i]` belongs to `pairs[i]`.
pub fn recheck(pairs: &[crate::TrianglePair], grid: &[CertifiedVerdict]) -> CertifiedRun {
    assert_eq!(pairs.len(), grid.len(), "one grid verdict per pair");
    let mut run = CertifiedRun {
        verdicts: Vec::with_capacity(pairs.len()),
        ..Default::default()
    };
    for (pair, v) in pairs.iter().zip(grid) {
        if v.certain {
            run.verdicts.push(v.hit);
        } else {
            let exact = crate::exact_f64::intersects(&pair.t1, &pair.t2);
            run.uncertain += 1;
            run.changed += (exact != v.hit) as usize;
            run.verdicts.push(exact);
        }
    }
    run
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact_f64;
    use crate::quantize::quantize_pair;

    #[test]
    fn magnitude_bits_bound_the_magnitude() {
        for x in -70i64..=70 {
            let bits = magnitude_bits(x);
            assert!(x.unsigned_abs() <= 1 << bits, "{x}");
            assert!(
                bits == 0 || x.unsigned_abs() >= 1 << (bits - 1),
                "{x}: not tight"
            );
        }
        assert_eq!(magnitude_bits(-4), 2);
        assert_eq!(magnitude_bits(4), 3);
    }

    /// The bound of the module docs: 6 ((M + e)^3 - M^3) < 2^(2m + 5).
    #[test]
    fn threshold_exceeds_every_admissible_change() {
        let e = 1.0 + 2f64.powi(-20);
        for m in 1..40u32 {
            let big_m = 2f64.powi(m as i32);
            let change = 6.0 * ((big_m + e).powi(3) - big_m.powi(3));
            assert!(change < 2f64.powi(2 * m as i32 + 5), "m {m}: {change}");
        }
        assert_eq!(entry_bits(&[0, 0]), 1);
        assert_eq!(entry_bits(&[-4, 3]), 2);
        assert_eq!(entry_bits(&[4]), 3);
    }

    /// Random and near-degenerate pairs quantized coarsely (W = 8, where
    /// grid verdicts are often wrong): no certain verdict disagrees with the
    /// exact verdict on the originals, and the certificate is not vacuous.
    #[test]
    fn certain_verdicts_are_the_originals_verdicts() {
        let mut pairs = crate::hard_cases::random_pairs(10_000, 11);
        pairs.extend(crate::hard_cases::random_near_degenerate_pairs(10_000, 12));
        let (mut certain_count, mut wrong) = (0, 0);
        for pair in &pairs {
            let (q1, q2) = quantize_pair(pair, 8).unwrap();
            let v = certified_intersects(&q1, &q2);
            let truth = exact_f64::intersects(&pair.t1, &pair.t2);
            wrong += (v.hit != truth) as usize;
            if v.certain {
                certain_count += 1;
                assert_eq!(v.hit, truth, "certain but wrong: {pair:?}");
            }
        }
        assert!(
            wrong > 500,
            "the test should see wrong grid verdicts ({wrong})"
        );
        // About 9 % at W = 8 (88 % of the random pairs at W = 12, all at 24).
        assert!(certain_count > 1_500, "{certain_count} certain of 20000");
    }

    /// Coplanar pairs are never certain.
    #[test]
    fn coplanar_pairs_are_uncertain() {
        let t1 = [[0, 0, 0], [1000, 0, 0], [0, 1000, 0]];
        let t2 = [[1, 1, 0], [500, 1, 0], [1, 500, 0]];
        assert!(!certain(&t1, &t2));
        let far = [[1, 1, 10_000], [5000, 1, 10_000], [1, 5000, 12_000]];
        assert!(
            certain(&t1, &far),
            "a triangle high above the other's plane"
        );
    }
}
