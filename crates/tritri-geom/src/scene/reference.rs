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
/// whose triangle boxes overlap (found by a sweep over the boxes,
/// [`f64_pairs_on`]).
pub fn exact_f64_pairs(a: &[Triangle], b: &[Triangle]) -> ExactF64Result {
    f64_pairs_with(a, b, exact_f64::intersects)
}

/// [`exact_f64_pairs`] on `threads` threads (the same pairs, in the same
/// set): the sweep's scans split among them.
pub fn exact_f64_pairs_threads(a: &[Triangle], b: &[Triangle], threads: usize) -> ExactF64Result {
    f64_pairs_on(a, b, exact_f64::intersects, threads.max(1))
}

/// [`exact_f64_pairs`] with another decision function (for timing the
/// published float code on the same work).
pub fn f64_pairs_with(
    a: &[Triangle],
    b: &[Triangle],
    test: impl Fn(&Triangle, &Triangle) -> bool + Sync,
) -> ExactF64Result {
    f64_pairs_on(a, b, test, 1)
}

/// A triangle's box and its index, as the sweep keeps them.
#[derive(Clone, Copy)]
struct SweepBox {
    lo: [f64; 3],
    hi: [f64; 3],
    index: u32,
}

impl SweepBox {
    /// The box both boxes hold (empty on an axis where `lo > hi`).
    fn common(&self, other: &SweepBox) -> SweepBox {
        SweepBox {
            lo: std::array::from_fn(|k| self.lo[k].max(other.lo[k])),
            hi: std::array::from_fn(|k| self.hi[k].min(other.hi[k])),
            index: 0,
        }
    }

    /// The closed boxes overlap.
    #[inline(always)]
    fn meets(&self, other: &SweepBox) -> bool {
        (0..3).all(|k| self.lo[k] <= other.hi[k] && other.lo[k] <= self.hi[k])
    }
}

/// The boxes of `triangles` that meet `within` (closed boxes).
fn boxes_within(triangles: &[Triangle], within: &SweepBox) -> Vec<SweepBox> {
    triangles
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let bb = triangle_box(t);
            SweepBox {
                lo: bb.lo,
                hi: bb.hi,
                index: i as u32,
            }
        })
        .filter(|bb| bb.meets(within))
        .collect()
}

/// The box around `triangles` (`None` for none).
fn bounds(triangles: &[Triangle]) -> Option<SweepBox> {
    let bb = Aabb::of_triangles(triangles.iter())?;
    Some(SweepBox {
        lo: bb.lo,
        hi: bb.hi,
        index: 0,
    })
}

/// The axis to sweep along: the one where the fewest pairs of boxes are
/// expected to overlap, `(n_b Σ w_a + n_a Σ w_b) / L` with `w` the boxes'
/// widths and `L` the common box's, as if the boxes were spread evenly over
/// it. A sweep along the axis two objects in contact are side by side on
/// scans little more than the contact; along another it can scan most of
/// `n_a × n_b`.
fn sweep_axis(a: &[SweepBox], b: &[SweepBox], common: &SweepBox) -> usize {
    let expected = |k: usize| {
        let width = |boxes: &[SweepBox]| boxes.iter().map(|bb| bb.hi[k] - bb.lo[k]).sum::<f64>();
        let all = a.len() as f64 * b.len() as f64;
        let spread = common.hi[k] - common.lo[k];
        if spread > 0.0 {
            ((b.len() as f64 * width(a) + a.len() as f64 * width(b)) / spread).min(all)
        } else {
            all
        }
    };
    (0..3)
        .map(|k| (k, expected(k)))
        .fold(
            (0, f64::INFINITY),
            |best, (k, e)| if e < best.1 { (k, e) } else { best },
        )
        .0
}

