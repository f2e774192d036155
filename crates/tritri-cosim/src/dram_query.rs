//! Two objects to their exact intersecting pairs on the accelerator that
//! fits the ECP5-85: the scene in DRAM behind one AXI4 port, binned,
//! tested and reported once in hardware
//! ([`tritri_rtl::broad_phase::dram_broad_phase`], docs/axi-port.md). The
//! route `tritri sim` runs by default, as one call.
//!
//! 1. The host culls both objects to their common box and quantizes what
//!    is left onto a 16-bit grid (`tritri_geom::scene::prepare`), and packs
//!    each object's kept triangles as a root list (32-byte entries, their
//!    vertices inside, [`host_root_lists`]): all it does before the
//!    hardware. It writes the lists into DRAM.
//! 2. The top bins the lists in DRAM, tests each leaf's pairs on its
//!    W = 16 pipeline and streams each pair once, with its certificate.
//!    On the model [`Engine`] that is the top's clock-exact model and the
//!    bit-exact narrow phase on the model's leaves; on `rusthdl`, `icarus`
//!    and `verilator` the emitted top itself against the AXI4 memory model,
//!    held to the model clock for clock (binning) and pair for pair.
//! 3. The host decides the pairs without a certificate again on the f64
//!    coordinates: the exact answer.
//!
//! The time runs from the first f64 triangle on the host to the last exact
//! pair on the host: the host's preparation, the root lists over the
//! host's link, the top's clocks at its post-route clock with the board's
//! memory ([`DramAccelerator::memory`]), the pairs back over the link, the
//! re-decisions. The software baseline beside it is the project's exact
//! path (box sweep and exact predicates, triangles in memory), which is
//! faster than CGAL's `box_intersection_d` (`examples/software_baseline`).
//!
//! ```
//! use tritri_cosim::dram_query::{find_pairs_in_dram, DramAccelerator, DramQueryOptions};
//! use tritri_geom::scene::load::load_object;
//! let (a, b) = (load_object("@torus", 8).unwrap(), load_object("@sphere", 8).unwrap());
//! let answer = find_pairs_in_dram(&a, &b, &DramAccelerator::versa(), &DramQueryOptions::default()).unwrap();
//! assert!(answer.faults.is_empty());
//! // The exact answer on the f64 coordinates.
//! assert_eq!(answer.pairs, answer.check.as_ref().unwrap().truth.pairs);
//! let time = answer.end_to_end().unwrap();
//! assert!(time.total() > time.accelerator);
//! ```

use crate::dram_binning::{binning_config, dram_case, run_model};
use crate::dram_broad_phase::{
    exact_on_grid, leaf_pairs, run_top_model, run_top_rusthdl, run_top_simulator, top_case,
    TopCase, TopRun,
};
use crate::engine::{no_progress, Engine};
use crate::fault::Fault;
use crate::scene_query::{
    fault_injected, Accelerator, Check, Clock, ClockSource, QueryError, Redecided,
};
use std::time::{Duration, Instant};
use tritri_geom::bounding_volume::grown_triangle_touches_box;
use tritri_geom::certificate::recheck_pairs;
use tritri_geom::octree::triangle_cell::BROAD_PHASE_MARGIN;
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::reference::PairSet;
use tritri_geom::scene::{prepare, PreparedScene, TaggedTriangle};
use tritri_geom::two_objects::on_both;
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::broad_phase::list_entry::{pack, ENTRY_BYTES};
use tritri_rtl::broad_phase::list_pass_machine::{ListPassConfig, PASS_DATA_BITS};
use tritri_rtl::emit::dram_broad_phase_unit::DramBroadPhaseConfig;
use tritri_rtl::measured::Measurements;
use tritri_rtl::pipeline::RareCasePath;

/// The ECP5-5G Versa board's DDR3: 16 bits at 800 MT/s, 1.6 GB/s.
pub const VERSA_GBYTES: f64 = 1.6;

/// The ECP5-5G Versa board's host link: PCI Express, one Gen 2 lane, 5
/// GT/s with 8b/10b coding, 0.5 GB/s each way before the protocol's
/// overhead, so a transfer at this rate is the least it takes.
pub const VERSA_LINK_GBYTES: f64 = 0.5;

