//! Two objects to their exact intersecting pairs, as one call: the route
//! `tritri sim`, `tritri report` and `tritri demo` run, and that a library
//! user runs the same way.
//!
//! 1. [`prepare_query`] does the host's part: the common box, quantization
//!    onto one grid, the broad phase's plan (`tritri_geom::scene`), and
//!    the binning unit's clock-exact model on it, once ([`Binning`]).
//! 2. [`PreparedQuery::run`] runs the accelerator on an [`Engine`] (the
//!    system's batches with the owner filter's rule, or the emitted
//!    broad-phase top), decides the uncertain verdicts again on the
//!    original coordinates, counts the cycles from the first triangle in
//!    to the last pair out, and, with [`QueryOptions::check`], holds the
//!    engine to the exact model on the grid and times the software
//!    baseline on the originals.
//!
//! [`find_pairs`] is both steps. Its [`SceneAnswer`] holds every figure
//! the command line prints; what says the hardware is wrong is a
//! [`Fault`] in [`SceneAnswer::faults`], and what cannot run at all a
//! [`QueryError`].
//!
//! ```
//! use tritri_cosim::scene_query::{find_pairs, Accelerator, QueryOptions};
//! use tritri_geom::scene::load::load_object;
//! let (a, b) = (load_object("@torus", 8).unwrap(), load_object("@sphere", 8).unwrap());
//! let answer = find_pairs(&a, &b, &Accelerator::new(24), &QueryOptions::default()).unwrap();
//! assert!(answer.faults.is_empty());
//! // The exact answer on the f64 coordinates, whatever the grid said.
//! let check = answer.check.as_ref().unwrap();
//! assert_eq!(answer.pairs, check.truth.pairs);
//! let time = answer.end_to_end().unwrap();
//! assert!(time.cycles >= answer.hardware.as_ref().unwrap().run.cycles);
//! ```

use crate::binning_unit::{bin_scene, BinningError, SceneBinning};
use crate::broad_phase_system::{run_scene_on_top, top_model, TopSceneRun};
use crate::engine::{check_quantized, no_progress, run_scene, Engine, SceneRun, SceneRunOptions};
use crate::fault::Fault;
use std::path::Path;
use std::time::{Duration, Instant};
use tritri_geom::certificate::recheck_pairs;
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::octree::{LocalFrames, OctreeSchedule};
use tritri_geom::scene::reference::{
    exact_f64_pairs, exact_f64_pairs_threads, ExactF64Result, PairDiff, PairSet,
};
use tritri_geom::scene::{prepare, prepare_octree, PreparedScene, SceneError, SceneOptions};
use tritri_rtl::broad_phase::binning_cost::{binning_cycles, BinningWork};
use tritri_rtl::broad_phase::broad_phase_system::broad_phase_cycles;
use tritri_rtl::pipeline::pipeline_for_width::check_width;
use tritri_rtl::pipeline::RareCasePath;
use tritri_rtl::system::cycle_model::scene_cycles;
use tritri_rtl::system::rare_case_model::{rare_case_cost, RareCaseCost};
use tritri_rtl::system::{SystemConfig, DEFAULT_TRIANGLES_PER_BANK};

/// Which pairs the system is given.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, clap::ValueEnum)]
pub enum BroadPhase {
    /// Every pair of triangles in the common box (the thesis, chapter 4).
    Flat,
    /// Octree leaves over the common box holding triangles of both objects
    /// (docs/broad-phase.md).
    Octree,
}

/// Where a clock comes from; every time printed names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClockSource {
    /// Given by the user or by no measurement (the thesis's 100 MHz): not
    /// a result.
    Assumed,
    /// The ECP5 post-route clock of the system of those pipelines.
    PostRouteSystem,
    /// The post-route clock of one pipeline routed alone.
    PostRoutePipeline,
    /// The ECP5 post-route clock of the broad-phase top with its scene in
    /// DRAM ([`crate::dram_query`]).
    PostRouteTop,
}

impl ClockSource {
    pub fn name(self) -> &'static str {
        match self {
            ClockSource::Assumed => "assumed",
            ClockSource::PostRouteSystem => "post-route, system",
            ClockSource::PostRoutePipeline => "post-route, pipeline",
            ClockSource::PostRouteTop => "post-route on the ECP5-85",
        }
    }

    pub fn is_post_route(self) -> bool {
        self != ClockSource::Assumed
    }
}

