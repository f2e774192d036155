//! Back-pressure: a result FIFO of two words and a reader that takes one
//! pair in seven cycles. Property: no result is lost (pairs == all pairs
//! under the stub verdict, 0 missing, 0 extra), the pipelines did stall
//! (stall counter > 0), and without overlap every stall cycle adds exactly
//! one cycle to the model's count.

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
        IdTriangle { id: *next_id, triangle: t }
    };
    Batch { a: (0..a).map(|_| tri(rng)).collect(), b: (0..b).map(|_| tri(rng)).collect() }
}

#[test]
fn tiny_fifo_slow_reader_loses_nothing() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut id = 0;
    let batches: Vec<Batch> =
        [(6, 8), (5, 7), (8, 3)].iter().map(|&(a, b)| random_batch(&mut rng, a, b, &mut id)).collect();
    let expected = expected_pairs(&batches, |a, b| stub_hit(a.id, a.triangle[0][0], b.id, b.triangle[2][2]));
    let sizes: Vec<_> = batches.iter().map(Batch::sizes).collect();
    for p in [1, 2, 4] {
        for overlap in [false, true] {
            let config = SystemConfig::new(24, p, 6).with_depth(8).with_result_fifo_depth(2);
            let r = run_stub_system(config, &batches, overlap, ReaderBehaviour::OneIn(7));
            let (missing, extra) = pair_differences(&r.pairs, &expected);
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