/// Words of the owner filter's tables in the design that fits the
/// ECP5-85 (its head and record tables take 80 of the 208 block RAMs):
/// the triangles of each object in the common box, and the entries a
/// leaf streams per object, are at most this.
pub const TABLE_WORDS: usize = 8192;

/// Clocks from a burst's address to its first beat in the memory model.
pub const DRAM_LATENCY: u64 = 24;

/// Bytes a pair takes on its way back to the host (two 32-bit indices).
pub const PAIR_BYTES: u64 = 8;

/// The arena the first walk may use, before it is cut to the walk's peak.
const WIDE_ARENA: u64 = 64 << 20;

/// The accelerator that fits the ECP5-85, and the board around it. Its
/// system is fixed: W = 16 pipelines on a 16-bit grid, one pipeline, depth
/// 256, the rare pairs on a shared unit, the owner filter's tables of
/// [`TABLE_WORDS`] (`tritri gen --dram-broad-phase --width 16 --pipelines
/// 1 --rare-cases shared --triangles 8192 --slots 8192 --data-bits DW`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DramAccelerator {
    /// The AXI4 port's data width: 64, 128 or 256 bits.
    pub data_bits: usize,
    /// The memory's bandwidth, reads and writes together.
    pub memory_gbytes: f64,
    /// The host link's bandwidth, each way.
    pub link_gbytes: f64,
    /// The top's clock: its post-route clock where it was routed
    /// (rtl-out/measurements.json), else assumed.
    pub clock: Clock,
}

impl DramAccelerator {
    /// The 256-bit top, routed on the ECP5-85, with the ECP5-5G Versa's
    /// DDR3 and PCIe link.
    pub fn versa() -> Self {
        Self::with_port(256)
    }

    /// The top on a `data_bits` port with the Versa's memory and link, at
    /// that top's post-route clock, or at the assumed 100 MHz if it has
    /// none.
    pub fn with_port(data_bits: usize) -> Self {
        let mut dram = DramAccelerator {
            data_bits,
            memory_gbytes: VERSA_GBYTES,
            link_gbytes: VERSA_LINK_GBYTES,
            clock: Clock::ASSUMED,
        };
        if let Some(row) = Measurements::committed().ecp5(&dram.unit_name()) {
            dram.clock = Clock {
                mhz: row.fmax_mhz,
                source: ClockSource::PostRouteTop,
            };
        }
        dram
    }

    /// Why these parameters do not make the top, naming the option.
    pub fn validate(&self) -> Result<(), String> {
        if !PASS_DATA_BITS.contains(&self.data_bits) {
            return Err(format!(
                "--data-bits {}: the port is {:?} bits wide",
                self.data_bits, PASS_DATA_BITS
            ));
        }
        for (option, value) in [
            ("--memory-gbytes", self.memory_gbytes),
            ("--link-gbytes", self.link_gbytes),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(format!("{option} {value}: a bandwidth above 0 GB/s"));
            }
        }
        Ok(())
    }

    /// The collision system inside the top, and the grid the host
    /// prepares the scene for.
    pub fn accelerator(&self) -> Accelerator {
        Accelerator {
            pipelines: 1,
            rare_cases: RareCasePath::Shared,
            clock: self.clock,
            ..Accelerator::new(16)
        }
    }

    /// One pass of the binning over the port.
    pub fn pass(&self) -> ListPassConfig {
        ListPassConfig {
            grid_bits: 16,
            data_bits: self.data_bits,
            max_read_burst: 16,
            outstanding: 4,
        }
    }

    /// The emitted top's parameters (the arena is the run's).
    pub fn top_config(&self) -> DramBroadPhaseConfig {
        DramBroadPhaseConfig {
            binning: binning_config(&self.accelerator(), self.pass()),
            system: self.accelerator().system_config(),
            triangles: TABLE_WORDS,
            slots: TABLE_WORDS,
            local_frames: false,
            rare_cases: RareCasePath::Shared,
        }
    }

    /// The emitted top's name (`tritri gen` writes it under this name).
    pub fn unit_name(&self) -> String {
        self.top_config().unit_name()
    }

    /// The memory: [`DRAM_LATENCY`], at most a beat a clock each way, and
    /// `memory_gbytes` in all at the top's clock.
    pub fn memory(&self) -> MemoryParams {
        MemoryParams::ideal(self.data_bits as u64 / 8, DRAM_LATENCY)
            .at_bandwidth(self.memory_gbytes, self.clock.mhz)
    }

    /// `bytes` over the host link.
    pub fn link_time(&self, bytes: u64) -> Duration {
        Duration::from_secs_f64(bytes as f64 / (self.link_gbytes * 1e9))
    }
}