/// A clock frequency and where it comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clock {
    pub mhz: f64,
    pub source: ClockSource,
}

impl Clock {
    /// The thesis's 100 MHz, assumed.
    pub const ASSUMED: Clock = Clock {
        mhz: 100.0,
        source: ClockSource::Assumed,
    };

    /// `cycles` at this clock.
    pub fn time_of(&self, cycles: u64) -> Duration {
        Duration::from_secs_f64(cycles as f64 / (self.mhz * 1e6))
    }
}

/// The hardware a query runs on, in one value: it builds both the scene's
/// options (grid, memory depth) and the system's configuration (its
/// latency derived from the pipeline), so the two cannot disagree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Accelerator {
    /// Coordinate width W of the pipelines (8 to 32 bits).
    pub width: u32,
    /// Bits G of the one grid the scene is quantized onto (W to 32); above
    /// W, each octree leaf goes to the hardware in a W-bit frame of its own.
    pub grid_bits: u32,
    /// Pipelines P working in parallel.
    pub pipelines: u32,
    /// Triangles per array per bank.
    pub depth: u32,
    /// Cut arrays longer than the depth into tiles (else refuse the scene).
    pub split: bool,
    pub broad_phase: BroadPhase,
    /// Where the pipelines test their rare pairs.
    pub rare_cases: RareCasePath,
    pub clock: Clock,
}

impl Accelerator {
    /// The default accelerator at width W: the grid W bits, two pipelines,
    /// the default depth, the octree broad phase, the rare pairs on
    /// parallel units, at the assumed clock.
    pub fn new(width: u32) -> Self {
        Accelerator {
            width,
            grid_bits: width,
            pipelines: 2,
            depth: DEFAULT_TRIANGLES_PER_BANK as u32,
            split: true,
            broad_phase: BroadPhase::Octree,
            rare_cases: RareCasePath::Parallel,
            clock: Clock::ASSUMED,
        }
    }

    /// Why these parameters do not make an accelerator, naming the option.
    pub fn validate(&self) -> Result<(), String> {
        let g = self.grid_bits;
        if g < self.width {
            return Err(format!(
                "--grid-bits {g} is below --width {}: the grid needs at least W bits",
                self.width
            ));
        }
        if g > self.width && self.broad_phase == BroadPhase::Flat {
            return Err(format!(
                "--grid-bits {g} above --width {} needs --broad-phase octree (the flat system sends the whole box in one W-bit frame)",
                self.width
            ));
        }
        Ok(())
    }

    /// Leaves in frames of their own when the grid is finer than W.
    pub fn local_frames(&self) -> Option<LocalFrames> {
        (self.grid_bits > self.width).then_some(LocalFrames { width: self.width })
    }

    /// What the host prepares the scene for: the grid and the depth.
    pub fn scene_options(&self) -> SceneOptions {
        SceneOptions {
            grid_bits: self.grid_bits,
            depth: self.depth as usize,
            split: self.split,
        }
    }

    /// The generator parameters of the system.
    pub fn system_config(&self) -> SystemConfig {
        SystemConfig::new(self.width as usize, self.pipelines as usize)
            .with_depth(self.depth as usize)
    }

    /// The scene prepared for this hardware with its broad phase.
    pub fn prepare(&self, a: &SceneObject, b: &SceneObject) -> Result<PreparedScene, SceneError> {
        self.prepare_with(self.broad_phase, a, b)
    }

    /// [`Self::prepare`] with another broad phase (`tritri chapter5` sets
    /// both side by side).
    pub fn prepare_with(
        &self,
        broad_phase: BroadPhase,
        a: &SceneObject,
        b: &SceneObject,
    ) -> Result<PreparedScene, SceneError> {
        match broad_phase {
            BroadPhase::Flat => prepare(a, b, &self.scene_options()),
            BroadPhase::Octree => prepare_octree(
                a,
                b,
                &self.scene_options(),
                &self.system_config(),
                self.local_frames(),
            ),
        }
    }

    /// `cycles` at the accelerator's clock.
    pub fn time_of(&self, cycles: u64) -> Duration {
        self.clock.time_of(cycles)
    }
}

