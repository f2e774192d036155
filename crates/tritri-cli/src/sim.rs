//! `tritri sim [--scene A B] [--pose-b tx,ty,tz,rx,ry,rz] [--scale-b S]
//! [--width W] [--pipelines P] [--depth N] [--broad-phase octree|flat]
//! [--grid-bits G] [--subdivide K] [--engine model|rusthdl|icarus|verilator]
//! [--clock-mhz F] [--out PAIRS] [--png FILE [--eye X,Y,Z] [--up x|y|z] [--size PX]]
//! [--tolerance T] [--broad-phase-top] [--certified] [--rare-cases parallel|shared]`
//!
//! `--tolerance T` tessellates `.bpt` objects for the query
//! (`tritri_geom::bezier::query`): only the patches that can meet the
//! other object, each as finely as `T` asks.
//!
//! Runs the whole bounding-volume-aware system on two objects (without
//! `--scene`, the built-in torus and sphere): common BV, the arrays of
//! triangles touching it, one W-bit frame (or a G-bit grid with leaves in
//! W-bit frames of their own), the broad phase (octree leaves by default,
//! or the thesis's flat common box; `docs/broad-phase.md`), batches of at
//! most D triangles, the engine, and the comparison with the exact models
//! and with the software box sweep's time. Prints a report (on stdout, or
//! on stderr when the pairs go to stdout with `--out -`).
//!
//! `--broad-phase-top` (with a hardware engine) runs the broad-phase top
//! instead: the binning unit, the system and the owner filter in one
//! emitted design, each object's triangles in once and each pair out once
//! (`tritri gen --broad-phase`), held to its models (pairs; `done` between
//! the binning unit and system's cycle model and that plus the owner
//! filter's clocks). W = 24, or W = 16 with `--grid-bits 24`.
//!
//! Every pair whose verdict has no certificate (`out_certain = 0`,
//! docs/certificates.md) is counted in the report. With `--certified`
//! those pairs are decided again with exact predicates on the original
//! coordinates, and the answer (what `--out` writes) is the grid's certain
//! hits plus the uncertain pairs that intersect on the originals.
//!
//! `--png FILE` renders both objects from the direction `--eye` (from the
//! scene's centre; `--up` names the axis pointing up) with the triangles
//! of the answer's pairs highlighted: A's in red, B's in magenta.
//!
//! `--out PAIRS` writes the intersecting pairs, one `i j` per line in
//! ascending order: `i` indexes A's triangles and `j` B's, in file order
//! with polygons split into fans (`--indices faces` reports face indices
//! instead, deduplicated).
//!
//! Engines (`tritri_cosim::engine`, the route this command only prints):
//! `model` is the bit-exact fixed-point model with the system's exact
//! cycle model; `rusthdl` simulates the system (memories, address
//! generator, P Devillers–Guigue pipelines, result FIFO) in rust-hdl, and
//! `icarus` and `verilator` run its emitted Verilog, all cycle by cycle
//! (slow: use small scenes), reporting the simulated cycle count.
//!
//! Before a cycle-by-cycle run (`rusthdl`, `icarus`, `verilator`) the report gives
//! an estimate (cycles from the cycle model, time at the engine's measured
//! speed, vector file size); above `--max-cycles` (default: what the
//! engine runs in about five minutes) the run is refused. The vectors are
//! streamed to the simulator through a pipe, so nothing grows with the
//! run but the pairs. Progress shows as a bar on a terminal and as a line
//! every ten seconds otherwise (pairs for the model, cycles for the
//! others). `--out` and `--vcd` are checked before any work and written
//! atomically; `--vcd FILE` records the system's waveform (Icarus or
//! Verilator, runs of at most `--vcd-max-cycles`).
//!
//! Exit status: 0 done; 1 the engine disagrees with the exact model on the
//! quantized coordinates, or its cycle count with the cycle model (a bug),
//! or a runtime failure; 2 a scene file cannot be read (the error names the
//! file and line), an unwritable `--out`, a width without hardware, a run
//! above `--max-cycles`, the arrays exceed D with `--no-split`, or bad
//! usage; 130 / 143 interrupted (simulators stopped, temporaries removed).

