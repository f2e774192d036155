//! The route from work to verdicts, as a library: one [`Engine`] names what
//! computes them, and one function per kind of work runs it and returns one
//! report.
//!
//! * [`run_pipeline`]: a schedule of input cycles through one triangle
//!   pipeline (what `tritri classify` and `tritri bench` run);
//! * [`run_scene`]: a prepared scene's batches through the whole system
//!   (memories, address generator, P pipelines, result FIFO), plus the
//!   pairs the host decides (what `tritri sim` and `tritri demo` run);
//! * [`check_quantized`]: the comparison every scene run ends with, the
//!   exact model on the same quantized coordinates.
//!
//! ```
//! use tritri_cosim::engine::{run_scene, Engine, SceneRunOptions};
//! use tritri_geom::scene::{load::load_object, prepare, SceneOptions};
//! use tritri_rtl::system::SystemConfig;
//! let (a, b) = (load_object("@torus", 8).unwrap(), load_object("@sphere", 8).unwrap());
//! let scene = prepare(&a, &b, &SceneOptions { grid_bits: 24, depth: 256, split: true }).unwrap();
//! let config = SystemConfig::new(24, 2).with_depth(256);
//! let run = run_scene(Engine::Model, &scene, config, &SceneRunOptions::default()).unwrap();
//! assert_eq!(run.cycles, run.model_cycles);
//! ```

use crate::fault::Fault;
use crate::owner_filter;
use crate::pipeline_rtl;
use crate::rusthdl_harness::{run_schedule_on, HarnessOptions};
use crate::simulator::Simulator;
use crate::stream::{PairVerdict, StreamResult};
use crate::system_harness::{run_system_reporting, PipelineKind, ReaderBehaviour, SystemResult};
use crate::system_rtl::{run_system_rtl_with, SystemRunOptions};
use std::path::Path;
use std::time::Instant;
use tritri_geom::certificate::{certified_intersects, CertifiedVerdict};
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::scene::owner_slots::OwnerSlots;
use tritri_geom::scene::reference::{fixed_point_pairs, quantized_exact_pairs, PairDiff, PairSet};
use tritri_geom::scene::{Batch, PreparedScene};
use tritri_rtl::pipeline::pipeline_for_width::{pipeline_for_width, PipelineInput};
use tritri_rtl::pipeline::triangle_pipeline::latency;
use tritri_rtl::pipeline::RareCasePath;
use tritri_rtl::system::cycle_model::scene_cycles;
use tritri_rtl::system::SystemConfig;

/// What computes the verdicts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, clap::ValueEnum)]
pub enum Engine {
    /// The bit-exact fixed-point model (and, for a scene, the system's
    /// exact cycle model).
    Model,
    /// The rust-hdl hardware, simulated cycle by cycle (slow).
    Rusthdl,
    /// The emitted Verilog in Icarus Verilog (cycle by cycle; slow).
    Icarus,
    /// The emitted Verilog in Verilator (cycle by cycle).
    Verilator,
}