/// How [`PreparedQuery::run`] runs.
#[derive(Clone, Copy)]
pub struct QueryOptions<'a> {
    pub engine: Engine,
    /// With a hardware engine: run the emitted broad-phase top (binning
    /// unit, system and owner filter in one design) instead of the system
    /// fed with the planner's leaves.
    pub on_top: bool,
    /// Told of work done: pairs for the model, cycles for a hardware engine.
    pub progress: &'a (dyn Fn(u64) + Sync),
    /// The system's waveform (Icarus or Verilator).
    pub vcd: Option<&'a Path>,
    /// Hold the engine to the exact model on the grid, and decide every
    /// pair on the originals in software (the check and the baseline).
    pub check: bool,
}

impl Default for QueryOptions<'static> {
    fn default() -> Self {
        QueryOptions {
            engine: Engine::Model,
            on_top: false,
            progress: &no_progress,
            vcd: None,
            check: true,
        }
    }
}

/// Why a query did not run.
#[derive(Debug, thiserror::Error)]
pub enum QueryError {
    /// The configuration has no hardware or does not apply (exit status 2).
    #[error("{0}")]
    Unsupported(String),
    /// The scene cannot be prepared for this hardware (exit status 2).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The engine failed while running: a simulator that did not build or
    /// crashed, or a simulation that disagreed with its model on the way
    /// (exit status 1).
    #[error("{0:#}")]
    Failed(anyhow::Error),
}

/// The binning unit on the scene's broad phase.
#[derive(Clone, Debug)]
pub enum Binning {
    /// The flat broad phase, or no common box: nothing to bin.
    None,
    /// The unit built for the scene: its clock-exact model's run (the
    /// emitted unit equals it in co-simulation).
    Unit(SceneBinning),
    /// The unit does not apply (or, a fault, its model differs from the
    /// planner): the cost formula's cycles on the planner's work.
    Formula {
        why: BinningError,
        work: BinningWork,
        cycles: u64,
    },
}

impl Binning {
    fn of(accelerator: &Accelerator, scene: &PreparedScene) -> Binning {
        let Some(octree) = &scene.octree else {
            return Binning::None;
        };
        if scene.common.is_none() {
            return Binning::None;
        }
        match bin_scene(
            scene,
            accelerator.grid_bits as usize,
            accelerator.depth as usize,
            accelerator.pipelines as usize,
            accelerator.local_frames().map(|l| l.max_leaf_level()),
        ) {
            Ok(unit) => Binning::Unit(unit),
            Err(why) => {
                let work = binning_work(octree);
                Binning::Formula {
                    why,
                    cycles: binning_cycles(&work),
                    work,
                }
            }
        }
    }
}

/// What the broad phase's plan asks of the binning unit.
fn binning_work(octree: &OctreeSchedule) -> BinningWork {
    BinningWork {
        triangles: octree.binned,
        cells: octree.cells_visited,
        entries: octree.classifications,
        cell_cycles: octree.classify_cycles,
    }
}

/// The host's part done: the scene prepared and binned, ready to run on
/// any engine.
pub struct PreparedQuery<'o> {
    pub a: &'o SceneObject,
    pub b: &'o SceneObject,
    pub accelerator: Accelerator,
    pub scene: PreparedScene,
    pub binning: Binning,
    /// The host's preparation: common box, quantization, broad phase plan.
    pub host: Duration,
}

/// The host's part: checks the accelerator, prepares the scene for it and
/// runs the binning unit's model on it.
pub fn prepare_query<'o>(
    a: &'o SceneObject,
    b: &'o SceneObject,
    accelerator: &Accelerator,
) -> Result<PreparedQuery<'o>, QueryError> {
    accelerator.validate().map_err(QueryError::Unsupported)?;
    let started = Instant::now();
    let scene = accelerator.prepare(a, b)?;
    let host = started.elapsed();
    let binning = Binning::of(accelerator, &scene);
    Ok(PreparedQuery {
        a,
        b,
        accelerator: *accelerator,
        scene,
        binning,
        host,
    })
}