use crate::model_files::write_png;
use crate::output_file::OutputFile;
use crate::progress::Progress;
use crate::scene_input::{human, pipeline_latency, HardwareArgs, SceneArgs};
use crate::voxelize::ViewArgs;
use clap::ValueEnum;
use std::collections::BTreeSet;
use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;
use tritri_cosim::binning_unit::{bin_scene, SceneBinning};
use tritri_cosim::broad_phase_system::{run_scene_on_top, top_model};
use tritri_cosim::engine::{check_quantized, run_scene_on, Engine, SceneRun};
use tritri_geom::bounding_volume::Aabb;
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::octree::OctreeSchedule;
use tritri_geom::scene::reference::{exact_f64_pairs, PairDiff, PairSet};
use tritri_geom::scene::render::render_pairs;
use tritri_geom::scene::PreparedScene;
use tritri_geom::scene::TaggedTriangle;
use tritri_rtl::octree::binning_model::{binning_cycles, BinningWork};
use tritri_rtl::octree::broad_phase_system::broad_phase_cycles;
use tritri_rtl::octree::owner_filter::SLOT_WORD_BITS;
use tritri_rtl::pipeline::pipeline_for_width::check_width;
use tritri_rtl::pipeline::RareCasePath;
use tritri_rtl::system::cycle_model::scene_cycles;
use tritri_rtl::system::rare_case_model::rare_case_cost;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    hardware: HardwareArgs,
    /// What computes the verdicts.
    #[arg(long, value_enum, default_value_t = Engine::Model)]
    engine: Engine,
    /// Write the intersecting pairs here, one `i j` per line (`-`: stdout).
    #[arg(long, value_name = "PAIRS")]
    out: Option<String>,
    /// Report triangle indices (polygons split into fans) or face indices.
    #[arg(long, value_enum, default_value_t = Indices::Triangles)]
    indices: Indices,
    /// Skip the comparison with the exact models.
    #[arg(long)]
    no_compare: bool,
    /// Decide every pair without a certificate (`out_certain = 0`) again on
    /// the original coordinates; the answer written by --out is then that one.
    #[arg(long)]
    certified: bool,
    /// Refuse a cycle-by-cycle simulation (rusthdl, icarus, verilator) longer than
    /// this many system cycles [default: what the engine runs in about
    /// five minutes here]; the estimate is printed either way.
    #[arg(long, value_name = "N")]
    max_cycles: Option<u64>,
    /// Write the system's waveform (every signal, VCD) here; with --engine
    /// icarus or verilator, for runs of at most --vcd-max-cycles cycles.
    #[arg(long, value_name = "FILE")]
    vcd: Option<String>,
    /// Render both objects with the triangles of the intersecting pairs
    /// highlighted (A's red, B's magenta) to this PNG.
    #[arg(long, value_name = "FILE")]
    png: Option<String>,
    #[command(flatten)]
    view: ViewArgs,
    /// With a hardware engine: run the broad-phase top (binning unit,
    /// system and owner filter: triangles in, each pair out once) on the
    /// scene instead of the system fed by the host's octree; W = 24, or
    /// W = 16 with --grid-bits 24.
    #[arg(long)]
    broad_phase_top: bool,
    /// Where the system's pipelines test their rare pairs (coplanar, or
    /// two degenerate triangles): `parallel`, their own units, or `shared`,
    /// one shared unit a pipeline that stalls the system while a rare pair
    /// waits for it (`tritri gen --rare-cases`). A hardware engine
    /// simulates it; every engine reports the stall model's bound.
    #[arg(long, value_name = "PATH", default_value = "parallel", value_parser = RareCasePath::NAMES, conflicts_with = "broad_phase_top")]
    rare_cases: String,
    /// The longest run --vcd records (every signal and memory word: the
    /// file grows by about 55 kB per cycle at W = 24, P = 2, depth 256).
    #[arg(long, value_name = "N", default_value_t = 10_000)]
    vcd_max_cycles: u64,
}

/// Seconds of simulation allowed without `--max-cycles`.
const DEFAULT_MAX_SECONDS: f64 = 300.0;

/// Bytes of the system testbench's vectors per triangle sent.
const VECTOR_BYTES_PER_TRIANGLE: u64 = 90;

/// Bytes of the system's waveform per cycle (measured in Verilator: the
/// built-in scene, W = 24, P = 2, depth 256, 72.3 MB for 1,316 cycles).
const VCD_BYTES_PER_CYCLE: u64 = 55_000;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Indices {
    Triangles,
    Faces,
}

/// Default scene of `tritri sim` without `--scene`.
pub const DEFAULT_SCENE: [&str; 2] = ["@torus", "@sphere"];