impl Engine {
    /// The name the command line uses.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Model => "model",
            Engine::Rusthdl => "rusthdl",
            Engine::Icarus => "icarus",
            Engine::Verilator => "verilator",
        }
    }

    /// The simulator of emitted Verilog, for the two engines that run it.
    pub fn simulator(self) -> Option<Simulator> {
        match self {
            Engine::Icarus => Some(Simulator::Icarus),
            Engine::Verilator => Some(Simulator::Verilator),
            Engine::Model | Engine::Rusthdl => None,
        }
    }

    /// What [`run_scene`]'s progress counts: pairs decided by the model,
    /// cycles simulated by a hardware engine.
    pub fn progress_unit(self) -> &'static str {
        if self.is_hardware() {
            "cycles"
        } else {
            "pairs"
        }
    }

    /// Whether the engine simulates hardware (and so needs a width that
    /// has a generated pipeline).
    pub fn is_hardware(self) -> bool {
        self != Engine::Model
    }

    /// What the engine is, for a report.
    pub fn describe(self) -> &'static str {
        match self {
            Engine::Model => "model (bit-exact fixed-point model; cycle model of the system)",
            Engine::Rusthdl => "rusthdl (rust-hdl simulation of the hardware)",
            Engine::Icarus => "icarus (the emitted Verilog in Icarus Verilog)",
            Engine::Verilator => "verilator (the emitted Verilog in Verilator)",
        }
    }

    /// System cycles per second on the 2-core project machine, for the
    /// estimate before a scene run; `None` for the model, which does not
    /// step cycles. Measured 2026-11-23 with `tritri sim --engine E
    /// --broad-phase flat` on the built-in scene (25,347 cycles: rust-hdl
    /// 18.4 s, Icarus 121 s) and with `--subdivide 2` (4,284,520 cycles:
    /// Verilator 31 s, model cached), preparation included.
    pub fn system_cycles_per_second(self) -> Option<f64> {
        match self {
            Engine::Model => None,
            Engine::Rusthdl => Some(1_400.0),
            Engine::Icarus => Some(210.0),
            Engine::Verilator => Some(140_000.0),
        }
    }
}

/// One run of a schedule through a pipeline.
#[derive(Clone, Debug)]
pub struct PipelineRun {
    /// The verdicts in output order and the cycle count.
    pub result: StreamResult,
    /// Seconds spent building (0: the model, rust-hdl, a cached Verilator model).
    pub build_seconds: f64,
    /// Seconds spent computing the verdicts.
    pub simulate_seconds: f64,
}

/// Runs `schedule` (per pair or group, a `bset` cycle then the tested
/// cycles) through the `width`-bit pipeline on `engine`. With `vcd`, a
/// hardware engine writes the waveform there (the model has none: an
/// error). The model's cycle count is what the hardware's must be: the
/// last tested cycle plus the latency.
pub fn run_pipeline(
    engine: Engine,
    width: usize,
    schedule: &[PipelineInput],
    vcd: Option<&Path>,
) -> anyhow::Result<PipelineRun> {
    let started = Instant::now();
    // Dispatched on the simulator, as `run_scene` does: the emitted
    // Verilog's two engines share one runner.
    match (engine, engine.simulator()) {
        (_, Some(simulator)) => {
            let run = pipeline_rtl::run_schedule(simulator, width, schedule, vcd)?;
            Ok(PipelineRun {
                result: run.result,
                build_seconds: run.build_seconds,
                simulate_seconds: run.simulate_seconds,
            })
        }
        (Engine::Model, None) => {
            anyhow::ensure!(vcd.is_none(), "the model has no waveform; choose a hardware engine (rusthdl, icarus or verilator)");
            let result = model_result(schedule, latency() as u64)?;
            Ok(PipelineRun {
                result,
                build_seconds: 0.0,
                simulate_seconds: started.elapsed().as_secs_f64(),
            })
        }
        (_, None) => {
            // Rusthdl: the rust-hdl pipeline, driven directly.
            let mut pipeline = pipeline_for_width(width)?;
            let options = HarnessOptions {
                vcd: vcd.map(Into::into),
            };
            let result = run_schedule_on(pipeline.as_mut(), schedule, &options)?;
            Ok(PipelineRun {
                result,
                build_seconds: 0.0,
                simulate_seconds: started.elapsed().as_secs_f64(),
            })
        }
    }
}

/// The fixed-point model's answer to a schedule, as the pipeline gives it.
fn model_result(schedule: &[PipelineInput], latency: u64) -> anyhow::Result<StreamResult> {
    let triangle = |c: &PipelineInput| -> FixedTriangle {
        let v = c.vertices;
        [[v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]]
    };
    let mut base: Option<(u32, FixedTriangle)> = None;
    let mut result = StreamResult::default();
    for (k, c) in schedule.iter().enumerate().filter(|(_, c)| c.valid) {
        if c.bset {
            base = Some((c.id, triangle(c)));
            continue;
        }
        let Some((base_id, b)) = base else {
            anyhow::bail!("streamed triangle {} before any base", c.id)
        };
        let CertifiedVerdict { hit, certain } = certified_intersects(&b, &triangle(c));
        result.verdicts.push(PairVerdict {
            base_id,
            stream_id: c.id,
            hit,
            certain,
        });
        // Input cycles count from 1; the verdict appears `latency` later.
        result.cycles = k as u64 + 1 + latency;
    }
    Ok(result)
}