/// How [`find_pairs_in_dram`] runs.
#[derive(Clone, Copy)]
pub struct DramQueryOptions<'a> {
    pub engine: Engine,
    /// Hold the answer to the exact model on the grid and to exact f64 on
    /// the originals, and time the software baseline.
    pub check: bool,
    /// A hardware engine stops past this many clocks (an error).
    pub max_clocks: Option<u64>,
    /// Told of the top's clocks as the model counts them, once it ran.
    pub progress: &'a (dyn Fn(u64) + Sync),
}

impl Default for DramQueryOptions<'static> {
    fn default() -> Self {
        DramQueryOptions {
            engine: Engine::Model,
            check: true,
            max_clocks: None,
            progress: &no_progress,
        }
    }
}

/// The top's run on a scene whose boxes meet.
#[derive(Clone, Debug)]
pub struct DramRun {
    /// The engine's run: the pairs it streamed (as the meshes number their
    /// triangles), its clocks and the memory's beats. On the model engine,
    /// the model's clocks with the model's leaves' pairs.
    pub top: TopRun,
    /// The clock-exact model's run on the same memory.
    pub model: TopRun,
    /// The regions' cases, run one after another (one unless the scene
    /// overflows the owner filter's tables, [`fitting_cases`]): the memory
    /// as the host leaves it, the top's inputs. The runs above are their
    /// sums.
    pub cases: Vec<TopCase>,
    /// Pairs the leaves held, tested one by one (with repeats).
    pub pairs_tested: u64,
    pub redecided: Redecided,
}

impl DramRun {
    /// Clocks from `start` to the last pair out: the emitted top's `done`,
    /// or the model's last verdict (the model leaves out the result FIFO's
    /// back-pressure and the shared rare-case unit's holds; the owner
    /// filter finished with the last verdict on every co-simulated scene).
    pub fn clocks(&self) -> u64 {
        self.top.cycles
    }

    /// The memory every region ran with.
    pub fn memory(&self) -> MemoryParams {
        self.cases.first().map_or_else(
            || MemoryParams::ideal(32, DRAM_LATENCY),
            |c| c.binning.params,
        )
    }

    /// Bytes the top read from and wrote to DRAM.
    pub fn dram_bytes(&self) -> (u64, u64) {
        let beat = self.memory().beat_bytes;
        (self.top.beats_read * beat, self.top.beats_written * beat)
    }

    /// The fewest clocks that traffic takes on this memory: a beat a clock
    /// each way, and the memory's bytes a clock in all.
    pub fn memory_bound(&self) -> u64 {
        let params = self.memory();
        let (read, written) = self.dram_bytes();
        let (num, den) = params.bytes_per_clock;
        let total = ((read + written) * den).div_ceil(num);
        self.top.beats_read.max(self.top.beats_written).max(total)
    }

    /// Bytes the host writes into DRAM: both root lists of every region.
    pub fn bytes_in(&self) -> u64 {
        self.cases
            .iter()
            .map(|c| {
                let [a, b] = c.binning.root_lists.map(|(_, n)| n);
                (a + b) * ENTRY_BYTES as u64
            })
            .sum()
    }

    /// Bytes of the pairs streamed back (each pair once, hit or uncertain).
    pub fn bytes_back(&self) -> u64 {
        let mut streamed: PairSet = self.top.pairs.iter().copied().collect();
        streamed.extend(self.top.uncertain.iter().copied());
        streamed.len() as u64 * PAIR_BYTES
    }
}

/// One row of [`DramAnswer::over_bandwidth`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandwidthRow {
    pub gbytes: f64,
    /// The model's clocks to the last verdict with that memory.
    pub clocks: u64,
    pub time: Duration,
}

/// From the first f64 triangle on the host to the last exact pair on the
/// host.
#[derive(Clone, Copy, Debug)]
pub struct DramEndToEnd {
    /// Cull, quantize, pack the root lists.
    pub host: Duration,
    /// The root lists to the board.
    pub link_in: Duration,
    pub clocks: u64,
    /// The top's clocks at its clock.
    pub accelerator: Duration,
    /// The pairs back.
    pub link_back: Duration,
    /// The uncertain pairs decided again.
    pub redecide: Duration,
}