/// The sweep behind [`exact_f64_pairs`]: only the triangles whose boxes
/// meet the common box of the two objects (no other can meet a triangle of
/// the other object), swept along [`sweep_axis`] by the one-way scan of
/// Zomorodian and Edelsbrunner (the step at the leaves of CGAL's
/// `box_intersection_d`) on both sides: both sets sorted by their boxes'
/// low end, each box scans the other set's boxes that start inside its
/// extent, an A box the B boxes starting no lower, a B box the A boxes
/// starting strictly higher, so each pair of boxes overlapping on the axis
/// is met exactly once, whatever the boxes' widths. Thread `k` of
/// `threads` takes the boxes `k, k + threads, ...` of each sorted set.
fn f64_pairs_on(
    a: &[Triangle],
    b: &[Triangle],
    test: impl Fn(&Triangle, &Triangle) -> bool + Sync,
    threads: usize,
) -> ExactF64Result {
    let mut result = ExactF64Result {
        pairs: PairSet::new(),
        pairs_decided: 0,
    };
    let (Some(bounds_a), Some(bounds_b)) = (bounds(a), bounds(b)) else {
        return result;
    };
    let mut boxes_a = boxes_within(a, &bounds_b);
    let mut boxes_b = boxes_within(b, &bounds_a);
    let common = bounds_a.common(&bounds_b);
    let axis = sweep_axis(&boxes_a, &boxes_b, &common);
    boxes_a.sort_unstable_by(|x, y| x.lo[axis].total_cmp(&y.lo[axis]));
    boxes_b.sort_unstable_by(|x, y| x.lo[axis].total_cmp(&y.lo[axis]));
    let (boxes_a, boxes_b) = (&boxes_a, &boxes_b);
    let test = &test;
    let part = move |k: usize| {
        let mut hits = Vec::new();
        let mut decided = 0u64;
        let mut decide = |x: &SweepBox, y: &SweepBox| {
            if x.meets(y) {
                decided += 1;
                if test(&a[x.index as usize], &b[y.index as usize]) {
                    hits.push((x.index, y.index));
                }
            }
        };
        // Each scan's first candidate, advanced as the scanning boxes rise.
        let mut first = 0;
        for x in boxes_a.iter().skip(k).step_by(threads) {
            while first < boxes_b.len() && boxes_b[first].lo[axis] < x.lo[axis] {
                first += 1;
            }
            for y in boxes_b[first..]
                .iter()
                .take_while(|y| y.lo[axis] <= x.hi[axis])
            {
                decide(x, y);
            }
        }
        let mut first = 0;
        for y in boxes_b.iter().skip(k).step_by(threads) {
            while first < boxes_a.len() && boxes_a[first].lo[axis] <= y.lo[axis] {
                first += 1;
            }
            for x in boxes_a[first..]
                .iter()
                .take_while(|x| x.lo[axis] <= y.hi[axis])
            {
                decide(x, y);
            }
        }
        (hits, decided)
    };
    let parts: Vec<(Vec<(u32, u32)>, u64)> = if threads == 1 {
        vec![part(0)]
    } else {
        // Part 0 on this thread, the others on threads of their own.
        std::thread::scope(|s| {
            let handles: Vec<_> = (1..threads).map(|k| s.spawn(move || part(k))).collect();
            let mut parts = vec![part(0)];
            parts.extend(
                handles
                    .into_iter()
                    .map(|h| h.join().expect("sweep thread panicked")),
            );
            parts
        })
    };
    for (hits, decided) in parts {
        result.pairs.extend(hits);
        result.pairs_decided += decided;
    }
    result
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

#[cfg(test)]
mod sweep_tests {
    use super::*;
    use crate::triangle::Point;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Triangles with corners on a small lattice around `centre`: many
    /// boxes share an end (ties in the sort, boxes that only touch), some
    /// triangles are degenerate. `spread` scales where the triangles sit,
    /// not their size.
    fn lattice_triangles(
        rng: &mut ChaCha8Rng,
        n: usize,
        centre: [i32; 3],
        spread: [f64; 3],
    ) -> Vec<Triangle> {
        (0..n)
            .map(|_| {
                let p: Point = std::array::from_fn(|k| {
                    (centre[k] + rng.gen_range(-6..=6)) as f64 * 0.5 * spread[k]
                });
                let near = |rng: &mut ChaCha8Rng| -> Point {
                    std::array::from_fn(|k| p[k] + rng.gen_range(-2..=2) as f64 * 0.5)
                };
                [p, near(rng), near(rng)]
            })
            .collect()
    }

    /// The sweep finds what testing every pair finds, and decides exactly
    /// the pairs whose boxes overlap, on one to three threads, with the
    /// objects side by side along each axis in turn (so each axis is swept).
    #[test]
    fn the_sweep_is_every_pair_tested() {
        let mut rng = ChaCha8Rng::seed_from_u64(66);
        for offset in [[4, 0, 0], [0, 4, 0], [0, 0, 4], [0, 0, 0], [40, 0, 0]] {
            let a = lattice_triangles(&mut rng, 300, [0, 0, 0], [1.0; 3]);
            let b = lattice_triangles(&mut rng, 200, offset, [1.0; 3]);
            let mut every = PairSet::new();
            let mut boxes = 0;
            for (i, x) in a.iter().enumerate() {
                for (j, y) in b.iter().enumerate() {
                    if triangle_box(x).overlap(&triangle_box(y)).is_some() {
                        boxes += 1;
                        if exact_f64::intersects(x, y) {
                            every.insert((i as u32, j as u32));
                        }
                    }
                }
            }
            for threads in 1..=3 {
                let swept = exact_f64_pairs_threads(&a, &b, threads);
                assert_eq!(swept.pairs, every, "offset {offset:?}, {threads} threads");
                assert_eq!(
                    swept.pairs_decided, boxes,
                    "offset {offset:?}, {threads} threads"
                );
            }
            if offset != [40, 0, 0] {
                assert!(every.len() > 20, "offset {offset:?}: {} pairs", every.len());
            }
        }
        assert!(
            exact_f64_pairs(&[], &lattice_triangles(&mut rng, 5, [0; 3], [1.0; 3]))
                .pairs
                .is_empty()
        );
    }

    /// Objects spread along one axis (small triangles over a long extent)
    /// are swept along it, where the fewest pairs of boxes overlap.
    #[test]
    fn the_sweep_runs_along_the_axis_the_boxes_spread_on() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for axis in 0..3 {
            let spread = std::array::from_fn(|k| if k == axis { 8.0 } else { 1.0 });
            let a = lattice_triangles(&mut rng, 200, [0, 0, 0], spread);
            let b = lattice_triangles(&mut rng, 200, [1, 1, 1], spread);
            let (ba, bb) = (bounds(&a).unwrap(), bounds(&b).unwrap());
            let common = ba.common(&bb);
            let (xa, xb) = (boxes_within(&a, &bb), boxes_within(&b, &ba));
            let on = |k: usize| {
                xa.iter()
                    .flat_map(|x| xb.iter().map(move |y| (x, y)))
                    .filter(|(x, y)| x.lo[k] <= y.hi[k] && y.lo[k] <= x.hi[k])
                    .count()
            };
            let counts = [on(0), on(1), on(2)];
            assert_eq!(
                counts.iter().min(),
                Some(&counts[axis]),
                "spread along {axis}: {counts:?}"
            );
            assert_eq!(
                sweep_axis(&xa, &xb, &common),
                axis,
                "spread along {axis}: {counts:?}"
            );
        }
    }
}