/// Pairs above which the model's progress is shown.
const PROGRESS_THRESHOLD: u64 = 5_000_000;

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    if let Err(e) = args.hardware.validate() {
        eprintln!("error: {e}");
        return Ok(ExitCode::from(2));
    }
    if let (true, Err(e)) = (
        args.engine.is_hardware(),
        check_width(args.hardware.width as usize),
    ) {
        eprintln!(
            "error: --width {} --engine {}: {e} (the model takes 8 to 32)",
            args.hardware.width,
            args.engine.name()
        );
        return Ok(ExitCode::from(2));
    }
    if args.broad_phase_top
        && (!args.engine.is_hardware()
            || args.vcd.is_some()
            || args.hardware.broad_phase != crate::scene_input::BroadPhase::Octree)
    {
        eprintln!("error: --broad-phase-top runs the emitted top: it needs --engine rusthdl, icarus or verilator, the octree broad phase, and no --vcd");
        return Ok(ExitCode::from(2));
    }
    if args.vcd.is_some() && args.engine.simulator().is_none() {
        eprintln!("error: --vcd needs --engine icarus or verilator (the emitted Verilog), not --engine {}", args.engine.name());
        return Ok(ExitCode::from(2));
    }
    let output = match args.out.as_deref().map(OutputFile::reserve).transpose() {
        Ok(output) => output,
        Err(e) => {
            eprintln!("error: --out: {e:#}");
            return Ok(ExitCode::from(2));
        }
    };
    let vcd = match args
        .vcd
        .as_deref()
        .filter(|p| *p != "-")
        .map(OutputFile::reserve)
        .transpose()
    {
        Ok(vcd) => vcd,
        Err(e) => {
            eprintln!("error: --vcd: {e:#}");
            return Ok(ExitCode::from(2));
        }
    };
    let png = match args.png.as_deref().map(reserve_png).transpose() {
        Ok(png) => png,
        Err(e) => {
            eprintln!("error: --png: {e:#}");
            return Ok(ExitCode::from(2));
        }
    };
    if args.vcd.as_deref() == Some("-") {
        eprintln!("error: --vcd -: a waveform goes to a file, not to standard output");
        return Ok(ExitCode::from(2));
    }
    // With a hardware engine, `.bpt` pieces for the query go through the
    // tessellation unit in it too.
    let unit = (args.engine != Engine::Model).then_some(args.engine);
    let (a, b, notes) = match args.scene.load_with_notes(DEFAULT_SCENE, unit) {
        Ok(objects) => objects,
        Err(e)
            if e.downcast_ref::<tritri_geom::scene::load::LoadError>()
                .is_some() =>
        {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(2));
        }
        Err(e) => return Err(e),
    };
    let pairs_to_stdout = args.out.as_deref() == Some("-");
    let mut report: Box<dyn Write> = if pairs_to_stdout {
        Box::new(std::io::stderr())
    } else {
        Box::new(std::io::stdout())
    };
    let pose = args.scene.pose_b.unwrap_or_default();
    writeln!(
        report,
        "scene: A = {} ({} triangles), B = {} ({} triangles), pose of B = {pose}",
        a.name,
        a.triangles.len(),
        b.name,
        b.triangles.len()
    )?;
    for note in notes {
        writeln!(report, "{note}")?;
    }
    writeln!(report, "box of A: {}", show_box(&scene_box(&a)))?;
    writeln!(report, "box of B: {}", show_box(&scene_box(&b)))?;

    let started = Instant::now();
    let scene = match args.hardware.prepare(&a, &b) {
        Ok(s) => s,
        Err(e @ tritri_geom::scene::SceneError::ExceedsDepth { .. }) => {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(2));
        }
        Err(e) => return Err(e.into()),
    };
    let Some(common) = scene.common else {
        writeln!(report, "no overlap: the bounding boxes of A and B do not meet, so no triangle pair can intersect; zero pairs tested")?;
        write_pairs(output, args.indices, &a, &b, &PairSet::new())?;
        write_render(png, &args, &a, &b, &PairSet::new(), &mut report)?;
        return Ok(ExitCode::SUCCESS);
    };
    let host_time = started.elapsed();
    print_filter(&mut report, &args, &scene, &common)?;
    writeln!(
        report,
        "host: common box, quantization and broad phase in software took {} (this machine)",
        human(host_time)
    )?;

    let pairs_tested = scene.pairs_tested();
    let mut status = ExitCode::SUCCESS;
    let config = args.hardware.system_config();
    let model_cycles = if args.engine.is_hardware() {
        scene_cycles(config, &scene.batches())
    } else {
        0
    };
    if args.engine.is_hardware() {
        writeln!(
            report,
            "estimate: {}",
            estimate(args.engine, model_cycles, &scene)
        )?;
        if vcd.is_some() && model_cycles > args.vcd_max_cycles {
            eprintln!(
                "error: --vcd: {model_cycles} cycles is above --vcd-max-cycles {} (the waveform would be about {:.0} MB); raise the limit or record a smaller scene",
                args.vcd_max_cycles,
                model_cycles as f64 * VCD_BYTES_PER_CYCLE as f64 / 1e6
            );
            return Ok(ExitCode::from(2));
        }
        let limit = args.max_cycles.unwrap_or_else(|| {
            (DEFAULT_MAX_SECONDS * args.engine.system_cycles_per_second().unwrap_or(0.0)) as u64
        });
        if model_cycles > limit {
            let why = if args.max_cycles.is_some() {
                String::new()
            } else {
                format!(" (the default: about {DEFAULT_MAX_SECONDS} s of simulation)")
            };
            eprintln!(
                "error: --engine {}: {model_cycles} cycles is above --max-cycles {limit}{why}; raise the limit to run it, or use --engine model (the same pairs and cycle count, bit-exact)",
                args.engine.name(),
            );
            return Ok(ExitCode::from(2));
        }
    }
    let progress = if args.engine.is_hardware() {
        // Shown for runs of more than a few seconds.
        let threshold = (5.0 * args.engine.system_cycles_per_second().unwrap_or(0.0)) as u64;
        Progress::new(model_cycles, args.engine.progress_unit(), threshold)
    } else {
        Progress::new(
            pairs_tested,
            args.engine.progress_unit(),
            PROGRESS_THRESHOLD,
        )
    };
    // The value parser admits only the names.
    let rare_cases = RareCasePath::parse(&args.rare_cases).unwrap_or_default();
    let run = if args.broad_phase_top {
        run_on_top(&args, &scene, &mut report, &mut status)
    } else {
        run_scene_on(
            args.engine,
            rare_cases.into(),
            &scene,
            config,
            &|n| progress.inc(n),
            vcd.as_ref().and_then(OutputFile::temporary),
        )
    };
    progress.finish();
    let run = match run {
        Ok(run) => run,
        Err(e) => {
            eprintln!("error: --engine {}: {e:#}", args.engine.name());
            return Ok(ExitCode::from(2));
        }
    };
    let (pairs, cycles) = (&run.pairs, run.cycles);
    writeln!(report, "engine: {}", args.engine.describe())?;
    if let (Some(vcd), Some(path)) = (vcd, &args.vcd) {
        let size = vcd.commit_written()?;
        writeln!(
            report,
            "waveform: {path} ({:.1} MB, {cycles} cycles)",
            size as f64 / 1e6
        )?;
    }
    if let Some(c) = run.counters {
        let mut notes = format!(
            "{} pairs tested by the hardware's counter (wraps at 2^32), {} hits, {} stall cycles; cycle model {}",
            c.pairs_tested, c.hits, c.stall_cycles, run.model_cycles
        );
        for fault in run.faults() {
            notes.push_str(&format!("; {fault}"));
            status = ExitCode::from(1);
        }
        writeln!(report, "hardware: {notes}")?;
    }
    if let Some(owner) = run.owner {
        writeln!(
            report,
            "owner filter (hardware rule: each pair from the first leaf holding both triangles): {} hits from the leaves, {} duplicates dropped, {} pairs through; {} cycles for the hits back to back; slot tables {} + {} words of {SLOT_WORD_BITS} bits ({:.2} Mbit){}",
            owner.hits,
            owner.hits - owner.pairs,
            owner.pairs,
            owner.cycles,
            owner.slots.0,
            owner.slots.1,
            (owner.slots.0 + owner.slots.1) as f64 * SLOT_WORD_BITS as f64 / 1e6,
            if args.engine.is_hardware() { format!("; simulated in {}: equal to its model", args.engine.name()) } else { String::new() }
        )?;
        for fault in run
            .faults()
            .into_iter()
            .filter(|f| f.contains("owner filter"))
        {
            if run.counters.is_none() {
                writeln!(report, "owner filter: {fault}")?;
                status = ExitCode::from(1);
            }
        }
    }
    writeln!(report, "intersecting pairs: {}", pairs.len())?;
    // Pairs too long for a leaf's local frame are decided by the host on
    // the grid, with certificates too.
    let decided = scene.pairs_tested() + scene.host_pairs();
    writeln!(
        report,
        "certificates: {} pairs without one ({:.4} % of the {} pairs decided{}), intersecting on the grid or not",
        run.uncertain.len(),
        100.0 * run.uncertain.len() as f64 / decided.max(1) as f64,
        decided,
        if scene.host_pairs() > 0 { format!(": {} in leaves, {} by the host", scene.pairs_tested(), scene.host_pairs()) } else { String::new() }
    )?;
    let certified = args
        .certified
        .then(|| certify(pairs, &run.uncertain, &a, &b));
    if let Some(c) = &certified {
        writeln!(
            report,
            "certified: the {} pairs without a certificate decided again on the original coordinates ({} verdicts changed): {} intersecting pairs",
            run.uncertain.len(),
            c.changed,
            c.pairs.len()
        )?;
    }
    let pairs = certified.as_ref().map_or(pairs, |c| &c.pairs);
    let time = args.hardware.time_of(cycles);
    writeln!(
        report,
        "cycles: {cycles} ({} pipelines, pipeline latency {}, banks overlapped), time at {} MHz: {}",
        args.hardware.pipelines,
        pipeline_latency(),
        args.hardware.clock_mhz,
        human(time)
    )?;
    let rare = rare_case_cost(args.hardware.pipelines as usize, &scene.batches());
    let simulated = match (rare_cases == RareCasePath::Shared, run.counters) {
        (true, Some(c)) => format!(
            "; simulated with them there ({}): {} stall cycles",
            args.engine.name(),
            c.stall_cycles
        ),
        (true, None) => "; the model engine does not simulate the stalls".to_string(),
        (false, _) => "; these pipelines test them on parallel units, without a stall".to_string(),
    };
    writeln!(
        report,
        "rare cases: {} coplanar and {} degenerate pairs of {} tested; on a shared path (`--rare-cases shared`, stall model) at most {} stall cycles, +{:.2} % on the cycle model's {}{simulated}",
        rare.coplanar,
        rare.segments,
        rare.pairs,
        rare.stall_cycles,
        100.0 * rare.stall_cycles as f64 / run.model_cycles.max(1) as f64,
        run.model_cycles
    )?;
    write_pairs(output, args.indices, &a, &b, pairs)?;
    write_render(png, &args, &a, &b, pairs, &mut report)?;

    if !args.no_compare {
        let (quantized, same) = check_quantized(&scene, &run.pairs);
        if same.is_empty() {
            writeln!(
                report,
                "check: engine = exact model on the quantized coordinates ({} pairs): equal",
                quantized.len()
            )?;
        } else {
            writeln!(
                report,
                "check: engine DIFFERS from the exact model on the quantized coordinates: {} missing, {} extra (a bug) e.g. {:?} {:?}",
                same.missing.len(),
                same.extra.len(),
                &same.missing[..same.missing.len().min(5)],
                &same.extra[..same.extra.len().min(5)]
            )?;
            status = ExitCode::from(1);
        }
        let started = Instant::now();
        let truth = exact_f64_pairs(&a.triangles, &b.triangles);
        let software = started.elapsed();
        let diff = PairDiff::between(&truth.pairs, &quantized);
        writeln!(
            report,
            "exact f64 on the original coordinates, all {} pairs ({} with overlapping triangle boxes decided): {} intersecting",
            scene.all_pairs(),
            truth.pairs_decided,
            truth.pairs.len()
        )?;
        writeln!(
            report,
            "work: pairs tested {} = {:.2} x the box-overlap pairs ({}) = {:.2e} of N1*N2",
            scene.pairs_tested(),
            scene.pairs_tested() as f64 / truth.pairs_decided.max(1) as f64,
            truth.pairs_decided,
            scene.pairs_tested() as f64 / scene.all_pairs().max(1) as f64
        )?;
        let ratio = |hardware: std::time::Duration| {
            software.as_secs_f64() / hardware.as_secs_f64().max(f64::MIN_POSITIVE)
        };
        let narrow = args.hardware.time_of(cycles);
        writeln!(
            report,
            "speed: software (box sweep + exact predicates, one thread, triangles in memory) {}; the system's cycles {} at {} MHz: {:.1} x",
            human(software),
            human(narrow),
            args.hardware.clock_mhz,
            ratio(narrow)
        )?;
        let whole = match args.broad_phase_top {
            true => Some((
                cycles,
                format!("simulated: the broad-phase top in {}", args.engine.name()),
            )),
            false => first_in_to_last_out(&args.hardware, &scene, &run, cycles),
        };
        if let Some((whole, how)) = whole {
            let whole_time = args.hardware.time_of(whole);
            writeln!(
                report,
                "speed, first triangle in to last pair out: {whole} cycles ({how}), {} at {} MHz, {:.1} x",
                human(whole_time),
                args.hardware.clock_mhz,
                ratio(whole_time)
            )?;
        }
        writeln!(
            report,
            "quantization error (grid of {} bits): {} pairs missing, {} extra against exact f64{}",
            args.hardware.grid_bits(),
            diff.missing.len(),
            diff.extra.len(),
            examples(&diff)
        )?;
        if let Some(c) = &certified {
            let diff = PairDiff::between(&truth.pairs, &c.pairs);
            writeln!(
                report,
                "certified answer: {} pairs missing, {} extra against exact f64{}",
                diff.missing.len(),
                diff.extra.len(),
                examples(&diff)
            )?;
        }
    }
    report.flush()?;
    Ok(status)
}

