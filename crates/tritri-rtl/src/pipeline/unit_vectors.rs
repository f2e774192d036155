//! Test vectors and their software answers for the pipeline's units,
//! which each unit's tests drive against tritri-geom's models
//! (`sim_drive::assert_stream_matches`), its latency constant asserted.
//! W = 24 (D = 25, C = 49, O = 74). The operand selection
//! (`orient3d_operands`) and the decision, whose model is the control
//! flow of `fixed_point::intersects` itself, are covered in context by
//! the whole pipeline's co-simulations (tritri-cosim).

use crate::arith::convert::from_i128;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rust_hdl::prelude::*;
use tritri_geom::certificate::{bit_length, l1};
use tritri_geom::devillers_guigue::hulls_intersect_2d;
use tritri_geom::fixed_point::{cross, FixedPoint, FixedPoint3, FixedTriangle};
use tritri_geom::kernel::ExactKernel;
use tritri_geom::sign::Sign;

pub(crate) const VECTORS: usize = 300;

pub(crate) const LIMIT: i64 = 1 << 23;

/// A random W = 24 point: uniform, at the ends of the range, or small.
pub(crate) fn point(rng: &mut ChaCha8Rng, kind: usize) -> FixedPoint3 {
    std::array::from_fn(|_| match kind % 3 {
        0 => rng.gen_range(-LIMIT..LIMIT),
        1 => {
            if rng.gen_bool(0.5) {
                -LIMIT
            } else {
                LIMIT - 1
            }
        }
        _ => rng.gen_range(-3..4),
    })
}

pub(crate) fn triangles(seed: u64) -> Vec<FixedTriangle> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..VECTORS)
        .map(|k| std::array::from_fn(|_| point(&mut rng, k)))
        .collect()
}

/// Triangles in one lattice plane `o + a u + b v` (small `a`, `b`), so that
/// pairs of them are exactly coplanar and often touch; a few degenerate.
pub(crate) fn coplanar_pairs(seed: u64) -> Vec<(FixedTriangle, FixedTriangle)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..VECTORS)
        .map(|_| {
            let o = point(&mut rng, 2);
            let span = 1 << rng.gen_range(0..18);
            let u: [i64; 3] = std::array::from_fn(|_| rng.gen_range(-span..=span));
            let v: [i64; 3] = std::array::from_fn(|_| rng.gen_range(-span..=span));
            let mut at = || {
                let (a, b) = (rng.gen_range(-4..5), rng.gen_range(-4..5));
                std::array::from_fn(|k| o[k] + a * u[k] + b * v[k])
            };
            ([at(), at(), at()], [at(), at(), at()])
        })
        .collect()
}

pub(crate) fn set_vertices<const W: usize>(
    signals: &mut [Signal<In, Bits<W>>; 9],
    t: &FixedTriangle,
) {
    for (k, s) in signals.iter_mut().enumerate() {
        s.next = from_i128(t[k / 3][k % 3] as i128);
    }
}

pub(crate) fn edges(t: &FixedTriangle) -> ([i64; 3], [i64; 3]) {
    let [p, q, r] = *t;
    (
        std::array::from_fn(|k| q[k] - p[k]),
        std::array::from_fn(|k| r[k] - p[k]),
    )
}

pub(crate) fn normal(t: &FixedTriangle) -> [i128; 3] {
    let (u, v) = edges(t);
    cross(u, v)
}

/// Indices of the lexicographically smallest and largest vertex, the first
/// on ties (as `devillers_guigue::shape` picks a degenerate triangle's ends).
pub(crate) fn lexicographic_ends(t: &FixedTriangle) -> (usize, usize) {
    let order = |i: usize, j: usize| FixedPoint::compare_lexicographic(t[i], t[j]);
    let low = (1..3).fold(0, |lo, i| if order(i, lo).is_lt() { i } else { lo });
    let high = (1..3).fold(0, |hi, i| if order(i, hi).is_gt() { i } else { hi });
    (low, high)
}

/// `ke = bitlen(|q - p|_1 + |r - p|_1)`, the certificates' of a triangle's
/// plane.
pub(crate) fn edges_bits(t: &FixedTriangle) -> u64 {
    let (u, v) = edges(t);
    bit_length(l1(u) + l1(v)) as u64
}

/// Pairs of degenerate triangles (three collinear vertices each) through
/// one point: on one line, crossing lines or skew.
pub(crate) fn degenerate_pairs() -> Vec<(FixedTriangle, FixedTriangle)> {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let mut collinear =
        |o: FixedPoint3, d: [i64; 3]| on_line(o, d, std::array::from_fn(|_| rng.gen_range(-3..4)));
    let mut vectors = Vec::new();
    let mut rng2 = ChaCha8Rng::seed_from_u64(10);
    for k in 0..VECTORS {
        let o = point(&mut rng2, 2);
        let d1: [i64; 3] = std::array::from_fn(|_| rng2.gen_range(-2..3));
        // The second segment on the same line, a crossing line or anywhere.
        let d2: [i64; 3] = if k % 3 == 0 {
            d1
        } else {
            std::array::from_fn(|_| rng2.gen_range(-2..3))
        };
        vectors.push((collinear(o, d1), collinear(o, d2)));
    }
    vectors
}

/// The segments (lexicographic ends) of two degenerate triangles meet in
/// all three axis projections.
pub(crate) fn segments_meet((t1, t2): &(FixedTriangle, FixedTriangle)) -> bool {
    let ((a, b), (c, d)) = (lexicographic_ends(t1), lexicographic_ends(t2));
    (0..3).all(|axis| hulls_intersect_2d::<FixedPoint>(axis, &[t1[a], t1[b]], &[t2[c], t2[d]]))
}

/// The sign triples alignment sees: not all zero (a triangle in the
/// other's plane goes to the coplanar test) and not all of one sign (a
/// triangle strictly on one side is rejected before), 24 of 27.
pub(crate) fn sign_triples() -> Vec<[Sign; 3]> {
    let signs = [Sign::Negative, Sign::Zero, Sign::Positive];
    let all: Vec<[Sign; 3]> = (0..27)
        .map(|k| [signs[k % 3], signs[k / 3 % 3], signs[k / 9]])
        .collect();
    all.into_iter()
        .filter(|s| !(s[0] == s[1] && s[1] == s[2]))
        .collect()
}

pub(crate) fn set_signs(
    negative: &mut [Signal<In, Bit>; 3],
    zero: &mut [Signal<In, Bit>; 3],
    s: &[Sign; 3],
) {
    for k in 0..3 {
        negative[k].next = s[k] == Sign::Negative;
        zero[k].next = s[k] == Sign::Zero;
    }
}

/// The degenerate triangle `o + s_k d`, `k = 0, 1, 2`.
pub(crate) fn on_line(o: FixedPoint3, d: [i64; 3], steps: [i64; 3]) -> FixedTriangle {
    steps.map(|s| std::array::from_fn(|i| o[i] + s * d[i]))
}

/// Random triangles, and degenerate ones (collinear vertices, repeated
/// vertices, points) whose segment ends matter.
pub(crate) fn triangles_and_degenerate_ones(seed: u64) -> Vec<FixedTriangle> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = triangles(seed);
    for k in 0..VECTORS {
        let o = point(&mut rng, 2);
        let d: [i64; 3] = std::array::from_fn(|_| rng.gen_range(-2..3));
        let s = [
            rng.gen_range(-3..4),
            rng.gen_range(-3..4),
            if k % 4 == 0 { 0 } else { rng.gen_range(-3..4) },
        ];
        out.push(on_line(o, d, s));
    }
    out
}
