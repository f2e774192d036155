//! The collision system with stub pipelines (memories, address generator,
//! result FIFO and serializer, checked independently of the arithmetic).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_cosim::stream::IdTriangle;
use tritri_cosim::system_harness::*;
use tritri_rtl::system::stub_pipeline::stub_hit;

fn random_batch(rng: &mut ChaCha8Rng, a: usize, b: usize, next_id: &mut u32) -> Batch {
    let mut tri = |rng: &mut ChaCha8Rng| {
        let mut t = [[0i64; 3]; 3];
        for v in t.iter_mut() {
            for c in v.iter_mut() {
                *c = rng.gen_range(-(1i64 << 23)..(1i64 << 23));
            }
        }
        *next_id += 1;
        IdTriangle { id: *next_id * 7 + 1000, triangle: t }
    };
    Batch { a: (0..a).map(|_| tri(rng)).collect(), b: (0..b).map(|_| tri(rng)).collect() }
}

fn stub_intersects(a: &IdTriangle, b: &IdTriangle) -> bool {
    stub_hit(a.id, a.triangle[0][0], b.id, b.triangle[2][2])
}

/// Pairs == all pairs of each batch under the stub verdict; cycles == model.
#[test]
fn stub_system_pairs_and_cycles() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut id = 0;
    let sizes = [(5, 3), (0, 4), (7, 6), (1, 1), (4, 0), (9, 5)];
    let batches: Vec<Batch> = sizes.iter().map(|&(a, b)| random_batch(&mut rng, a, b, &mut id)).collect();
    for p in [1, 2, 4] {
        for overlap in [false, true] {
            let config = SystemConfig::new(24, p, 5).with_depth(16).with_result_fifo_depth(16);
            let r = run_stub_system(config, &batches, overlap, ReaderBehaviour::AlwaysReady);
            let expected = expected_pairs(&batches, stub_intersects);
            let (missing, extra) = pair_differences(&r.pairs, &expected);
            let sizes: Vec<_> = batches.iter().map(Batch::sizes).collect();
            let model = system_cycles(config, &sizes, overlap, ReaderBehaviour::AlwaysReady);
            eprintln!("P={p} overlap={overlap}: pairs {} missing {missing} extra {extra} cycles {} model {model} stalls {} tested {}", r.pairs.len(), r.cycles, r.stall_cycles, r.pairs_tested);
            assert_eq!((missing, extra), (0, 0));
            assert_eq!(r.hits as usize, expected.len());
            assert_eq!(r.pairs_tested, sizes.iter().map(|s| (s.a * s.b) as u64).sum::<u64>());
            assert_eq!(r.stall_cycles, 0);
            assert_eq!(r.cycles, model);
        }
    }
}