/// The answer on the original coordinates: `grid`'s hits that carry a
/// certificate, and the `uncertain` pairs that intersect on the originals.
pub struct Certified {
    pub pairs: PairSet,
    /// Uncertain pairs whose verdict on the originals differs from the grid's.
    pub changed: usize,
}

pub fn certify(grid: &PairSet, uncertain: &PairSet, a: &SceneObject, b: &SceneObject) -> Certified {
    let mut pairs: PairSet = grid.difference(uncertain).copied().collect();
    let mut changed = 0;
    for &(i, j) in uncertain {
        let exact =
            tritri_geom::exact_f64::intersects(&a.triangles[i as usize], &b.triangles[j as usize]);
        changed += (exact != grid.contains(&(i, j))) as usize;
        if exact {
            pairs.insert((i, j));
        }
    }
    Certified { pairs, changed }
}

fn scene_box(o: &SceneObject) -> Option<Aabb<f64>> {
    Aabb::of_triangles(&o.triangles)
}

fn show_box(b: &Option<Aabb<f64>>) -> String {
    match b {
        None => "empty".into(),
        Some(b) => format!(
            "[{:.6}, {:.6}, {:.6}] .. [{:.6}, {:.6}, {:.6}]",
            b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]
        ),
    }
}

fn print_filter(
    report: &mut dyn Write,
    args: &Args,
    scene: &PreparedScene,
    common: &Aabb<f64>,
) -> anyhow::Result<()> {
    writeln!(report, "common BV: {}", show_box(&Some(*common)))?;
    writeln!(
        report,
        "in the common BV: A {} of {} (f64 box filter {}), B {} of {} (f64 box filter {}): {:.1} % of all triangles",
        scene.kept_a.len(),
        scene.n_a,
        scene.candidates_a.len(),
        scene.kept_b.len(),
        scene.n_b,
        scene.candidates_b.len(),
        100.0 * scene.fraction_in_common_bv()
    )?;
    if let Some(frame) = scene.frame {
        writeln!(
            report,
            "frame: {} bits, step h = {:e}, centre {:?}",
            args.hardware.grid_bits(),
            frame.step,
            frame.centre
        )?;
        if let Some(local) = args.hardware.local_frames() {
            writeln!(
                report,
                "local frames: leaves go to the {}-bit hardware as grid coordinates minus the leaf's centre; {} pairs with a triangle too long for a leaf's window decided by the host",
                local.width,
                scene.host_pairs()
            )?;
        }
    }
    let t = scene.tiling;
    if scene.octree.is_some() {
        writeln!(
            report,
            "memories: depth {}: {} batches (one per leaf, tiled where a leaf exceeds the depth)",
            t.depth,
            scene.batches().len()
        )?;
    } else if t.is_split() {
        writeln!(
            report,
            "memories: depth {}: arrays of {} and {} triangles split into {} x {} tiles = {} batches",
            t.depth,
            scene.kept_a.len(),
            scene.kept_b.len(),
            t.a_tiles,
            t.b_tiles,
            scene.batches().len()
        )?;
    } else {
        writeln!(
            report,
            "memories: depth {}: {} batch, no split",
            t.depth,
            scene.batches().len()
        )?;
    }
    if let Some(octree) = &scene.octree {
        writeln!(
            report,
            "broad phase: octree over the common box, root side 2^{} grid steps: {} cells classified, {} leaves with both objects, depth {}, arrays {} (A) + {} (B) triangles{}",
            octree.root.map_or(0, |r| r.level),
            octree.cells_visited,
            octree.leaves.len(),
            octree.tree_depth,
            octree.a.len(),
            octree.b.len(),
            if octree.oversized_leaves > 0 { format!(", {} leaves over the depth (tiled)", octree.oversized_leaves) } else { String::new() }
        )?;
        match scene_binning(&args.hardware, scene) {
            Ok(SceneBinning { config, run }) => writeln!(
                report,
                "binning unit (built; its cycle-exact model here, equal to its Verilog in co-simulation): {} triangles in, {} cell passes over {} entries, {} leaves (the planner's), at most {} frames deep: {} cycles; memories {:.2} Mbit for {} triangles per object, {} list words, {} leaves (tritri gen --binning-unit --width {} --triangles {} --list-words {} --leaves {} --depth {} --pipelines {})",
                scene.kept_a.len() + scene.kept_b.len(),
                run.cells,
                run.entries,
                run.leaves.len(),
                run.peak_frames,
                run.cycles,
                config.memory_bits() as f64 / 1e6,
                config.triangles,
                config.list_words,
                config.leaves,
                config.grid_bits,
                config.triangles,
                config.list_words,
                config.leaves,
                1u64 << config.log_depth,
                1u64 << config.log_pipelines
            )?,
            Err(why) => {
                let work = binning_work(octree);
                writeln!(
                    report,
                    "binning unit: not built for this configuration ({why}); its cost formula: {} triangles in, {} entries classified in {} cells: {} cycles",
                    work.triangles,
                    work.entries,
                    work.cells,
                    binning_cycles(&work)
                )?
            }
        }
    } else {
        writeln!(report, "broad phase: flat (every pair in the common box)")?;
    }
    let (tested, all) = (scene.pairs_tested(), scene.all_pairs());
    writeln!(
        report,
        "pairs tested: {tested} of N1*N2 = {all} ({:.3} %; the broad phase saves {:.1} %)",
        percent(tested, all),
        100.0 - percent(tested, all)
    )?;
    Ok(())
}

