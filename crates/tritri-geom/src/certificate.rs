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
//! An orientation determinant `[a,b,c,d] = det(e1, e2, w)` with the rows
//! `e1 = b - a`, `e2 = c - a`, `w = d - a`; `n = e1 × e2`, so the
//! determinant is `w · n`. Move every entry by at most `e`. Expanding the
//! determinant by rows (multilinearity), the change is at most
//!
//! ```text
//! |Δ| <= e (|n|_1 + |e2 × w|_1 + |w × e1|_1)      first order
//!      + 2 e^2 (|w|_1 + |e1|_1 + |e2|_1)          second order
//!      + 6 e^3                                     third order
//! ```
//!
//! and `|u × v|_1 <= |u|_1 |v|_1`, so with `X = |n|_1`, `Sw = |w|_1`,
//! `Se = |e1|_1 + |e2|_1 < 2^ke` (`ke` its bit length) and
//! `Y = 2^(bitlen Sw + ke) > Sw Se`:
//!
//! ```text
//! |Δ| <= e X + e Sw Se + 2 e^2 (Sw + Se) + 6 e^3
//!      < T = X + (X >> 19) + Y + (Y >> 19) + 4 Sw + 2^(ke + 2) + 16.
//! ```
//!
//! (`X >> 19` and `Y >> 19` cover the `2^-20` of `e` up to less than 1
//! each, and `4 Sw + 2^(ke + 2) + 16` the rest with 11 to spare.) The
//! hardware sums the normal's ones' complement magnitudes instead
//! ([`normal_l1`], no negation), at least `|n|_1 - 3`: that takes 4 of the
//! spare 11, with its `>> 19`. A sign is *certain*
//! when `|det| >= T`: then no admissible move reaches zero, and by
//! continuity the sign on the originals is the sign on the grid. A zero
//! determinant is never certain (`T >= 16`).
//!
//! The earlier bound, `2^(2m + 5)` from the largest entry `2^m` alone
//! (`6 ((M + e)^3 - M^3)`), needed no adder; on real scenes at W = 24 it sent
//! 0.24 to 0.34 % of the pairs back to the host, this one 0 to 0.03 %
//! (docs/certificates.md).
//!
//! # What the hardware computes
//!
//! Adders, comparators and shifts; no multiplier (`arith/certificate.rs`):
//!
//! * `X`, `Sw` and `Se`: sums of magnitudes; the plane's `ke` comes once
//!   per triangle, with its normal;
//! * `bitlen Sw` and `ke` from the leading ones; `Y + (Y >> 19)` and
//!   `2^(ke + 2)` decoded from their exponents;
//! * `T` in two additions, and `certain = (P ^ (P >> top)) >= T`: the ones'
//!   complement magnitude `|P| - [P < 0]` at least `T` implies `|P| >= T`.
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
use crate::fixed_point::{cross, orient3d_value, sub, FixedPoint3, FixedTriangle};
use crate::scene::reference::PairSet;
use crate::sign::Sign;

/// A fixed-point verdict and its certificate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CertifiedVerdict {
    /// The exact verdict on the grid (what the hardware's `out_hit` says).
    pub hit: bool,
    /// The verdict on the original coordinates is provably `hit`.
    pub certain: bool,
}

/// Bit length: `x < 2^bit_length(x)`, 0 for 0.
#[inline]
pub fn bit_length(x: u128) -> u32 {
    128 - x.leading_zeros()
}

/// `|v|_1` of a vector of coordinate differences.
#[inline]
pub fn l1(v: [i64; 3]) -> u128 {
    v.iter().map(|x| x.unsigned_abs() as u128).sum()
}

/// `X`: the sum of a cross product's ones' complement magnitudes
/// `|x| - [x < 0]`, at least `|n|_1 - 3` (no negation in hardware; the
/// threshold's slack covers the 3).
#[inline]
pub fn normal_l1(n: [i128; 3]) -> u128 {
    n.into_iter().map(ones_complement_magnitude).sum()
}

/// `|x| - [x < 0]`: `x` with its bits inverted when negative.
#[inline]
pub fn ones_complement_magnitude(x: i128) -> u128 {
    (x ^ (x >> 127)) as u128
}

/// `T` of the module docs from `X` ([`normal_l1`]), `Sw = |w|_1` and the
/// bit length of `Se = |e1|_1 + |e2|_1`: every admissible move changes the
/// determinant by less than `T`.
#[inline]
pub fn threshold(normal_l1: u128, offset_l1: u128, edges_bits: u32) -> u128 {
    let y = 1u128 << (bit_length(offset_l1) + edges_bits);
    normal_l1 + (normal_l1 >> 19) + y + (y >> 19) + 4 * offset_l1 + (4 << edges_bits) + 16
}

/// `(P ^ (P >> 127)) >= T`: the determinant is clear of every admissible
/// move.
#[inline]
pub fn clears_threshold(value: i128, threshold: u128) -> bool {
    ((value ^ (value >> 127)) as u128) >= threshold
}

