//! Direct drive of the collision system's rust-hdl model (docs/ARCHITECTURE.md, conventions: set
//! the inputs, settle, clock; no `simple_sim!` threads), with a host that
//! writes batches and reads pairs.
//!
//! Host behaviour, cycle by cycle (the same in the Verilog testbench
//! `testbenches/tb_collision_system.sv`): after two reset cycles, cycle 0
//! presents the first word. A word is presented until it is accepted
//! (`in_valid & in_ready`), then the next one in the next cycle. A batch is
//! its A triangles, its B triangles, then the end-of-batch word. With
//! `overlap` the next batch follows at once (into the other bank); without,
//! the host waits until it sees `done` in a cycle after the batch's
//! end-of-batch word and starts in the cycle after that. `out_ready` follows
//! the [`ReaderBehaviour`]; a pair is taken in a cycle with
//! `out_valid & out_ready`.
//!
//! `cycles` is the index of the first cycle after the last end-of-batch word
//! in which `done` is high (as [`system_cycles`] predicts); the run goes on
//! until the result FIFO is empty, so every pair is collected.

pub use crate::system_rtl::PROGRESS_PERIOD;
use rust_hdl::prelude::*;
pub use tritri_geom::scene::{Batch, TaggedTriangle};
use tritri_rtl::sim_drive::MAX_DELTA_CYCLES;
pub use tritri_rtl::system::cycle_model::{system_cycles, BatchSizes, ReaderBehaviour};
use tritri_rtl::system::host_ports::{HostInputs, HostOutputs, HostPorts};
use tritri_rtl::system::system_for_width::system_for_config;
pub use tritri_rtl::system::system_for_width::PipelineKind;
pub use tritri_rtl::system::SystemConfig;

/// What a run returns.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SystemResult {
    /// The intersecting pairs (`out_hit`), `(id_a, id_b)` in the order the
    /// result stream delivered them.
    pub pairs: Vec<(u32, u32)>,
    /// The pairs without a certificate (`out_certain = 0`), intersecting on
    /// the grid or not, in the order delivered.
    pub uncertain: Vec<(u32, u32)>,
    /// From the first write to `done` (module docs).
    pub cycles: u64,
    pub pairs_tested: u64,
    pub hits: u64,
    pub stall_cycles: u64,
    /// The sticky overflow flag (an array exceeded the memory depth).
    pub overflow: bool,
}

impl SystemResult {
    /// One pair of the result stream.
    pub fn record(&mut self, id_a: u32, id_b: u32, hit: bool, certain: bool) {
        if hit {
            self.pairs.push((id_a, id_b));
        }
        if !certain {
            self.uncertain.push((id_a, id_b));
        }
    }
}

/// One word of the host stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HostWord {
    pub end: bool,
    pub object_b: bool,
    pub id: u32,
    pub coordinates: [i64; 9],
}

/// The host stream of a batch: A, then B, then the end-of-batch word.
pub fn host_words(batch: &Batch) -> Vec<HostWord> {
    let word = |t: &TaggedTriangle, object_b| HostWord {
        end: false,
        object_b,
        id: t.id,
        coordinates: tritri_rtl::pipeline::pipeline_for_width::flatten(&t.triangle),
    };
    let mut words: Vec<HostWord> = batch.a.iter().map(|t| word(t, false)).collect();
    words.extend(batch.b.iter().map(|t| word(t, true)));
    words.push(HostWord {
        end: true,
        object_b: false,
        id: 0,
        coordinates: [0; 9],
    });
    words
}

impl ReaderBehaviourExt for ReaderBehaviour {
    fn ready(&self, cycle: u64) -> bool {
        match *self {
            ReaderBehaviour::AlwaysReady => true,
            ReaderBehaviour::OneIn(k) => k <= 1 || cycle % k as u64 == k as u64 - 1,
        }
    }
}

/// `out_ready` of a reader in a cycle.
pub trait ReaderBehaviourExt {
    fn ready(&self, cycle: u64) -> bool;
}

/// Reset cycles before cycle 0.
pub const RESET_CYCLES: u64 = 2;

/// Runs the batches through the system with real pipelines, the host
/// overlapping each batch's writes with the previous batch's tests.
/// `config.pipeline_latency` must be the pipeline's latency
/// (`tritri_rtl::pipeline::triangle_pipeline::latency()`).
pub fn run_system(
    config: SystemConfig,
    batches: &[Batch],
    reader: ReaderBehaviour,
) -> anyhow::Result<SystemResult> {
    run_system_with(config, PipelineKind::Parallel, batches, true, reader)
}

/// Runs the batches through a fresh system of `kind` for `config`.
pub fn run_system_with(
    config: SystemConfig,
    kind: PipelineKind,
    batches: &[Batch],
    overlap: bool,
    reader: ReaderBehaviour,
) -> anyhow::Result<SystemResult> {
    run_system_reporting(config, kind, batches, overlap, reader, &|_| {})
}

