//! The system with the real Devillers–Guigue pipelines on a small scene (a
//! torus and a sphere in contact, filtered to the common bounding volume,
//! quantized to 24 bits, tiled into batches of at most 8 triangles per
//! array). Property: for P = 1, 2, 4, with and without bank overlap, the
//! pairs it returns are exactly the pairs of each batch's arrays for which
//! `fixed_point::intersects` holds (0 missing, 0 extra), the counters agree
//! (pairs tested = sum of N1·N2, hits = pairs), and the cycle count equals
//! the cycle model.

mod system_common;

use std::time::Instant;
use tritri_cosim::system_harness::*;
use tritri_geom::fixed_point::intersects;
use tritri_geom::scene::reference::{pairs_where, PairDiff};

#[test]
fn real_pipelines_return_exactly_the_intersecting_pairs() {
    let (a, b) = system_common::small_scene(24, 12, 6);
    let batches = tritri_geom::scene::tile(&a, &b, 8);
    let expected = pairs_where(&batches, |x, y| intersects(&x.triangle, &y.triangle));
    let sizes: Vec<_> = batches.iter().map(BatchSizes::of).collect();
    let tested: u64 = sizes.iter().map(|s| (s.a * s.b) as u64).sum();
    eprintln!(
        "scene: {} A and {} B triangles in the common box, {} batches, {tested} pairs, {} hits",
        a.len(),
        b.len(),
        batches.len(),
        expected.len()
    );
    assert!(!expected.is_empty());
    for p in [1, 2, 4] {
        for overlap in [false, true] {
            let config = SystemConfig::new(24, p)
                .with_depth(8)
                .with_result_fifo_room(16);
            let started = Instant::now();
            let r = run_system_with(
                config,
                PipelineKind::Parallel,
                &batches,
                overlap,
                ReaderBehaviour::AlwaysReady,
            )
            .unwrap();
            let (missing, extra) = PairDiff::between(&expected, &r.pairs).counts();
            let model = system_cycles(config, &sizes, overlap, ReaderBehaviour::AlwaysReady);
            eprintln!(
                "P={p} overlap={overlap}: pairs {} missing {missing} extra {extra}, cycles {} model {model}, \
                 stalls {} ({:.2} s)",
                r.pairs.len(),
                r.cycles,
                r.stall_cycles,
                started.elapsed().as_secs_f64()
            );
            assert_eq!((missing, extra), (0, 0));
            assert_eq!(
                (r.hits as usize, r.pairs_tested, r.stall_cycles),
                (expected.len(), tested, 0)
            );
            assert_eq!(r.cycles, model);
        }
    }
}

/// A batch with more triangles of A and of B than a bank holds: the system
/// raises the sticky `overflow`, tests the first `depth` triangles of each
/// array (exactly their pairs come back) and drops the rest, and the next
/// batch, in the other bank, is tested whole.
#[test]
fn arrays_over_the_depth_set_overflow_and_keep_their_first_triangles() {
    use tritri_geom::scene::Batch;
    let depth = 8;
    let (a, b) = system_common::small_scene(24, 12, 6);
    assert!(
        a.len() > depth && b.len() > depth,
        "{} {}",
        a.len(),
        b.len()
    );
    let over = Batch {
        a: &a[..a.len().min(depth + 3)],
        b: &b[..b.len().min(depth + 2)],
    };
    let kept = Batch {
        a: &a[..depth],
        b: &b[..depth],
    };
    let expected = pairs_where(&[kept, kept], |x, y| intersects(&x.triangle, &y.triangle));
    assert!(!expected.is_empty());
    let config = SystemConfig::new(24, 2)
        .with_depth(depth)
        .with_result_fifo_room(16);
    let r = run_system_with(
        config,
        PipelineKind::Parallel,
        &[over, kept],
        true,
        ReaderBehaviour::AlwaysReady,
    )
    .unwrap();
    assert!(r.overflow);
    assert_eq!(PairDiff::between(&expected, &r.pairs).counts(), (0, 0));
    assert_eq!(r.pairs_tested, 2 * (depth * depth) as u64);
}