/// What the hardware's own counters said after a scene run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HardwareCounters {
    /// Pairs tested (a 32-bit counter: wraps at 2^32).
    pub pairs_tested: u64,
    pub hits: u64,
    pub stall_cycles: u64,
    /// Sticky: an array exceeded the memory depth.
    pub overflow: bool,
}

/// What the owner filter did on an octree scene's hits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OwnerFiltering {
    /// Hits that left the system: every leaf's, a pair found in several
    /// leaves once per leaf.
    pub hits: u64,
    /// Pairs the filter let through: each intersecting pair once.
    pub pairs: u64,
    /// The filter's cycles for those hits offered back to back (its cycle
    /// model, `tritri_rtl::broad_phase::owner_filter::pair_cycles`).
    pub cycles: u64,
    /// Words of A's and B's slot tables (one per triangle per leaf).
    pub slots: (u64, u64),
}

/// One scene through the system.
#[derive(Clone, Debug)]
pub struct SceneRun {
    pub engine: Engine,
    /// Every intersecting pair `(i in A, j in B)`: the hardware's and the
    /// host's. With the octree broad phase the leaves' arrays carry slots,
    /// and the hits go through the owner filter's rule
    /// (`tritri_geom::scene::owner_slots`), which lets each pair through
    /// once, from its first leaf.
    pub pairs: PairSet,
    /// The pairs whose verdict has no certificate (`out_certain = 0`),
    /// intersecting on the grid or not, each once: what `--certified`
    /// decides again on the original coordinates.
    pub uncertain: PairSet,
    /// The owner filter's work (octree scenes).
    pub owner: Option<OwnerFiltering>,
    /// Cycles from the first host word to `done`: simulated by a hardware
    /// engine, the cycle model's for the model.
    pub cycles: u64,
    /// The system's cycle model on the same batches.
    pub model_cycles: u64,
    /// The hardware's counters (hardware engines only).
    pub counters: Option<HardwareCounters>,
}

impl SceneRun {
    /// What says the hardware is wrong, apart from its pairs: the overflow
    /// flag, a cycle count off the cycle model without a stall, or a pair
    /// the owner filter let through twice (each a bug).
    pub fn faults(&self) -> Vec<Fault> {
        let mut faults = Vec::new();
        if let Some(c) = self.counters {
            if c.overflow {
                faults.push(Fault::Overflow {
                    what: "an array exceeded the memory depth",
                });
            }
            if c.stall_cycles == 0 && self.cycles != self.model_cycles {
                faults.push(Fault::Cycles {
                    simulated: self.cycles,
                    low: self.model_cycles,
                    high: self.model_cycles,
                });
            }
        }
        if let Some(owner) = self.owner {
            if owner.pairs > self.pairs.len() as u64 {
                faults.push(Fault::OwnerDuplicates {
                    through: owner.pairs,
                    distinct: self.pairs.len() as u64,
                });
            }
        }
        faults
    }
}

/// How [`run_scene`] runs: the pipelines' rare-case path, progress and a
/// waveform.
#[derive(Clone, Copy)]
pub struct SceneRunOptions<'a> {
    /// Where the system's pipelines test their rare pairs; a hardware
    /// engine simulates that system (the model's pairs and cycles are the
    /// same for both: its cycle model has no stalls).
    pub rare_cases: RareCasePath,
    /// Told of work done as it is done: pairs for the model, simulated
    /// cycles for a hardware engine ([`Engine::progress_unit`]).
    pub progress: &'a (dyn Fn(u64) + Sync),
    /// The system's waveform is written here (Icarus and Verilator only:
    /// a traced build).
    pub vcd: Option<&'a Path>,
}

