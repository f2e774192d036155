//! The software answers a hardware run is compared with.
//!
//! * [`fixed_point_pairs`]: the bit-exact model of the hardware
//!   ([`crate::fixed_point`]) over every pair of every batch — what the
//!   `model` engine reports;
//! * [`quantized_exact_pairs`]: an independent exact model on the same
//!   quantized coordinates ([`crate::exact_f64`], whose adaptive predicates
//!   are exact on the integer coordinates, which f64 holds exactly for
//!   W <= 32); it must equal the fixed-point model, any difference is a bug;
//! * [`exact_f64_pairs`]: the ground truth, exact predicates on the original
//!   f64 coordinates over all `N1 * N2` pairs of the full objects. The
//!   difference between it and the quantized answer is the quantization error
//!   ([`PairDiff`]).
//!
//! Every function returns the deduplicated set of intersecting pairs
//! `(index in A, index in B)`. Skipping a pair whose two triangles have
//! disjoint boxes is exact (closed triangles in disjoint boxes cannot meet),
//! and all of them do it to stay fast; the hardware does not, and the
//! number of pairs it tests is [`super::PreparedScene::pairs_tested`].

use super::{Batch, TaggedTriangle};
use crate::bounding_volume::Aabb;
use crate::triangle::Triangle;
use crate::{exact_f64, fixed_point};
use std::collections::BTreeSet;

/// Intersecting pairs `(i, j)`: triangle `i` of A meets triangle `j` of B.
pub type PairSet = BTreeSet<(u32, u32)>;

/// The bit-exact hardware model over every pair of every batch; `progress`
/// is told how many pairs were done (in pieces).
pub fn fixed_point_pairs(batches: &[Batch], progress: &(dyn Fn(u64) + Sync)) -> PairSet {
    pairs_over_batches(
        batches,
        |x, y| fixed_point::intersects(&x.triangle, &y.triangle),
        progress,
    )
}

/// Exact predicates on the quantized coordinates (as f64), over every pair of
/// every batch, deduplicated across tiles.
pub fn quantized_exact_pairs(batches: &[Batch]) -> PairSet {
    let as_f64 = |t: &TaggedTriangle| t.triangle.map(|p| p.map(|c| c as f64));
    pairs_over_batches(
        batches,
        |x, y| exact_f64::intersects(&as_f64(x), &as_f64(y)),
        &|_| {},
    )
}

/// `test` on every pair of every batch (pairs with disjoint integer boxes are
/// skipped: they cannot intersect), on all cores, deduplicated.
pub fn pairs_over_batches(
    batches: &[Batch],
    test: impl Fn(&TaggedTriangle, &TaggedTriangle) -> bool + Sync,
    progress: &(dyn Fn(u64) + Sync),
) -> PairSet {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    // One set of threads for all batches. Many batches: thread k takes
    // batches k, k + threads, ...; few (large) batches: thread k takes rows
    // k, k + threads, ... of every batch.
    let by_batch = batches.len() >= 4 * threads;
    let found: Vec<Vec<(u32, u32)>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let test = &test;
                s.spawn(move || {
                    let mut hits = Vec::new();
                    let mine = batches
                        .iter()
                        .enumerate()
                        .filter(|(i, _)| !by_batch || i % threads == k);
                    for (_, batch) in mine {
                        let (first_row, row_step) = if by_batch { (0, 1) } else { (k, threads) };
                        let rows = batch_pairs(batch, first_row, row_step, test, &mut hits);
                        progress(rows * batch.b.len() as u64);
                    }
                    hits
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("worker thread panicked"))
            .collect()
    });
    found.into_iter().flatten().collect()
}

/// `test` on rows `first_row, first_row + row_step, ...` of A against all of
/// B, skipping pairs with disjoint boxes; returns the number of rows done.
fn batch_pairs(
    batch: &Batch,
    first_row: usize,
    row_step: usize,
    test: &impl Fn(&TaggedTriangle, &TaggedTriangle) -> bool,
    hits: &mut Vec<(u32, u32)>,
) -> u64 {
    // B's boxes sorted by their low x: the B boxes that can overlap an A box
    // [lo, hi] in x start in [lo - widest, hi] (exact in integers).
    let mut boxes_b: Vec<(Aabb<i64>, &TaggedTriangle)> = batch
        .b
        .iter()
        .map(|t| (triangle_box(&t.triangle), t))
        .collect();
    boxes_b.sort_unstable_by_key(|(bb, _)| bb.lo[0]);
    let widest = boxes_b
        .iter()
        .map(|(bb, _)| bb.hi[0] - bb.lo[0])
        .max()
        .unwrap_or(0);
    let mut rows = 0;
    for x in batch.a.iter().skip(first_row).step_by(row_step) {
        rows += 1;
        let bx = triangle_box(&x.triangle);
        let start = boxes_b.partition_point(|(bb, _)| bb.lo[0] < bx.lo[0] - widest);
        for (by, y) in &boxes_b[start..] {
            if by.lo[0] > bx.hi[0] {
                break;
            }
            if bx.overlap(by).is_some() && test(x, y) {
                hits.push((x.id, y.id));
            }
        }
    }
    rows
}

fn triangle_box<T: Copy + PartialOrd>(t: &[[T; 3]; 3]) -> Aabb<T> {
    Aabb::of_triangles(std::iter::once(t)).expect("one triangle")
}

/// The ground truth over all pairs of the full objects.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactF64Result {
    pub pairs: PairSet,
    /// Pairs whose triangle boxes overlap: the ones actually decided (every
    /// other pair of the `N1 * N2` is disjoint by its boxes).
    pub pairs_decided: u64,
}