impl PreparedQuery<'_> {
    /// The cycles a hardware engine will step (the cycle model's count, for
    /// an estimate before the run).
    pub fn model_cycles(&self, on_top: bool) -> u64 {
        match (&self.binning, on_top) {
            (Binning::Unit(unit), true) => {
                broad_phase_cycles(self.accelerator.system_config(), &unit.run)
            }
            _ => scene_cycles(self.accelerator.system_config(), &self.scene.batches()),
        }
    }

    /// Runs the accelerator on `options.engine` and returns the exact answer.
    pub fn run(self, options: &QueryOptions) -> Result<SceneAnswer, QueryError> {
        let engine = options.engine;
        if engine.is_hardware() {
            check_width(self.accelerator.width as usize).map_err(|e| {
                QueryError::Unsupported(format!(
                    "--width {} --engine {}: {e} (the model takes 8 to 32)",
                    self.accelerator.width,
                    engine.name()
                ))
            })?;
        }
        if options.on_top && (!engine.is_hardware() || options.vcd.is_some()) {
            return Err(QueryError::Unsupported("the broad-phase top runs the emitted design: it needs a hardware engine (rusthdl, icarus or verilator) and no waveform".into()));
        }
        let mut faults = Vec::new();
        if let Binning::Formula {
            why: BinningError::DiffersFromPlanner { unit, planner },
            ..
        } = &self.binning
        {
            faults.push(Fault::BinningLeaves {
                unit: *unit,
                planner: *planner,
            });
        }
        let hardware = match self.scene.common {
            None => None,
            Some(_) => Some(self.run_hardware(options, &mut faults)?),
        };
        let pairs = hardware
            .as_ref()
            .map_or_else(PairSet::new, |h| h.redecided.pairs.clone());
        let check = match (&hardware, options.check) {
            (Some(h), true) => {
                let check = Check::of(&self.scene, self.a, self.b, &h.run.pairs, &pairs);
                if !check.engine_vs_grid.is_empty() {
                    faults.push(Fault::DiffersFromGrid {
                        engine,
                        missing: check.engine_vs_grid.missing.clone(),
                        extra: check.engine_vs_grid.extra.clone(),
                    });
                }
                Some(check)
            }
            _ => None,
        };
        Ok(SceneAnswer {
            pairs,
            engine,
            accelerator: self.accelerator,
            scene: self.scene,
            binning: self.binning,
            host: self.host,
            hardware,
            faults,
            check,
        })
    }

    fn run_hardware(
        &self,
        options: &QueryOptions,
        faults: &mut Vec<Fault>,
    ) -> Result<HardwareRun, QueryError> {
        let config = self.accelerator.system_config();
        let batches = self.scene.batches();
        let rare = rare_case_cost(config.pipelines, &batches);
        let (run, top) = if options.on_top {
            let Binning::Unit(unit) = &self.binning else {
                let why = match &self.binning {
                    Binning::Formula { why, .. } => why.to_string(),
                    _ => "it needs the octree broad phase".into(),
                };
                return Err(QueryError::Unsupported(format!(
                    "the broad-phase top does not apply: {why}"
                )));
            };
            let top = run_scene_on_top(
                &self.scene,
                unit,
                config,
                self.accelerator.local_frames().map(|l| l.max_leaf_level()),
                options.engine.simulator(),
            )
            .map_err(QueryError::Failed)?;
            faults.extend(top.faults());
            let run = SceneRun {
                engine: options.engine,
                pairs: top.pairs.clone(),
                uncertain: top.uncertain.clone(),
                owner: None,
                cycles: top.output.cycles,
                model_cycles: top.model_cycles,
                counters: None,
            };
            (run, Some(top))
        } else {
            let run = run_scene(
                options.engine,
                &self.scene,
                config,
                &SceneRunOptions {
                    rare_cases: self.accelerator.rare_cases,
                    progress: options.progress,
                    vcd: options.vcd,
                },
            )
            .map_err(QueryError::Failed)?;
            faults.extend(run.faults());
            (run, None)
        };
        let run = inject_fault(run);
        let started = Instant::now();
        let redecided = recheck_pairs(
            &run.pairs,
            &run.uncertain,
            &self.a.triangles,
            &self.b.triangles,
        );
        let redecide = started.elapsed();
        let cycles = self.cycles(&run, top.as_ref(), &rare);
        Ok(HardwareRun {
            run,
            top,
            redecided: Redecided {
                pairs: redecided.pairs,
                changed: redecided.changed,
                host: redecide,
            },
            cycles,
            rare,
        })
    }

    /// Cycles from the first triangle in to the last pair out.
    fn cycles(&self, run: &SceneRun, top: Option<&TopSceneRun>, rare: &RareCaseCost) -> Cycles {
        // A hardware engine on the shared rare-case path simulates its
        // stalls; the model adds the stall model's bound.
        let stall_bound = match self.accelerator.rare_cases {
            RareCasePath::Shared if run.counters.is_none() => rare.stall_cycles,
            _ => 0,
        };
        let (whole, count) = match (top, &self.binning) {
            (Some(top), _) => (
                top.output.cycles,
                WholeCount::SimulatedTop {
                    binned_at: top.output.binned_at,
                },
            ),
            (None, Binning::None) => (run.cycles, WholeCount::NarrowPhase),
            // The broad-phase top's cycle model: the leaves go from the
            // binning unit into the system's banks as they stream, and the
            // owner filter decides the hits as they come; its clocks for
            // the hits back to back bound what it adds (co-simulation holds
            // the emitted top within both).
            (None, Binning::Unit(unit)) => {
                let config = self.accelerator.system_config();
                let top = broad_phase_cycles(config, &unit.run);
                let arrays = |kept: &[tritri_geom::scene::TaggedTriangle]| {
                    kept.iter().map(|t| t.triangle).collect::<Vec<_>>()
                };
                let filter = top_model(
                    &unit.run,
                    config.triangles_per_bank,
                    &arrays(&self.scene.kept_a),
                    &arrays(&self.scene.kept_b),
                )
                .filter_clocks;
                (top + filter, WholeCount::TopModel { top, filter })
            }
            (None, Binning::Formula { cycles, .. }) => {
                let owner = run.owner.map_or(0, |o| o.cycles);
                (
                    cycles + run.cycles + owner,
                    WholeCount::Sum {
                        binning: *cycles,
                        narrow: run.cycles,
                        owner,
                    },
                )
            }
        };
        Cycles {
            narrow: run.cycles,
            whole: whole + stall_bound,
            stall_bound,
            count,
        }
    }
}