/// A progress callback that is told nothing (the options' default).
pub(crate) fn no_progress(_: u64) {}

impl Default for SceneRunOptions<'static> {
    fn default() -> Self {
        SceneRunOptions {
            rare_cases: RareCasePath::Parallel,
            progress: &no_progress,
            vcd: None,
        }
    }
}

/// Runs a prepared scene's batches through the system `config` describes
/// on `engine`, the host's pairs (triangles too long for a leaf's local
/// frame) through the model. With the octree broad phase the leaves'
/// arrays carry slots and the hits go through the owner filter's rule.
pub fn run_scene(
    engine: Engine,
    scene: &PreparedScene,
    config: SystemConfig,
    options: &SceneRunOptions,
) -> anyhow::Result<SceneRun> {
    let SceneRunOptions {
        rare_cases,
        progress,
        vcd,
    } = *options;
    let kind = PipelineKind::from(rare_cases);
    anyhow::ensure!(
        vcd.is_none() || engine.simulator().is_some(),
        "a waveform needs --engine icarus or verilator, not {}",
        engine.name()
    );
    let slots = scene.octree.as_ref().map(OwnerSlots::of);
    let slotted = match (&scene.octree, &slots) {
        (Some(octree), Some(slots)) => Some(slots.slotted(octree)),
        _ => None,
    };
    let batches = match &slotted {
        Some((a, b)) => scene.leaf_batches(a, b),
        None => scene.batches(),
    };
    let model_cycles = scene_cycles(config, &batches);
    // The system's hits in the order they leave it (ids, or slots).
    let (hits, uncertain, cycles, counters) = match engine {
        Engine::Model => {
            let (hits, uncertain) = narrow_phase(&batches, progress);
            (hits, uncertain, model_cycles, None)
        }
        _ => {
            let result: SystemResult = match engine.simulator() {
                None => run_system_reporting(
                    config,
                    kind,
                    &batches,
                    true,
                    ReaderBehaviour::AlwaysReady,
                    progress,
                )?,
                Some(simulator) => {
                    let options = SystemRunOptions {
                        progress: Some(progress),
                        vcd,
                    };
                    run_system_rtl_with(
                        simulator,
                        config,
                        kind,
                        &batches,
                        true,
                        ReaderBehaviour::AlwaysReady,
                        options,
                    )?
                }
            };
            let counters = HardwareCounters {
                pairs_tested: result.pairs_tested,
                hits: result.hits,
                stall_cycles: result.stall_cycles,
                overflow: result.overflow,
            };
            (
                result.pairs,
                result.uncertain,
                result.cycles,
                Some(counters),
            )
        }
    };
    let (mut pairs, owner) = match &slots {
        Some(slots) => {
            // The filter's model, and a hardware engine's own simulation of
            // the filter on the same hits, which must agree with it.
            // A slot outside the tables would be a fault of the system's
            // simulation; say so rather than index past them.
            if let Some(&(sa, sb)) = hits
                .iter()
                .find(|&&(sa, sb)| sa as usize >= slots.a.len() || sb as usize >= slots.b.len())
            {
                anyhow::bail!("the {} system returned the hit ({sa}, {sb}) outside the slot tables ({} and {} slots; a bug)", engine.name(), slots.a.len(), slots.b.len());
            }
            let (model, busy) = owner_filter::model(slots, &hits);
            let simulated = match (engine, engine.simulator()) {
                (Engine::Model, _) => None,
                (_, None) => Some(owner_filter::run_rusthdl(slots, &hits, |_| true)),
                (_, Some(simulator)) => Some(owner_filter::run_emitted(slots, &hits, simulator)?),
            };
            if let Some(simulated) = simulated {
                anyhow::ensure!(
                    simulated == model,
                    "the owner filter's {} simulation differs from its model: {} pairs at edges ending {:?}, the model {} ending {:?} (a bug)",
                    engine.name(),
                    simulated.pairs.len(),
                    simulated.edges.last(),
                    model.pairs.len(),
                    model.edges.last()
                );
            }
            let owner = OwnerFiltering {
                hits: hits.len() as u64,
                pairs: model.pairs.len() as u64,
                cycles: busy,
                slots: (slots.a.len() as u64, slots.b.len() as u64),
            };
            (model.pairs.into_iter().collect::<PairSet>(), Some(owner))
        }
        None => (hits.into_iter().collect(), None),
    };
    pairs.extend(fixed_point_pairs(&scene.host_batches(), &|_| {}));
    // Uncertain pairs by triangle ids (a pair in several leaves once), and
    // the host's.
    let mut uncertain: PairSet = match &slots {
        Some(slots) => uncertain
            .into_iter()
            .map(|(sa, sb)| slots.ids(sa, sb))
            .collect(),
        None => uncertain.into_iter().collect(),
    };
    uncertain.extend(narrow_phase(&scene.host_batches(), &|_| {}).1);
    Ok(SceneRun {
        engine,
        pairs,
        uncertain,
        owner,
        cycles,
        model_cycles,
        counters,
    })
}