/// Cycles from the first triangle in to the last pair out with the octree
/// broad phase (`None` for the flat one), and how they were counted.
pub fn first_in_to_last_out(
    hardware: &HardwareArgs,
    scene: &PreparedScene,
    run: &SceneRun,
    cycles: u64,
) -> Option<(u64, String)> {
    let octree = scene.octree.as_ref()?;
    Some(match scene_binning(hardware, scene) {
        // The broad-phase top: the leaves go from the binning unit into the
        // system's banks as they stream (its cycle model), and its owner
        // filter decides the hits as they come; the filter's clocks for
        // the hits back to back bound what it adds (co-simulation holds the
        // emitted top within both).
        Ok(unit) => {
            let config = hardware.system_config();
            let top = broad_phase_cycles(config, &unit.run);
            let arrays =
                |kept: &[TaggedTriangle]| kept.iter().map(|t| t.triangle).collect::<Vec<_>>();
            let filter = top_model(
                &unit.run,
                config.triangles_per_bank,
                &arrays(&scene.kept_a),
                &arrays(&scene.kept_b),
            )
            .filter_clocks;
            (top + filter, format!("the broad-phase top: binning and narrow phase {top} + its owner filter at most {filter} cycles"))
        }
        Err(_) => {
            let owner = run.owner.map_or(0, |o| o.cycles);
            let binning = binning_cycles(&binning_work(octree));
            (binning + cycles + owner, format!("binning {binning} (cost formula) + narrow phase {cycles} + owner filter {owner} cycles, not overlapped"))
        }
    })
}

