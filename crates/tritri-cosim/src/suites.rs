//! Test vectors that every engine runs, so the rust-hdl harness, Icarus and
//! Verilator are compared with the model on the very same pairs.

use crate::stream::{all_orderings, PairGroup};
use tritri_geom::hard_cases::hard_case_suite;
use tritri_geom::quantize::quantize_pair;

/// Every how-many-th hard case the long co-simulations take (the rust-hdl
/// pipeline at three widths, the shared rare-case unit in three engines):
/// `TRITRI_HARD_CASES=N`, 1 for the whole suite (what
/// `scripts/test-long.sh` runs), by default every 8th, so that the test
/// command stays within CI's hour. Every case still runs through the
/// models in `tritri-geom`'s tests.
pub fn hard_case_step() -> usize {
    const DEFAULT: usize = 8;
    match std::env::var("TRITRI_HARD_CASES") {
        Err(_) => DEFAULT,
        Ok(v) => v
            .parse::<usize>()
            .ok()
            .filter(|&n| n >= 1)
            .unwrap_or_else(|| {
                panic!("TRITRI_HARD_CASES={v}: a whole number from 1 (every case) up")
            }),
    }
}

/// The hard-case suite (`tritri_geom::hard_cases`: coplanar, touching,
/// near-degenerate, needles and slivers, ...) at `width` bits, every
/// `every`-th case, each quantized in a frame of its own (so the case keeps
/// as much of its geometry as W bits allow) and sent in all 72 orderings
/// (12 groups per case).
pub fn hard_case_groups(width: u32, every: usize) -> Vec<PairGroup> {
    hard_case_suite()
        .iter()
        .step_by(every.max(1))
        .flat_map(|case| {
            let (t1, t2) =
                quantize_pair(&case.pair, width).expect("the hard cases have finite coordinates");
            all_orderings(t1, t2)
        })
        .collect()
}

/// The number of cases in the hard-case suite.
pub fn hard_case_count() -> usize {
    hard_case_suite().len()
}