impl DramEndToEnd {
    pub fn total(&self) -> Duration {
        self.host + self.link_in + self.accelerator + self.link_back + self.redecide
    }
}

/// A query's answer and every figure of its run.
pub struct DramAnswer {
    /// The exact answer on the user's f64 coordinates: pairs `(i, j)` of
    /// A's and B's triangles that intersect.
    pub pairs: PairSet,
    pub engine: Engine,
    pub dram: DramAccelerator,
    pub scene: PreparedScene,
    /// The host's preparation: cull, quantize, and pack the root lists.
    pub host: Duration,
    /// `None` when the objects' boxes do not meet: no pair can intersect.
    pub run: Option<DramRun>,
    /// What says the hardware or a model is wrong (each a bug).
    pub faults: Vec<Fault>,
    /// With [`DramQueryOptions::check`], on a scene whose boxes meet.
    pub check: Option<Check>,
}

impl DramAnswer {
    /// The grid's own verdicts (the raw hardware answer).
    pub fn grid_pairs(&self) -> PairSet {
        self.run
            .as_ref()
            .map_or_else(PairSet::new, |r| r.top.pairs.iter().copied().collect())
    }

    pub fn end_to_end(&self) -> Option<DramEndToEnd> {
        let run = self.run.as_ref()?;
        Some(DramEndToEnd {
            host: self.host,
            link_in: self.dram.link_time(run.bytes_in()),
            clocks: run.clocks(),
            accelerator: self.dram.clock.time_of(run.clocks()),
            link_back: self.dram.link_time(run.bytes_back()),
            redecide: run.redecided.host,
        })
    }

    /// The software baseline over the end-to-end time.
    pub fn speedup(&self) -> Option<f64> {
        let software = self.check.as_ref()?.software.as_secs_f64();
        let whole = self.end_to_end()?.total().as_secs_f64();
        Some(software / whole.max(f64::MIN_POSITIVE))
    }

    /// The model's clocks and time at the top's clock with memories of
    /// `gbytes` GB/s (latency and port as [`DramAccelerator::memory`]), so
    /// that a user of a larger board reads their own row.
    pub fn over_bandwidth(&self, gbytes: &[f64]) -> Result<Vec<BandwidthRow>, QueryError> {
        let Some(run) = &self.run else {
            return Ok(Vec::new());
        };
        gbytes
            .iter()
            .map(|&g| {
                let dram = DramAccelerator {
                    memory_gbytes: g,
                    ..self.dram
                };
                let mut clocks = 0;
                for case in &run.cases {
                    let mut case = case.clone();
                    case.binning.params = dram.memory();
                    clocks += run_top_model(&case, u64::MAX)
                        .map_err(QueryError::Failed)?
                        .tested_at;
                }
                Ok(BandwidthRow {
                    gbytes: g,
                    clocks,
                    time: self.dram.clock.time_of(clocks),
                })
            })
            .collect()
    }
}

/// The memories of [`DramAnswer::over_bandwidth`]'s table: 0.4 to 25.6
/// GB/s, the Versa's 1.6 among them.
pub const BANDWIDTHS: [f64; 7] = [0.4, 0.8, 1.6, 3.2, 6.4, 12.8, 25.6];

/// The case of `scene` for the top of `dram` on a memory of `params`
/// (`dram.memory()` for the board's): the walk run once on a wide arena,
/// then the arena cut to its peak (so that a simulator's memory stays
/// small), the owner filter's tables of [`TABLE_WORDS`]. A scene that
/// needs larger tables is refused, naming what it needs
/// ([`fitting_cases`] cuts it into regions instead).
pub fn device_case(
    dram: &DramAccelerator,
    scene: &PreparedScene,
    params: MemoryParams,
) -> Result<TopCase, QueryError> {
    case_within_tables(dram, scene, params)?.map_err(|need| {
        QueryError::Unsupported(format!(
            "the scene has {need}; the owner filter of the design that fits the ECP5-85 holds {TABLE_WORDS}"
        ))
    })
}

