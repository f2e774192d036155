//! Test vectors that every engine runs, so the rust-hdl harness, Icarus and
//! Verilator are compared with the model on the very same pairs.

use crate::stream::{all_orderings, PairGroup};
use tritri_geom::hard_cases::hard_case_suite;
use tritri_geom::quantize::quantize_pair;

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
