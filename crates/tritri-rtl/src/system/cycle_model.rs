//! The exact cycle count of the collision system, derived from its state
//! machines ([`super::address_generator`]) and checked against the rust-hdl
//! simulation and the emitted Verilog (`tritri-cosim/tests/system_*.rs`).
//!
//! # What is counted
//!
//! Cycle 0 is the cycle of the host's first transfer; the count is the
//! index of the first cycle, after the last end-of-batch word, in which
//! `done` is high (so: the clock edges from the first write until `done` is
//! visible). The host writes one word per cycle while `in_ready` is high;
//! without overlap it starts batch `k + 1` in the cycle after it sees `done`
//! for batch `k`. The result reader is always ready and the result FIFO
//! never reaches its mark (`stall_cycles = 0`). While the FIFO is above its mark the
//! read side holds (the pipelines run on); `stall_cycles` counts the clocks
//! it holds while the system is busy (`done` low), so without overlap each
//! adds exactly one cycle, while with overlap it may be hidden by the
//! host's writes.
//!
//! # Formula
//!
//! A batch of `N1` A-triangles and `N2` B-triangles (`P` pipelines, latency
//! `L`) costs
//!
//! * `N1 + N2 + 1` write cycles (one per triangle, one end-of-batch word);
//! * 1 idle cycle in which the read state machine takes the bank;
//! * `I = N1 + ceil(N1 / P) · N2` read cycles (each group of up to `P`
//!   bases is loaded one per cycle, then B streams past all of them; `I = 0`
//!   when an array is empty);
//! * `M = 2` cycles of memory read latency
//!   ([`MEMORY_READ_LATENCY`](super::MEMORY_READ_LATENCY)), `L` cycles of
//!   pipeline latency after the last read and `K = 1` in which the last
//!   verdicts are counted ([`COUNT_LATENCY`](super::COUNT_LATENCY)), then
//!   `done` rises.
//!
//! One batch: `cycles = (N1 + N2 + 1) + 1 + N1 + ceil(N1 / P) · N2 + M + L + K`
//! (for `P = 1` the thesis's `N1 + N1 · N2 + L` plus the write phase and
//! four cycles); an empty batch costs `N1 + N2 + 2`. Without overlap the
//! batches add up, plus one cycle each for the host to see `done`. With
//! overlap the recurrence below applies: batch `k` is written while batch
//! `k − 1` is read, into the bank that batch `k − 2` released.
//!
//! ```text
//! S_k = C_{k-1} + 1                    (overlap: the host writes on)
//!     = D_{k-1} + 1                    (no overlap: after done)
//! T_k = max(S_k, R_{k-2} + 1)          first write: the bank is free
//! C_k = T_k + N1_k + N2_k              end-of-batch word accepted
//! Q_k = max(C_k + 1, R_{k-1} + 1)      idle cycle that takes the bank
//! R_k = Q_k + I_k                      last read; the bank is released
//! D   = max(R_last + 1, X + M + L + K + 1) X: the last cycle that read B
//! ```

use super::SystemConfig;
use tritri_geom::scene::octree::BatchCost;
use tritri_geom::scene::Batch;

/// The sizes of one batch: triangles of A (bases) and of B (streamed).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct BatchSizes {
    pub a: usize,
    pub b: usize,
}

impl BatchSizes {
    pub fn of(batch: &Batch) -> BatchSizes {
        BatchSizes {
            a: batch.a.len(),
            b: batch.b.len(),
        }
    }
}

/// The cycles of `batches` as a scene runs them: the banks alternate
/// (loading batch k+1 overlaps processing batch k), the reader is always
/// ready. What `tritri sim` reports and every engine must reproduce.
pub fn scene_cycles(config: SystemConfig, batches: &[Batch]) -> u64 {
    let sizes: Vec<BatchSizes> = batches.iter().map(BatchSizes::of).collect();
    system_cycles(config, &sizes, true, ReaderBehaviour::AlwaysReady)
}