/// Exact predicates on the original coordinates, every pair of `a × b`
/// whose triangle boxes overlap (a sweep along x over the boxes).
pub fn exact_f64_pairs(a: &[Triangle], b: &[Triangle]) -> ExactF64Result {
    f64_pairs_with(a, b, exact_f64::intersects)
}

/// [`exact_f64_pairs`] with another decision function (for timing the
/// published float code on the same work).
pub fn f64_pairs_with(
    a: &[Triangle],
    b: &[Triangle],
    test: impl Fn(&Triangle, &Triangle) -> bool,
) -> ExactF64Result {
    let boxes_a: Vec<Aabb<f64>> = a.iter().map(triangle_box).collect();
    let mut order_b: Vec<(Aabb<f64>, u32)> = b
        .iter()
        .enumerate()
        .map(|(j, t)| (triangle_box(t), j as u32))
        .collect();
    order_b.sort_by(|x, y| x.0.lo[0].total_cmp(&y.0.lo[0]));
    // Widths rounded up, so `widest_b` is at least every true width.
    let widest_b = order_b
        .iter()
        .map(|(bb, _)| next_up(bb.hi[0] - bb.lo[0]))
        .fold(0.0, f64::max);
    let mut result = ExactF64Result {
        pairs: PairSet::new(),
        pairs_decided: 0,
    };
    for (i, ba) in boxes_a.iter().enumerate() {
        // A B box that overlaps has hi >= ba.lo, so lo = hi - width >= ba.lo - widest,
        // and lo <= ba.hi. The subtraction rounds; one step down keeps the bound below.
        let from = next_down(ba.lo[0] - widest_b);
        let start = order_b.partition_point(|(bb, _)| bb.lo[0] < from);
        for (bb, j) in &order_b[start..] {
            if bb.lo[0] > ba.hi[0] {
                break;
            }
            if ba.overlap(bb).is_some() {
                result.pairs_decided += 1;
                if test(&a[i], &b[*j as usize]) {
                    result.pairs.insert((i as u32, *j));
                }
            }
        }
    }
    result
}

/// The largest f64 below `x` (`x` itself for NaN and -inf).
fn next_down(x: f64) -> f64 {
    if x.is_nan() || x == f64::NEG_INFINITY {
        return x;
    }
    if x == 0.0 {
        return -f64::from_bits(1);
    }
    let bits = x.to_bits();
    f64::from_bits(if x > 0.0 { bits - 1 } else { bits + 1 })
}

/// The smallest f64 above `x`.
fn next_up(x: f64) -> f64 {
    -next_down(-x)
}

/// How a list of pairs differs from the reference, as multisets: a pair
/// the other list holds twice but the reference once is one extra (so a
/// hardware run that reports a pair twice is caught).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PairDiff {
    /// In the reference, not in the other list (sorted).
    pub missing: Vec<(u32, u32)>,
    /// In the other list, not in the reference (sorted).
    pub extra: Vec<(u32, u32)>,
}

impl PairDiff {
    /// `reference` and `other` in any order: sets, sorted lists, or pairs
    /// in the order a run delivered them.
    pub fn between<'p>(
        reference: impl IntoIterator<Item = &'p (u32, u32)>,
        other: impl IntoIterator<Item = &'p (u32, u32)>,
    ) -> PairDiff {
        let sorted = |pairs: Vec<&'p (u32, u32)>| {
            let mut v: Vec<(u32, u32)> = pairs.into_iter().copied().collect();
            v.sort_unstable();
            v
        };
        let (reference, other) = (
            sorted(reference.into_iter().collect()),
            sorted(other.into_iter().collect()),
        );
        let mut diff = PairDiff::default();
        let (mut i, mut j) = (0, 0);
        while i < reference.len() || j < other.len() {
            if j == other.len() || (i < reference.len() && reference[i] < other[j]) {
                diff.missing.push(reference[i]);
                i += 1;
            } else if i == reference.len() || other[j] < reference[i] {
                diff.extra.push(other[j]);
                j += 1;
            } else {
                i += 1;
                j += 1;
            }
        }
        diff
    }

    pub fn is_empty(&self) -> bool {
        self.missing.is_empty() && self.extra.is_empty()
    }

    /// `(missing, extra)` counts.
    pub fn counts(&self) -> (usize, usize) {
        (self.missing.len(), self.extra.len())
    }
}

/// Every pair `(a.id, b.id)` of every batch's arrays for which `test`
/// holds, one entry per batch it occurs in, sorted. Unlike
/// [`pairs_over_batches`] it skips nothing, so `test` may be any verdict
/// (the stub pipeline's, for example), and it keeps duplicates across
/// batches, as a hardware run reports them.
pub fn pairs_where(
    batches: &[Batch],
    test: impl Fn(&TaggedTriangle, &TaggedTriangle) -> bool,
) -> Vec<(u32, u32)> {
    let mut pairs: Vec<(u32, u32)> = batches
        .iter()
        .flat_map(|batch| {
            batch
                .a
                .iter()
                .flat_map(|a| batch.b.iter().filter(|b| test(a, b)).map(|b| (a.id, b.id)))
                .collect::<Vec<_>>()
        })
        .collect();
    pairs.sort_unstable();
    pairs
}

#[cfg(test)]
mod pair_diff_tests {
    use super::*;

    /// Missing and extra are found in unsorted input, and a duplicate in
    /// the other list is an extra.
    #[test]
    fn differences_are_multiset_differences() {
        let reference = [(1, 2), (0, 5), (3, 3)];
        let other = [(3, 3), (0, 5), (0, 5), (4, 4)];
        let diff = PairDiff::between(&reference, &other);
        assert_eq!(diff.missing, vec![(1, 2)]);
        assert_eq!(diff.extra, vec![(0, 5), (4, 4)]);
        assert!(PairDiff::between(&other, &other).is_empty());
    }
}