/// The binning unit on the scene's broad phase (the cycle-exact model of
/// the unit built for it), or why the unit does not apply.
pub fn scene_binning(
    hardware: &HardwareArgs,
    scene: &PreparedScene,
) -> Result<SceneBinning, String> {
    let max_leaf_level = hardware.local_frames().map(|l| l.max_leaf_level());
    bin_scene(
        scene,
        hardware.grid_bits() as usize,
        hardware.depth as usize,
        hardware.pipelines as usize,
        max_leaf_level,
    )
}

/// What the broad phase's plan asks of the binning unit (its cost formula,
/// where the unit does not apply).
fn binning_work(octree: &OctreeSchedule) -> BinningWork {
    BinningWork {
        triangles: octree.binned,
        cells: octree.cells_visited,
        entries: octree.classifications,
        cell_cycles: octree.classify_cycles,
    }
}

fn percent(part: u64, whole: u64) -> f64 {
    if whole == 0 {
        0.0
    } else {
        100.0 * part as f64 / whole as f64
    }
}

fn examples(diff: &PairDiff) -> String {
    if diff.is_empty() {
        return String::new();
    }
    let show = |what: &str, v: &[(u32, u32)]| {
        let listed: Vec<String> = v
            .iter()
            .take(5)
            .map(|(i, j)| format!("({i} {j})"))
            .collect();
        if listed.is_empty() {
            String::new()
        } else {
            format!("; {what} e.g. {}", listed.join(" "))
        }
    };
    format!(
        "{}{}",
        show("missing", &diff.missing),
        show("extra", &diff.extra)
    )
}

