//! Random operands, and the ends of their ranges, for the arithmetic
//! primitives' tests: each streams them one per clock and holds the
//! outputs to the exact integer values, its latency constant asserted
//! (`sim_drive::assert_stream_matches`). Widths are the W = 24
//! pipeline's: W = 24, D = 25, C = 49, O = 74.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub(crate) const VECTORS: usize = 400;

/// `n` values of `bits`-bit two's complement: uniform, the two ends of the
/// range, and small values, in turn.
pub(crate) fn values(rng: &mut ChaCha8Rng, bits: u32, n: usize) -> Vec<i128> {
    let lim = 1i128 << (bits - 1);
    (0..n)
        .map(|k| match k % 3 {
            0 => rng.gen_range(-lim..lim),
            1 => {
                if rng.gen_bool(0.5) {
                    -lim
                } else {
                    lim - 1
                }
            }
            _ => rng.gen_range(-2..3),
        })
        .collect()
}

/// Difference vectors `b - a` and `c - a` of random W = 24 points `a`, `b`,
/// `c`, and `d - a` for a fourth: the operands the products see in the
/// pipeline. (Their widths C = 2W + 1 and O = 3W + 2 hold for these, not
/// for any 25-bit vectors: a cross product is twice a triangle's area.)
pub(crate) fn edge_vectors(seed: u64) -> Vec<[[i128; 3]; 3]> {
    tuples::<12>(seed, 24)
        .into_iter()
        .map(|p| {
            let edge = |k: usize| std::array::from_fn(|i| p[3 * k + i] - p[i]);
            [edge(1), edge(2), edge(3)]
        })
        .collect()
}

pub(crate) fn narrow(v: [i128; 3]) -> [i64; 3] {
    v.map(|x| x as i64)
}

pub(crate) fn tuples<const K: usize>(seed: u64, bits: u32) -> Vec<[i128; K]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let columns: Vec<Vec<i128>> = (0..K).map(|_| values(&mut rng, bits, VECTORS)).collect();
    (0..VECTORS)
        .map(|i| std::array::from_fn(|k| columns[k][(i + 7 * k) % VECTORS]))
        .collect()
}