/// [`device_case`], or what the scene needs that the tables do not hold.
fn case_within_tables(
    dram: &DramAccelerator,
    scene: &PreparedScene,
    params: MemoryParams,
) -> Result<Result<TopCase, String>, QueryError> {
    let (accelerator, pass) = (dram.accelerator(), dram.pass());
    let failed = QueryError::Failed;
    let (wide, _) = dram_case(&accelerator, scene, pass, params, WIDE_ARENA).map_err(failed)?;
    let (walk, _) = run_model(&wide).map_err(failed)?;
    if walk.arena_full != 0 {
        return Err(QueryError::Unsupported(format!(
            "the scene's lists need more than {} MiB of DRAM arena",
            WIDE_ARENA >> 20
        )));
    }
    let (mut case, _) =
        top_case(&accelerator, scene, pass, params, walk.peak_arena.max(1)).map_err(failed)?;
    for (what, need) in [
        (
            "triangles of one object in the common box",
            case.config.triangles,
        ),
        (
            "entries of one object streamed over the run",
            case.config.slots,
        ),
    ] {
        if need > TABLE_WORDS {
            return Ok(Err(format!("{need} {what}")));
        }
    }
    case.config.triangles = TABLE_WORDS;
    case.config.slots = TABLE_WORDS;
    Ok(Ok(case))
}

/// Halvings of a region before a scene is refused: a region a grid step
/// wide that still overflows the tables (thousands of triangles through
/// one point) cannot be cut further.
const MAX_SPLITS: u32 = 24;

/// The cases that cover `scene` within the owner filter's tables: the
/// whole common box if its tables hold it; else its two halves along the
/// longest axis, each with the kept triangles whose grown triangle touches
/// it (the host's own cull, `grown_triangle_touches_box`), each cut again
/// until it fits. The top runs them one after another. Every intersecting
/// pair is found: its triangles share a point, which lies in some region
/// (the regions cover the common box, and the point is in it), and both
/// touch that region, so both are in its lists; a pair found in two
/// regions is one pair of the answer. Halves without both objects are
/// skipped: no pair can be there.
pub fn fitting_cases(
    dram: &DramAccelerator,
    scene: &PreparedScene,
    params: MemoryParams,
) -> Result<Vec<TopCase>, QueryError> {
    let mut cases = Vec::new();
    cut_to_fit(dram, scene, params, 0, &mut cases)?;
    Ok(cases)
}

fn cut_to_fit(
    dram: &DramAccelerator,
    region: &PreparedScene,
    params: MemoryParams,
    splits: u32,
    cases: &mut Vec<TopCase>,
) -> Result<(), QueryError> {
    let need = match case_within_tables(dram, region, params)? {
        Ok(case) => {
            cases.push(case);
            return Ok(());
        }
        Err(need) => need,
    };
    let Some(bounds) = region.integer_box else {
        return Ok(());
    };
    let axis = (0..3)
        .max_by_key(|&k| bounds.hi[k] - bounds.lo[k])
        .unwrap_or(0);
    if splits >= MAX_SPLITS || bounds.hi[axis] - bounds.lo[axis] < 2 {
        return Err(QueryError::Unsupported(format!(
            "a region of the scene {} grid steps wide has {need}; the owner filter of the design that fits the ECP5-85 holds {TABLE_WORDS}",
            bounds.hi[axis] - bounds.lo[axis]
        )));
    }
    let middle = bounds.lo[axis] + (bounds.hi[axis] - bounds.lo[axis]) / 2;
    let (mut low, mut high) = (bounds, bounds);
    low.hi[axis] = middle;
    high.lo[axis] = middle;
    for half in [low, high] {
        let touching = |list: &[TaggedTriangle]| -> Vec<TaggedTriangle> {
            list.iter()
                .filter(|t| grown_triangle_touches_box(&t.triangle, BROAD_PHASE_MARGIN, &half))
                .copied()
                .collect()
        };
        let (kept_a, kept_b) = (touching(&region.kept_a), touching(&region.kept_b));
        if kept_a.is_empty() || kept_b.is_empty() {
            continue;
        }
        let part = PreparedScene {
            integer_box: Some(half),
            kept_a,
            kept_b,
            ..region.clone()
        };
        cut_to_fit(dram, &part, params, splits + 1, cases)?;
    }
    Ok(())
}