/// A spinner while a hardware simulation runs (they report no progress).
/// Writes the pairs into the output reserved before the run.
fn write_pairs(
    output: Option<OutputFile>,
    indices: Indices,
    a: &SceneObject,
    b: &SceneObject,
    pairs: &PairSet,
) -> anyhow::Result<()> {
    let Some(output) = output else { return Ok(()) };
    let pairs: BTreeSet<(usize, usize)> = match indices {
        Indices::Triangles => pairs
            .iter()
            .map(|&(i, j)| (i as usize, j as usize))
            .collect(),
        Indices::Faces => pairs
            .iter()
            .map(|&(i, j)| (a.face_of[i as usize], b.face_of[j as usize]))
            .collect(),
    };
    output.commit(|w| {
        for (i, j) in pairs {
            writeln!(w, "{i} {j}")?;
        }
        Ok(())
    })
}

/// The scene through the broad-phase top on the chosen engine, as a
/// [`SceneRun`]; what the top's models say is reported, and a fault sets
/// `status` to 1.
fn run_on_top(
    args: &Args,
    scene: &PreparedScene,
    report: &mut dyn Write,
    status: &mut ExitCode,
) -> anyhow::Result<SceneRun> {
    let max_leaf_level = args.hardware.local_frames().map(|l| l.max_leaf_level());
    let config = args.hardware.system_config();
    let top = run_scene_on_top(
        scene,
        config,
        args.hardware.grid_bits() as usize,
        max_leaf_level,
        args.engine.simulator(),
    )?;
    writeln!(
        report,
        "broad-phase top {} in {}: {} pairs tested, {} hits, {} pairs out once each, {} without a certificate; binned at clock {}, done at {} (its models: {} to {}){}",
        top.config.unit_name(),
        args.engine.name(),
        top.output.pairs_tested,
        top.output.hits,
        top.pairs.len(),
        top.uncertain.len(),
        top.output.binned_at,
        top.output.cycles,
        top.model_cycles,
        top.model_cycles + top.model.filter_clocks,
        if top.faults().is_empty() { "; its pairs equal its model's".to_string() } else { String::new() }
    )?;
    for fault in top.faults() {
        writeln!(report, "broad-phase top: {fault}")?;
        *status = ExitCode::from(1);
    }
    Ok(SceneRun {
        engine: args.engine,
        pairs: top.pairs,
        uncertain: top.uncertain,
        owner: None,
        cycles: top.output.cycles,
        model_cycles: top.model_cycles,
        counters: None,
    })
}