/// The exact model on the scene's quantized coordinates (every batch and
/// the host's pairs), and how `pairs` differ from it: any difference is a
/// bug in the engine, since both decide the same integer triangles.
pub fn check_quantized(scene: &PreparedScene, pairs: &PairSet) -> (PairSet, PairDiff) {
    let mut exact = quantized_exact_pairs(&scene.batches());
    exact.extend(quantized_exact_pairs(&scene.host_batches()));
    let diff = PairDiff::between(&exact, pairs);
    (exact, diff)
}

/// The model engine's narrow phase: what the system reports of `batches`,
/// as `(id_a, id_b)` (slots, for the leaves' slotted batches), batch by
/// batch, in the order the system tests them (A's triangles, then B's,
/// within a batch): its hits, and the pairs whose verdict has no
/// certificate (`tritri_geom::certificate`), one pass over the pairs for
/// both; `progress` is told of each batch's pairs.
pub fn narrow_phase(
    batches: &[Batch],
    progress: &dyn Fn(u64),
) -> (Vec<(u32, u32)>, Vec<(u32, u32)>) {
    let (mut hits, mut uncertain) = (Vec::new(), Vec::new());
    for batch in batches {
        for x in batch.a {
            for y in batch.b {
                let v = certified_intersects(&x.triangle, &y.triangle);
                if v.hit {
                    hits.push((x.id, y.id));
                }
                if !v.certain {
                    uncertain.push((x.id, y.id));
                }
            }
        }
        progress(batch.pairs());
    }
    (hits, uncertain)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tritri_geom::scene::TaggedTriangle;

    /// The model answers a schedule as the pipeline does: one verdict per
    /// tested cycle against the latest base, the cycle count the last
    /// tested cycle plus the latency, bubbles counted.
    #[test]
    fn the_model_answers_a_schedule_like_the_pipeline() {
        let t = TaggedTriangle {
            id: 4,
            triangle: [[0, 0, 0], [10, 0, 0], [0, 10, 0]],
        };
        let through = TaggedTriangle {
            id: 9,
            triangle: [[1, 1, -5], [1, 1, 5], [3, 2, 5]],
        };
        let far = TaggedTriangle {
            id: 11,
            triangle: [[50, 50, 50], [60, 50, 50], [50, 60, 50]],
        };
        let schedule = [
            PipelineInput::load_base(&t),
            PipelineInput::test(&through),
            PipelineInput::idle(),
            PipelineInput::test(&far),
        ];
        let result = model_result(&schedule, 30).unwrap();
        let hits: Vec<(u32, u32, bool)> = result
            .verdicts
            .iter()
            .map(|v| (v.base_id, v.stream_id, v.hit))
            .collect();
        assert_eq!(hits, vec![(4, 9, true), (4, 11, false)]);
        assert_eq!(result.cycles, 4 + 30);
        assert!(
            model_result(&schedule[1..], 30).is_err(),
            "a test before any base is an error"
        );
    }
}