/// The environment variable that makes [`PreparedQuery::run`] lose one of
/// the engine's pairs (value `drop-grid-pair`), so that tests can see a
/// fault travel from the check to the user; nothing else reads it.
pub const INJECT_FAULT: &str = "TRITRI_INJECT_FAULT";

fn inject_fault(mut run: SceneRun) -> SceneRun {
    if fault_injected() {
        if let Some(&first) = run.pairs.iter().next() {
            run.pairs.remove(&first);
        }
    }
    run
}

/// Whether [`INJECT_FAULT`] asks to lose a pair.
pub(crate) fn fault_injected() -> bool {
    std::env::var(INJECT_FAULT).as_deref() == Ok("drop-grid-pair")
}

/// Both steps: [`prepare_query`], then [`PreparedQuery::run`].
pub fn find_pairs(
    a: &SceneObject,
    b: &SceneObject,
    accelerator: &Accelerator,
    options: &QueryOptions,
) -> Result<SceneAnswer, QueryError> {
    prepare_query(a, b, accelerator)?.run(options)
}

/// The uncertain verdicts decided again on the original coordinates.
#[derive(Clone, Debug)]
pub struct Redecided {
    /// The exact answer: the grid's certain hits and the uncertain pairs
    /// that intersect on the originals.
    pub pairs: PairSet,
    /// Uncertain pairs whose verdict on the originals differs from the grid's.
    pub changed: usize,
    /// What deciding them again took on the host.
    pub host: Duration,
}

/// How [`Cycles::whole`] was counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WholeCount {
    /// The flat broad phase: the system's cycles are all there is.
    NarrowPhase,
    /// The broad-phase top's cycle model (binning streamed into the narrow
    /// phase) plus its owner filter's bound.
    TopModel { top: u64, filter: u64 },
    /// The binning unit does not apply: its cost formula, the narrow phase
    /// and the owner filter one after the other.
    Sum {
        binning: u64,
        narrow: u64,
        owner: u64,
    },
    /// Simulated: the emitted broad-phase top, binned at that clock.
    SimulatedTop { binned_at: u64 },
}

/// The accelerator's cycles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cycles {
    /// The system's cycles for the leaves' batches (simulated by a
    /// hardware engine, its cycle model's for the model).
    pub narrow: u64,
    /// From the first triangle in to the last pair out, the stall bound
    /// included.
    pub whole: u64,
    /// With the rare pairs on a shared unit and the model engine, the stall
    /// model's bound on the clocks the system holds for them.
    pub stall_bound: u64,
    pub count: WholeCount,
}

/// The accelerator's run on a scene whose boxes meet.
#[derive(Clone, Debug)]
pub struct HardwareRun {
    /// The engine's run: the grid's pairs, the uncertain ones, the owner
    /// filter's work, the hardware's counters.
    pub run: SceneRun,
    /// The broad-phase top's own figures, when it ran.
    pub top: Option<TopSceneRun>,
    pub redecided: Redecided,
    pub cycles: Cycles,
    /// Coplanar and degenerate pairs among those tested.
    pub rare: RareCaseCost,
}