/// The render's file, checked before any work: `.png`, not `-`, writable.
fn reserve_png(path: &str) -> anyhow::Result<OutputFile> {
    if path == "-" || !path.to_ascii_lowercase().ends_with(".png") {
        anyhow::bail!("{path}: the render is written to a .png file");
    }
    OutputFile::reserve(path)
}

/// Renders the scene with `pairs` highlighted into the reserved file.
fn write_render(
    png: Option<OutputFile>,
    args: &Args,
    a: &SceneObject,
    b: &SceneObject,
    pairs: &PairSet,
    report: &mut dyn Write,
) -> anyhow::Result<()> {
    let Some(png) = png else { return Ok(()) };
    let image = render_pairs(&a.triangles, &b.triangles, pairs, &args.view.view());
    png.commit(|w| write_png(&image, w))?;
    writeln!(
        report,
        "render: {} ({} pairs highlighted: A's triangles red, B's magenta)",
        args.png.as_deref().unwrap_or(""),
        pairs.len()
    )?;
    Ok(())
}

/// What a cycle-by-cycle run will take, before it starts.
fn estimate(engine: Engine, cycles: u64, scene: &PreparedScene) -> String {
    let seconds = engine
        .system_cycles_per_second()
        .map_or(0.0, |rate| cycles as f64 / rate);
    let triangles: u64 = scene
        .batches()
        .iter()
        .map(|b| (b.a.len() + b.b.len()) as u64)
        .sum();
    let disk = match engine.simulator() {
        Some(_) => format!(
            ", vectors about {:.1} MB streamed through a pipe (not stored)",
            (triangles * VECTOR_BYTES_PER_TRIANGLE) as f64 / 1e6
        ),
        None => String::new(),
    };
    format!(
        "{cycles} system cycles (cycle model), about {} with --engine {} on this machine{disk}",
        human(std::time::Duration::from_secs_f64(seconds)),
        engine.name()
    )
}