/// How the host reads the result stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum ReaderBehaviour {
    /// `out_ready` is always high.
    #[default]
    AlwaysReady,
    /// `out_ready` is high in one cycle of every `k` (cycles `k-1, 2k-1, …`).
    OneIn(u32),
}

/// Read cycles of one batch: `N1 + ceil(N1 / P) · N2`, or 0 when an array
/// is empty (the bank is released without reading).
pub fn read_cycles(pipelines: usize, batch: BatchSizes) -> u64 {
    if batch.a == 0 || batch.b == 0 {
        0
    } else {
        let groups = batch.a.div_ceil(pipelines);
        (batch.a + groups * batch.b) as u64
    }
}

/// Triangle pairs a batch tests: `N1 · N2`.
pub fn pairs(batch: BatchSizes) -> u64 {
    (batch.a * batch.b) as u64
}

/// The cycles from the host's first write to `done` (module docs). Exact
/// when the result FIFO never reaches its mark; with a slower `reader` or dense hits
/// the hardware adds its `stall_cycles` (exactly, without overlap), so this
/// is then a lower bound.
pub fn system_cycles(
    config: SystemConfig,
    batches: &[BatchSizes],
    overlap: bool,
    reader: ReaderBehaviour,
) -> u64 {
    let _ = reader; // the always-ready reader never stalls the read side
    recurrence(config, batches, overlap, 0, 0).max(0) as u64
}

/// [`system_cycles`] with the banks overlapped, for a writer whose first
/// word can come at cycle `first` and which spends `gap` idle cycles
/// between a batch's end word and the next batch's first triangle (the
/// broad phase's leaf batcher: one, the clock of the leaf's header).
/// Returns the cycle in which `done` rises, counted like `first`.
pub fn streamed_system_cycles(
    config: SystemConfig,
    batches: &[BatchSizes],
    first: u64,
    gap: u64,
) -> u64 {
    recurrence(config, batches, true, first as i64, gap as i64).max(0) as u64
}

/// The module's recurrence: `S_0 = first`, `S_k = C_{k-1} + 1 + gap` with
/// overlap (else `D_{k-1} + 1`); returns `D`.
fn recurrence(
    config: SystemConfig,
    batches: &[BatchSizes],
    overlap: bool,
    first: i64,
    gap: i64,
) -> i64 {
    let latency = config.read_to_counted_cycles() as i64;
    // Cycle indices; -1 stands for "before cycle 0".
    let mut commit_previous: i64 = -1; // C_{k-1}
    let mut done_previous: i64 = -1; // D_{k-1}
    let mut release: [i64; 2] = [-1, -1]; // R_{k-2}, R_{k-1} by bank (k mod 2)
    let mut release_previous: i64 = -1; // R_{k-1}
    let mut last_stream_read: Option<i64> = None; // X
    let mut done = 0i64;
    for (k, &batch) in batches.iter().enumerate() {
        let start = if k == 0 {
            first
        } else if overlap {
            commit_previous + 1 + gap
        } else {
            done_previous + 1
        };
        let first_write = start.max(release[k % 2] + 1);
        let commit = first_write + (batch.a + batch.b) as i64;
        let take = (commit + 1).max(release_previous + 1);
        let reads = read_cycles(config.pipelines, batch) as i64;
        let last_read = take + reads;
        if reads > 0 {
            last_stream_read = Some(last_read);
        }
        release[k % 2] = last_read;
        release_previous = last_read;
        commit_previous = commit;
        done = (last_read + 1).max(last_stream_read.map_or(0, |x| x + latency + 1));
        done_previous = done;
    }
    done
}

/// What one batch adds to a long run with the banks overlapped: in the
/// recurrence, writing it (`N1 + N2 + 1`) hides behind reading the previous
/// batch and reading it (`1 + I`, the idle cycle and the reads) behind
/// writing the next, so the slower of the two sets the pace. The octree
/// broad phase decides its splits with this ([`BatchCost`]).
pub fn overlapped_batch_cycles(config: SystemConfig, batch: BatchSizes) -> u64 {
    let writes = (batch.a + batch.b + 1) as u64;
    writes.max(1 + read_cycles(config.pipelines, batch))
}