/// Runs the top of `dram` on `a` and `b` and returns the exact answer.
pub fn find_pairs_in_dram(
    a: &SceneObject,
    b: &SceneObject,
    dram: &DramAccelerator,
    options: &DramQueryOptions,
) -> Result<DramAnswer, QueryError> {
    dram.validate().map_err(QueryError::Unsupported)?;
    let accelerator = dram.accelerator();
    let started = Instant::now();
    let scene = prepare(a, b, &accelerator.scene_options())?;
    let host = started.elapsed();
    let mut answer = DramAnswer {
        pairs: PairSet::new(),
        engine: options.engine,
        dram: *dram,
        scene,
        host,
        run: None,
        faults: Vec::new(),
        check: None,
    };
    if answer.scene.integer_box.is_none() {
        return Ok(answer);
    }
    let cases = fitting_cases(dram, &answer.scene, dram.memory())?;
    // The host's packing of every region's root lists, timed with its
    // preparation; they are the bytes the simulated memory holds
    // (tests/dram_query.rs). Which regions, the top's model chose above,
    // untimed: a host would learn it from a run that overflows.
    let started = Instant::now();
    std::hint::black_box(host_root_lists(&answer.scene, &cases)?);
    answer.host += started.elapsed();
    let run = run_engine(cases, a, b, options, &mut answer.faults)?;
    answer.pairs = run.redecided.pairs.clone();
    answer.run = Some(run);
    if options.check {
        let grid = answer.grid_pairs();
        let quantized: PairSet = exact_on_grid(&answer.scene).into_iter().collect();
        let check = Check::against(quantized, a, b, &grid, &answer.pairs);
        if !check.engine_vs_grid.is_empty() {
            answer.faults.push(Fault::DiffersFromGrid {
                engine: options.engine,
                missing: check.engine_vs_grid.missing.clone(),
                extra: check.engine_vs_grid.extra.clone(),
            });
        }
        answer.check = Some(check);
    }
    Ok(answer)
}

/// The root lists of `cases` (the regions of `scene`) as the host writes
/// them into DRAM: for each region, each object's triangles of the region
/// in the order of the case's lists, as entries numbered 0, 1, ... (the
/// pairs come back as these numbers). The region's triangles are found
/// among the scene's kept ones by their mesh numbers, through a table of
/// each number's place in the kept list, made once for all regions.
pub fn host_root_lists(
    scene: &PreparedScene,
    cases: &[TopCase],
) -> Result<Vec<[Vec<u8>; 2]>, QueryError> {
    // Object `k`'s lists of every region, the two objects on two threads
    // when they are large (as `prepare` does).
    let lists_of = |k: usize| -> Result<Vec<Vec<u8>>, QueryError> {
        let kept = [&scene.kept_a, &scene.kept_b][k];
        let mut places = vec![u32::MAX; [scene.n_a, scene.n_b][k]];
        for (place, t) in kept.iter().enumerate() {
            places[t.id as usize] = place as u32;
        }
        cases
            .iter()
            .map(|case| {
                let grid_bits = case.binning.config.pass.grid_bits;
                let mut list = Vec::with_capacity(case.ids[k].len() * ENTRY_BYTES);
                for (i, &id) in case.ids[k].iter().enumerate() {
                    let place = places.get(id as usize).copied().unwrap_or(u32::MAX);
                    let Some(t) = kept.get(place as usize) else {
                        return Err(QueryError::Failed(anyhow::anyhow!(
                            "triangle {id} of a region's list is not among object {k}'s kept triangles (a bug)"
                        )));
                    };
                    list.extend_from_slice(&pack(i as u32, &t.triangle, grid_bits));
                }
                Ok(list)
            })
            .collect()
    };
    // The objects' sizes decide the threads, as in `prepare`.
    let (a, b) = on_both(scene.n_a + scene.n_b, || lists_of(0), || lists_of(1));
    Ok(a?.into_iter().zip(b?).map(|(a, b)| [a, b]).collect())
}