/// The engine held to the exact model on the grid, and every answer to
/// exact f64 on the originals.
#[derive(Clone, Debug)]
pub struct Check {
    /// The exact model on the quantized coordinates: what the engine's
    /// grid pairs must be.
    pub quantized: PairSet,
    /// The engine against it (anything but empty is a fault).
    pub engine_vs_grid: PairDiff,
    /// Exact f64 over every pair whose triangle boxes overlap: the
    /// software baseline (box sweep and exact predicates, one thread,
    /// triangles in memory).
    pub truth: ExactF64Result,
    pub software: Duration,
    /// The same path on two threads (the machine's cores), timed after.
    pub software_two_threads: Duration,
    /// The grid's answer against the truth (quantization error).
    pub grid_vs_truth: PairDiff,
    /// The exact answer against the truth (empty unless a certificate is wrong).
    pub answer_vs_truth: PairDiff,
}

impl Check {
    fn of(
        scene: &PreparedScene,
        a: &SceneObject,
        b: &SceneObject,
        grid: &PairSet,
        answer: &PairSet,
    ) -> Check {
        let (quantized, _) = check_quantized(scene, grid);
        Check::against(quantized, a, b, grid, answer)
    }

    /// The check with the exact model's pairs on the grid given.
    pub(crate) fn against(
        quantized: PairSet,
        a: &SceneObject,
        b: &SceneObject,
        grid: &PairSet,
        answer: &PairSet,
    ) -> Check {
        let engine_vs_grid = PairDiff::between(&quantized, grid);
        let started = Instant::now();
        let truth = exact_f64_pairs(&a.triangles, &b.triangles);
        let software = started.elapsed();
        let started = Instant::now();
        std::hint::black_box(exact_f64_pairs_threads(&a.triangles, &b.triangles, 2));
        let software_two_threads = started.elapsed();
        Check {
            grid_vs_truth: PairDiff::between(&truth.pairs, &quantized),
            answer_vs_truth: PairDiff::between(&truth.pairs, answer),
            quantized,
            engine_vs_grid,
            truth,
            software,
            software_two_threads,
        }
    }
}

/// The end-to-end time: host preparation, the accelerator's cycles at its
/// clock, the host's re-decisions.
#[derive(Clone, Copy, Debug)]
pub struct EndToEnd {
    pub host: Duration,
    pub cycles: u64,
    pub accelerator: Duration,
    pub redecide: Duration,
}

impl EndToEnd {
    pub fn total(&self) -> Duration {
        self.host + self.accelerator + self.redecide
    }
}

/// A query's answer and every figure of its run.
pub struct SceneAnswer {
    /// The exact answer on the user's f64 coordinates: pairs `(i, j)` of
    /// A's and B's triangles that intersect.
    pub pairs: PairSet,
    pub engine: Engine,
    pub accelerator: Accelerator,
    pub scene: PreparedScene,
    pub binning: Binning,
    /// The host's preparation.
    pub host: Duration,
    /// `None` when the objects' boxes do not meet: no pair can intersect.
    pub hardware: Option<HardwareRun>,
    /// What says the hardware or a model is wrong (each a bug).
    pub faults: Vec<Fault>,
    /// With [`QueryOptions::check`], on a scene whose boxes meet.
    pub check: Option<Check>,
}

impl SceneAnswer {
    /// The grid's own verdicts (the raw hardware answer).
    pub fn grid_pairs(&self) -> PairSet {
        self.hardware
            .as_ref()
            .map_or_else(PairSet::new, |h| h.run.pairs.clone())
    }

    /// First f64 triangle in to last exact pair out (no transfer counted).
    pub fn end_to_end(&self) -> Option<EndToEnd> {
        let h = self.hardware.as_ref()?;
        Some(EndToEnd {
            host: self.host,
            cycles: h.cycles.whole,
            accelerator: self.accelerator.time_of(h.cycles.whole),
            redecide: h.redecided.host,
        })
    }

    /// The software baseline over the end-to-end time.
    pub fn speedup(&self) -> Option<f64> {
        let software = self.check.as_ref()?.software.as_secs_f64();
        let whole = self.end_to_end()?.total().as_secs_f64();
        Some(software / whole.max(f64::MIN_POSITIVE))
    }
}