/// The sign of `[a,b,c,d]` and whether it is certain.
pub fn orient3d_certified(
    a: FixedPoint3,
    b: FixedPoint3,
    c: FixedPoint3,
    d: FixedPoint3,
) -> (Sign, bool) {
    let (e1, e2, w) = (sub(b, a), sub(c, a), sub(d, a));
    let value = orient3d_value(a, b, c, d);
    let t = threshold(normal_l1(cross(e1, e2)), l1(w), bit_length(l1(e1) + l1(e2)));
    (Sign::of_i128(value), clears_threshold(value, t))
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

/// The host's share of a certified answer: an uncertain verdict decided
/// again with the exact predicates on the original coordinates
/// (`crate::exact_f64`). Every route to an exact answer calls this one.
pub fn decide_again(t1: &crate::Triangle, t2: &crate::Triangle) -> bool {
    crate::exact_f64::intersects(t1, t2)
}

/// Decides every uncertain verdict again ([`decide_again`]); `grid[i]`
/// belongs to `pairs[i]`.
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
            let exact = decide_again(&pair.t1, &pair.t2);
            run.uncertain += 1;
            run.changed += (exact != v.hit) as usize;
            run.verdicts.push(exact);
        }
    }
    run
}

/// A scene's answer on the original coordinates, from the grid's pairs.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct CertifiedPairs {
    /// The grid's hits that carry a certificate, and the uncertain pairs
    /// that intersect on the originals.
    pub pairs: PairSet,
    /// Uncertain pairs whose verdict on the originals differs from the grid's.
    pub changed: usize,
}

/// [`recheck`] for a scene: `grid` holds the pairs `(i, j)` that intersect
/// on the grid, `uncertain` every pair whose verdict (hit or not) has no
/// certificate; `a[i]` and `b[j]` are the original triangles.
pub fn recheck_pairs(
    grid: &PairSet,
    uncertain: &PairSet,
    a: &[crate::Triangle],
    b: &[crate::Triangle],
) -> CertifiedPairs {
    let mut pairs: PairSet = grid.difference(uncertain).copied().collect();
    let mut changed = 0;
    for &(i, j) in uncertain {
        let exact = decide_again(&a[i as usize], &b[j as usize]);
        changed += (exact != grid.contains(&(i, j))) as usize;
        if exact {
            pairs.insert((i, j));
        }
    }
    CertifiedPairs { pairs, changed }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact_f64;
    use crate::quantize::quantize_pair;

    /// `T` exceeds the change of the determinant under the worst moves we
    /// can find: every corner of the box of moves (each entry by `±e`) for
    /// random rows, small and large, and rows along the axes.
    #[test]
    fn threshold_exceeds_every_admissible_change() {
        let e = 1.0 + 2f64.powi(-20);
        let det = |r: [[f64; 3]; 3]| {
            r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
                - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
                + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0])
        };
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let mut worst: f64 = 0.0;
        for trial in 0..4000 {
            let scale = [1i64, 3, 40, 1 << 12][trial % 4];
            let mut rows = [[0i64; 3]; 3];
            for row in rows.iter_mut() {
                for x in row.iter_mut() {
                    *x = rng.gen_range(-scale..=scale);
                }
            }
            if trial % 7 == 0 {
                rows = [[scale, 0, 0], [0, scale, 0], [0, 0, 1]];
            }
            let [e1, e2, w] = rows;
            let t = threshold(normal_l1(cross(e1, e2)), l1(w), bit_length(l1(e1) + l1(e2))) as f64;
            let base = det(rows.map(|r| r.map(|x| x as f64)));
            for corner in 0..512u32 {
                let moved = std::array::from_fn(|i| {
                    std::array::from_fn(|k| {
                        let s = if corner >> (3 * i + k) & 1 == 1 {
                            e
                        } else {
                            -e
                        };
                        rows[i][k] as f64 + s
                    })
                });
                let change = (det(moved) - base).abs();
                assert!(change < t, "{rows:?}: change {change} >= T {t}");
                worst = worst.max(change / t);
            }
        }
        // The bound is not far from the worst move.
        eprintln!("the worst move changes the determinant by {worst:.3} T");
        assert!(worst > 0.2, "worst change / T {worst}");
    }

    #[test]
    fn threshold_parts() {
        assert_eq!(bit_length(0), 0);
        assert_eq!(bit_length(1), 1);
        assert_eq!(bit_length(4), 3);
        assert_eq!(l1([-3, 4, 0]), 7);
        assert_eq!(normal_l1([-3, 4, -1]), 6);
        // X = 0, Sw = 1, Se of 2 bits: Y = 2^(1 + 2) = 8; 8 + 4 + 16 + 16.
        assert_eq!(threshold(0, 1, 2), 44);
        // X = 2^20: X >> 19 = 2; Sw = 0, Se = 0: Y = 1, 4 << 0 = 4.
        assert_eq!(threshold(1 << 20, 0, 0), (1 << 20) + 2 + 1 + 4 + 16);
        assert!(clears_threshold(44, 44) && clears_threshold(-45, 44));
        assert!(!clears_threshold(-44, 44) && !clears_threshold(43, 44));
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
        eprintln!("{certain_count} certain of 20000, {wrong} grid verdicts wrong");
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
