//! Back-pressure: a result FIFO with two words of room above its reserve of
//! `L` words (the pairs in flight) and a reader that takes one pair in seven
//! cycles. Property: no result is lost (pairs == all pairs under the stub
//! verdict, 0 missing, 0 extra), the read side did stall (stall counter >
//! 0), and without overlap every stall cycle adds exactly one cycle to the
//! model's count.

mod system_common;

use tritri_cosim::system_harness::*;
use tritri_geom::scene::reference::{pairs_where, PairDiff};
use tritri_rtl::system::stub_pipeline::stub_hit;

#[test]
fn tiny_fifo_slow_reader_loses_nothing() {
    let mut rng = system_common::rng(7);
    let arrays = system_common::random_arrays(&mut rng, &[(6, 8), (5, 7), (8, 3)], 24, 100);
    let batches = system_common::batches(&arrays);
    let expected = pairs_where(&batches, |a, b| {
        stub_hit(a.id, a.triangle[0][0], b.id, b.triangle[2][2])
    });
    let sizes: Vec<_> = batches.iter().map(BatchSizes::of).collect();
    for p in [1, 2, 4] {
        for overlap in [false, true] {
            let config = SystemConfig::new(24, p)
                .with_pipeline_latency(6)
                .with_depth(8)
                .with_result_fifo_room(2);
            let r = run_stub_system(config, &batches, overlap, ReaderBehaviour::OneIn(7));
            let (missing, extra) = PairDiff::between(&expected, &r.pairs).counts();
            let model = system_cycles(config, &sizes, overlap, ReaderBehaviour::AlwaysReady);
            eprintln!(
                "P={p} overlap={overlap}: pairs {} (expected {}), missing {missing}, extra {extra}, \
                 stalls {}, cycles {} (model without stalls {model})",
                r.pairs.len(),
                expected.len(),
                r.stall_cycles,
                r.cycles
            );
            assert_eq!((missing, extra), (0, 0));
            assert_eq!(r.hits as usize, expected.len());
            assert!(r.stall_cycles > 0);
            if !overlap {
                assert_eq!(r.cycles, model + r.stall_cycles);
            } else {
                assert!(r.cycles >= model);
            }
        }
    }
}

/// The same with the real pipelines (P = 4) on the small torus/sphere scene.
#[test]
fn tiny_fifo_slow_reader_loses_nothing_with_real_pipelines() {
    let (a, b) = system_common::small_scene(24, 12, 6);
    let batches = tritri_geom::scene::tile(&a, &b, 8);
    let expected = pairs_where(&batches, |x, y| {
        tritri_geom::fixed_point::intersects(&x.triangle, &y.triangle)
    });
    let config = SystemConfig::new(24, 4)
        .with_depth(8)
        .with_result_fifo_room(2);
    let r = run_system_with(
        config,
        PipelineKind::Parallel,
        &batches,
        true,
        ReaderBehaviour::OneIn(7),
    )
    .unwrap();
    let (missing, extra) = PairDiff::between(&expected, &r.pairs).counts();
    eprintln!(
        "real P=4: pairs {} (expected {}), missing {missing}, extra {extra}, stalls {}",
        r.pairs.len(),
        expected.len(),
        r.stall_cycles
    );
    assert_eq!((missing, extra), (0, 0));
    assert!(r.stall_cycles > 0);
}