/// [`run_system_with`], telling `progress` the cycles simulated since its
/// last call, every [`PROGRESS_PERIOD`] cycles.
pub fn run_system_reporting(
    config: SystemConfig,
    kind: PipelineKind,
    batches: &[Batch],
    overlap: bool,
    reader: ReaderBehaviour,
    progress: &dyn Fn(u64),
) -> anyhow::Result<SystemResult> {
    let mut uut = system_for_config(config, kind)?;
    run_system_on(uut.as_mut(), batches, overlap, reader, progress)
}

/// Runs the batches through a system with stub pipelines.
pub fn run_stub_system(
    config: SystemConfig,
    batches: &[Batch],
    overlap: bool,
    reader: ReaderBehaviour,
) -> SystemResult {
    run_system_with(config, PipelineKind::Stub, batches, overlap, reader)
        .expect("a supported width")
}

/// Runs the batches through `uut` (connected or not) and collects the
/// pairs; `progress` as in [`run_system_reporting`]. A system that does
/// not finish within a generous budget of cycles is an error (a bug).
pub fn run_system_on<S: HostPorts + ?Sized>(
    uut: &mut S,
    batches: &[Batch],
    overlap: bool,
    reader: ReaderBehaviour,
    progress: &dyn Fn(u64),
) -> anyhow::Result<SystemResult> {
    let config = uut.system_config();
    uut.connect_all();
    let words: Vec<Vec<HostWord>> = batches.iter().map(host_words).collect();
    let sizes: Vec<BatchSizes> = batches.iter().map(BatchSizes::of).collect();
    let budget = 4 * system_cycles(config, &sizes, false, ReaderBehaviour::AlwaysReady)
        + 16 * batches.iter().map(|b| b.a.len() * b.b.len()).sum::<usize>() as u64
            * match reader {
                ReaderBehaviour::AlwaysReady => 1,
                ReaderBehaviour::OneIn(k) => k.max(1) as u64,
            }
        + 10_000;

    let mut inputs = HostInputs {
        reset: true,
        ..Default::default()
    };
    for _ in 0..RESET_CYCLES {
        uut.set_inputs(&inputs);
        settle(uut);
        tick(uut);
    }
    inputs.reset = false;

    let mut result = SystemResult::default();
    let (mut batch, mut position) = (0usize, 0usize);
    let mut waiting_for_done = false;
    let mut done_cycle: Option<u64> = None;
    let mut cycle = 0u64;
    loop {
        let all_written = batch == words.len();
        let word = if all_written || waiting_for_done {
            None
        } else {
            Some(words[batch][position])
        };
        inputs.in_valid = word.is_some();
        if let Some(w) = word {
            inputs.in_end = w.end;
            inputs.in_object = w.object_b;
            inputs.in_id = w.id;
            inputs.in_coordinates = w.coordinates;
        } else {
            inputs.in_end = false;
            inputs.in_object = false;
            inputs.in_id = 0;
            inputs.in_coordinates = [0; 9];
        }
        inputs.out_ready = reader.ready(cycle);
        uut.set_inputs(&inputs);
        settle(uut);
        let out: HostOutputs = uut.outputs();

        if out.out_valid && inputs.out_ready {
            result.record(out.out_id_a, out.out_id_b, out.out_hit, out.out_certain);
        }
        if all_written && done_cycle.is_none() && out.done {
            done_cycle = Some(cycle);
        }
        if waiting_for_done && out.done {
            waiting_for_done = false;
        }
        if let Some(w) = word {
            if out.in_ready {
                position += 1;
                if w.end {
                    batch += 1;
                    position = 0;
                    waiting_for_done = !overlap;
                }
            }
        }
        if let (Some(done), true, false) = (done_cycle, out.results_empty, out.out_valid) {
            result.cycles = done;
            result.pairs_tested = out.pairs_tested as u64;
            result.hits = out.hits as u64;
            result.stall_cycles = out.stall_cycles as u64;
            result.overflow = out.overflow;
            progress(cycle % PROGRESS_PERIOD);
            return Ok(result);
        }
        tick(uut);
        cycle += 1;
        if cycle % PROGRESS_PERIOD == 0 {
            progress(PROGRESS_PERIOD);
        }
        anyhow::ensure!(
            cycle < budget,
            "the system did not finish within {budget} cycles (a bug)"
        );
    }
}

/// Propagates until nothing changes (`sim_drive::settle` for unsized tops).
fn settle<S: HostPorts + ?Sized>(uut: &mut S) {
    for _ in 0..MAX_DELTA_CYCLES {
        uut.update_all();
        if !uut.has_changed() {
            return;
        }
    }
    panic!("the system did not settle within {MAX_DELTA_CYCLES} delta cycles");
}

/// One clock period: rising edge, settle, falling edge, settle.
fn tick<S: HostPorts + ?Sized>(uut: &mut S) {
    uut.clock_signal().next = Clock { clk: true };
    settle(uut);
    uut.clock_signal().next = Clock { clk: false };
    settle(uut);
}