/// Each region's model, then the engine's run held to it, one region
/// after another; then the re-decisions.
fn run_engine(
    cases: Vec<TopCase>,
    a: &SceneObject,
    b: &SceneObject,
    options: &DramQueryOptions,
    faults: &mut Vec<Fault>,
) -> Result<DramRun, QueryError> {
    let (mut top, mut model) = (TopRun::default(), TopRun::default());
    let (mut grid, mut uncertain) = (PairSet::new(), PairSet::new());
    let mut pairs_tested = 0;
    for case in &cases {
        let mut region_model = run_top_model(case, u64::MAX).map_err(QueryError::Failed)?;
        region_model.cycles = region_model.tested_at;
        let leaves = leaf_pairs(case).map_err(QueryError::Failed)?;
        if let Some(max) = options.max_clocks {
            if options.engine.is_hardware() && model.cycles + region_model.cycles > max {
                return Err(QueryError::Unsupported(format!(
                    "the top takes more than {max} clocks (its model), above --max-cycles"
                )));
            }
        }
        let limit = region_model.cycles.saturating_mul(4).max(100_000);
        let region_top = match (options.engine, options.engine.simulator()) {
            (Engine::Model, _) => TopRun {
                pairs: leaves.hits.clone(),
                uncertain: leaves.uncertain.clone(),
                pairs_tested: leaves.tested,
                ..region_model.clone()
            },
            (_, Some(simulator)) => {
                run_top_simulator(simulator, case, limit).map_err(QueryError::Failed)?
            }
            (_, None) => run_top_rusthdl(case, limit).map_err(QueryError::Failed)?,
        };
        if options.engine.is_hardware() {
            faults.extend(top_faults(&region_top, &region_model, &leaves.uncertain));
        }
        (options.progress)(region_top.cycles);
        grid.extend(region_top.pairs.iter().copied());
        uncertain.extend(region_top.uncertain.iter().copied());
        pairs_tested += leaves.tested;
        add_run(&mut top, &region_top);
        add_run(&mut model, &region_model);
    }
    if fault_injected() {
        if let Some(&first) = grid.iter().next() {
            grid.remove(&first);
        }
    }
    // Each pair once over the regions, in order.
    top.pairs = grid.iter().copied().collect();
    top.uncertain = uncertain.iter().copied().collect();
    let started = Instant::now();
    let redecided = recheck_pairs(&grid, &uncertain, &a.triangles, &b.triangles);
    let redecide = started.elapsed();
    Ok(DramRun {
        top,
        model,
        cases,
        pairs_tested,
        redecided: Redecided {
            pairs: redecided.pairs,
            changed: redecided.changed,
            host: redecide,
        },
    })
}

/// `run` after `total`: the regions run one after another, so clocks,
/// beats and counts add.
fn add_run(total: &mut TopRun, run: &TopRun) {
    total.binned_at += run.binned_at;
    total.tested_at += run.tested_at;
    total.cycles += run.cycles;
    total.leaves += run.leaves;
    total.passes += run.passes;
    total.pairs_tested += run.pairs_tested;
    total.hits += run.hits;
    total.stalled += run.stalled;
    total.beats_read += run.beats_read;
    total.beats_written += run.beats_written;
    total.error |= run.error;
    total.overflow |= run.overflow;
    total.faults += run.faults;
}

/// Where the emitted top's run differs from its model's: a flag raised,
/// a pair streamed twice, other uncertain pairs than the leaves hold,
/// another walk, or a last verdict before the model's (the model leaves
/// out only holds, so it is never later).
fn top_faults(top: &TopRun, model: &TopRun, uncertain: &[(u32, u32)]) -> Vec<Fault> {
    let mut faults = Vec::new();
    if top.error || top.overflow || top.faults != 0 {
        faults.push(Fault::Overflow {
            what: "the DRAM top's error, overflow or memory fault",
        });
    }
    let streamed: PairSet = top.pairs.iter().copied().collect();
    if streamed.len() != top.pairs.len() {
        faults.push(Fault::OwnerDuplicates {
            through: top.pairs.len() as u64,
            distinct: streamed.len() as u64,
        });
    }
    let top_uncertain: PairSet = top.uncertain.iter().copied().collect();
    if top_uncertain != uncertain.iter().copied().collect::<PairSet>() {
        faults.push(Fault::TopPairs {
            top: top_uncertain.len(),
            model: uncertain.len(),
        });
    }
    for (what, got, want) in [
        ("leaves", top.leaves, model.leaves),
        ("passes", top.passes, model.passes),
        (
            "clock of the last leaf binned",
            top.binned_at,
            model.binned_at,
        ),
    ] {
        if got != want {
            faults.push(Fault::TopWalk {
                what,
                top: got,
                model: want,
            });
        }
    }
    if top.tested_at < model.tested_at {
        faults.push(Fault::Cycles {
            simulated: top.tested_at,
            low: model.tested_at,
            high: u64::MAX,
        });
    }
    faults
}
