//! The cycle model against the hardware, with stub pipelines (so many batch
//! shapes run in well under a second). Property: for P = 1, 2, 4, with and
//! without bank overlap, the cycles the rust-hdl system takes from the first
//! host write to `done` equal `cycle_model::system_cycles` exactly; and the
//! pairs are all pairs of each batch under the stub's verdict (0 missing,
//! 0 extra), with matching counters and no stall.

mod system_common;

use tritri_cosim::system_harness::*;
use tritri_geom::scene::reference::{pairs_where, PairDiff};
use tritri_rtl::system::stub_pipeline::stub_hit;

#[test]
fn cycles_equal_the_model_for_p_1_2_4_with_and_without_overlap() {
    let mut rng = system_common::rng(1);
    // Includes empty arrays, single triangles, a full bank (8) and groups
    // that do not divide by P.
    let shapes = [
        (5, 3),
        (0, 4),
        (7, 6),
        (1, 1),
        (4, 0),
        (8, 8),
        (3, 5),
        (0, 0),
        (6, 2),
    ];
    let arrays = system_common::random_arrays(&mut rng, &shapes, 24, 1000);
    let batches = system_common::batches(&arrays);
    let expected = pairs_where(&batches, |a, b| {
        stub_hit(a.id, a.triangle[0][0], b.id, b.triangle[2][2])
    });
    let sizes: Vec<_> = batches.iter().map(BatchSizes::of).collect();
    let tested: u64 = sizes.iter().map(|s| (s.a * s.b) as u64).sum();
    for latency in [1, 9] {
        for p in [1, 2, 4] {
            for overlap in [false, true] {
                let config = SystemConfig::new(24, p)
                    .with_pipeline_latency(latency)
                    .with_depth(8)
                    .with_result_fifo_depth(16);
                let r = run_stub_system(config, &batches, overlap, ReaderBehaviour::AlwaysReady);
                let model = system_cycles(config, &sizes, overlap, ReaderBehaviour::AlwaysReady);
                let (missing, extra) = PairDiff::between(&expected, &r.pairs).counts();
                eprintln!(
                    "L={latency} P={p} overlap={overlap}: cycles {} model {model}, pairs {} missing {missing} extra {extra}",
                    r.cycles,
                    r.pairs.len()
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
}