impl BatchCost for SystemConfig {
    fn batch_cycles(&self, a: usize, b: usize) -> u64 {
        overlapped_batch_cycles(*self, BatchSizes { a, b })
    }

    fn classify_cycles(&self, a: usize, b: usize) -> u64 {
        crate::broad_phase::binning_cost::cell_cycles(a as u64, b as u64)
    }
}

/// [`system_cycles`] of one batch in closed form.
pub fn single_batch_cycles(config: SystemConfig, batch: BatchSizes) -> u64 {
    let writes = (batch.a + batch.b + 1) as u64;
    let reads = read_cycles(config.pipelines, batch);
    if reads == 0 {
        writes + 1
    } else {
        writes + 1 + reads + config.read_to_counted_cycles() as u64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The recurrence agrees with the closed form on single batches, and
    /// without overlap the batches add up (plus one cycle each to see done).
    #[test]
    fn recurrence_matches_closed_forms() {
        for p in [1, 2, 4] {
            let config = SystemConfig::new(24, p).with_pipeline_latency(7);
            let sizes = [
                (0, 0),
                (0, 3),
                (3, 0),
                (1, 1),
                (5, 3),
                (4, 4),
                (9, 2),
                (2, 9),
            ];
            for &(a, b) in &sizes {
                let batch = BatchSizes { a, b };
                for overlap in [false, true] {
                    assert_eq!(
                        system_cycles(config, &[batch], overlap, ReaderBehaviour::AlwaysReady),
                        single_batch_cycles(config, batch)
                    );
                }
            }
            let batches: Vec<_> = sizes.iter().map(|&(a, b)| BatchSizes { a, b }).collect();
            let serial: u64 = batches
                .iter()
                .map(|&b| single_batch_cycles(config, b) + 1)
                .sum::<u64>()
                - 1;
            assert_eq!(
                system_cycles(config, &batches, false, ReaderBehaviour::AlwaysReady),
                serial
            );
            assert!(system_cycles(config, &batches, true, ReaderBehaviour::AlwaysReady) < serial);
        }
    }

    /// Thesis check: one batch, one pipeline: N1 + N1*N2 + L plus the write
    /// phase (N1 + N2 + 1) and four cycles (bank take-over, the memories'
    /// two read clocks, the counters' clock).
    #[test]
    fn one_pipeline_is_the_thesis_formula_plus_overheads() {
        let config = SystemConfig::new(24, 1).with_pipeline_latency(32);
        let (n1, n2) = (10u64, 20u64);
        let expected = (n1 + n2 + 1) + n1 + n1 * n2 + 32 + 4;
        assert_eq!(
            single_batch_cycles(config, BatchSizes { a: 10, b: 20 }),
            expected
        );
    }

    /// A scene's batches: loading the next batch hides behind processing
    /// the current one, two pipelines share the bases, no batch costs 0.
    #[test]
    fn scene_cycles_overlap_loading_and_share_the_bases() {
        use tritri_geom::scene::TaggedTriangle;
        let ts = vec![
            TaggedTriangle {
                id: 0,
                triangle: [[0; 3]; 3]
            };
            10
        ];
        let batch = Batch { a: &ts, b: &ts };
        let config = |p| SystemConfig::new(24, p).with_pipeline_latency(30);
        let one = scene_cycles(config(1), &[batch]);
        assert_eq!(one, single_batch_cycles(config(1), BatchSizes::of(&batch)));
        assert!(scene_cycles(config(1), &[batch, batch]) < 2 * one);
        assert!(scene_cycles(config(2), &[batch]) < one - 40);
        assert_eq!(scene_cycles(config(1), &[]), 0);
    }
}
