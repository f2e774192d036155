//! `tritri sim [--scene A B] [--pose-b tx,ty,tz,rx,ry,rz] [--scale-b S]
//! [--subdivide K] [--engine model|rusthdl|icarus|verilator] [--out PAIRS]
//! [--grid-verdicts] [--verbose] [--json FILE]
//! [--png FILE [--eye X,Y,Z] [--up x|y|z] [--size PX]] [--tolerance T]
//! [--data-bits 64|128|256] [--memory-gbytes G] [--link-gbytes G] [--clock-mhz F]
//! [--broad-phase octree|flat [--width W] [--pipelines P] [--depth N]
//! [--grid-bits G] [--broad-phase-top] [--rare-cases parallel|shared]
//! [--vcd FILE]]`
//!
//! Two objects (without `--scene`, the built-in torus and sphere) to their
//! exact intersecting pairs through the accelerator. By default
//! (`--broad-phase dram`) that is the design that fits the ECP5-85: the
//! scene in DRAM behind an AXI4 port, binned, tested and reported once in
//! hardware, timed at its post-route clock with the board's memory and
//! link (the library's `tritri_cosim::dram_query::find_pairs_in_dram`;
//! this command's `dram` module prints it). `--broad-phase octree` and
//! `flat` run the on-chip design studies instead, through
//! `tritri_cosim::scene_query::find_pairs`: the host prepares the scene
//! (common box, one grid of G bits, the broad phase: octree leaves, or the
//! thesis's flat common box; `docs/broad-phase.md`), the engine runs the
//! system, and the verdicts without a certificate (`out_certain = 0`,
//! docs/certificates.md) are decided again on the original coordinates.
//! An option of one design given to the other is refused by name. This
//! command parses the options and prints the answer: four lines by
//! default (the scene, the exact pairs, the time against the software
//! baseline, the checks), every line of the run with `--verbose`, every
//! figure as JSON with `--json`. The report goes to stdout, or to stderr
//! when the pairs go to stdout with `--out -`.
//!
//! `--tolerance T` tessellates `.bpt` objects for the query
//! (`tritri_geom::bezier::query`): only the patches that can meet the
//! other object, each as finely as `T` asks.
//!
//! `--broad-phase-top` (with a hardware engine) runs the broad-phase top
//! instead: the binning unit, the system and the owner filter in one
//! emitted design, each object's triangles in once and each pair out once
//! (`tritri gen --broad-phase`), held to its models (pairs; `done` between
//! the binning unit and system's cycle model and that plus the owner
//! filter's clocks). W = 24, or W = 16 with `--grid-bits 24`.
//!
//! `--out PAIRS` writes the exact pairs, one `i j` per line in ascending
//! order: `i` indexes A's triangles and `j` B's, in file order with
//! polygons split into fans (`--indices faces` reports face indices
//! instead, deduplicated). `--grid-verdicts` writes the grid's raw
//! verdicts instead, for studying quantization.
//!
//! `--png FILE` renders both objects from the direction `--eye` (from the
//! scene's centre; `--up` names the axis pointing up) with the triangles
//! of the written pairs highlighted: A's in red, B's in magenta.
//!
//! Engines (`tritri_cosim::engine`), on the DRAM design: `model` is the
//! top's clock-exact model with the bit-exact narrow phase on its leaves;
//! `rusthdl` simulates the top in rust-hdl against the AXI4 memory model,
//! and `icarus` and `verilator` run its emitted Verilog against
//! `axi_memory.sv`, cycle by cycle, held to the model's walk and pairs
//! (`--max-cycles` refuses a run whose model takes longer). On the design
//! studies: `model` is the bit-exact fixed-point model with the system's
//! exact cycle model; `rusthdl` simulates the system (memories, address
//! generator, P Devillers–Guigue pipelines, result FIFO) in rust-hdl, and
//! `icarus` and `verilator` run its emitted Verilog, all cycle by cycle
//! (slow: use small scenes), reporting the simulated cycle count.
//!
//! Before a design study's cycle-by-cycle run the report gives
//! an estimate (cycles from the cycle model, time at the engine's measured
//! speed, vector file size); above `--max-cycles` (default: what the
//! engine runs in about five minutes) the run is refused. The vectors are
//! streamed to the simulator through a pipe, so nothing grows with the
//! run but the pairs. Progress shows as a bar on a terminal and as a line
//! every ten seconds otherwise (pairs for the model, cycles for the
//! others). `--out`, `--json` and `--vcd` are checked before any work and
//! written atomically; `--vcd FILE` records the system's waveform (Icarus
//! or Verilator, runs of at most `--vcd-max-cycles`).
//!
//! Exit status: 0 done; 1 a fault (`tritri_cosim::fault::Fault`: the
//! engine disagrees with the exact model on the quantized coordinates, its
//! cycle count with the cycle model, a simulation with its model, the
//! binning unit's model with the planner; each a bug, named on stderr as
//! `fault: ...`), a simulator that failed, or a runtime failure; 2 a scene
//! file cannot be read (the error names the file and line), an unwritable
//! `--out`, a width without hardware, a run above `--max-cycles`, the
//! arrays exceed D with `--no-split`, or bad usage; 130 / 143 interrupted
//! (simulators stopped, temporaries removed).

use crate::model_files::write_png;
use crate::output_file::OutputFile;
use crate::progress::Progress;
use crate::scene_input::{human, pipeline_latency, BroadPhase, HardwareArgs, SceneArgs};
use crate::voxelize::ViewArgs;
use clap::ValueEnum;
use std::collections::BTreeSet;
use std::io::Write;
use std::process::ExitCode;
use std::time::Duration;
use tritri_cosim::binning_unit::SceneBinning;
use tritri_cosim::engine::Engine;
use tritri_cosim::scene_query::{
    prepare_query, Accelerator, Binning, HardwareRun, PreparedQuery, QueryError, QueryOptions,
    SceneAnswer, WholeCount,
};
use tritri_geom::bounding_volume::Aabb;
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::reference::{PairDiff, PairSet};
use tritri_geom::scene::render::render_pairs;
use tritri_geom::scene::PreparedScene;
use tritri_rtl::broad_phase::owner_filter::SLOT_WORD_BITS;
use tritri_rtl::pipeline::pipeline_for_width::check_width;
use tritri_rtl::pipeline::RareCasePath;

mod dram;

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
    /// The default, kept for scripts: every pair without a certificate
    /// (`out_certain = 0`) is decided again on the original coordinates.
    #[arg(long, hide = true, conflicts_with = "grid_verdicts")]
    certified: bool,
    /// Write the grid's raw verdicts with --out (and highlight them with
    /// --png) instead of the exact answer: for studying quantization.
    #[arg(long)]
    grid_verdicts: bool,
    /// Print the broad phase, the binning unit, the engine's counters, the
    /// cycles and the certificates line by line.
    #[arg(long, short)]
    verbose: bool,
    /// Write every figure of the run as JSON here (`-`: stdout).
    #[arg(long, value_name = "FILE")]
    json: Option<String>,
    /// Refuse a cycle-by-cycle simulation (rusthdl, icarus, verilator) longer than
    /// this many system cycles [default: what the engine runs in about
    /// five minutes here]; the estimate is printed either way.
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = crate::input::parse_cycles)]
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
    /// The design: `dram`, the accelerator that fits the ECP5-85 (the scene
    /// in DRAM behind an AXI4 port, binned, tested and reported once in
    /// hardware; W = 16, one pipeline, depth 256; docs/axi-port.md);
    /// `octree` and `flat`, the on-chip design studies that --width,
    /// --pipelines, --depth and --grid-bits set (the octree broad phase, or
    /// every pair in the common box as in the thesis; docs/broad-phase.md).
    #[arg(long, value_enum, default_value_t = Design::Dram)]
    broad_phase: Design,
    /// With --broad-phase dram: the AXI4 port's data width, 64, 128 or 256
    /// bits [default: 256, the top routed on the ECP5-85].
    #[arg(long, value_name = "BITS", value_parser = crate::input::parse_port_bits)]
    data_bits: Option<usize>,
    /// With --broad-phase dram: the DRAM's bandwidth in GB/s, reads and
    /// writes together [default: 1.6, the ECP5-5G Versa's DDR3].
    #[arg(long, value_name = "GB/S", allow_negative_numbers = true, value_parser = crate::input::parse_gbytes)]
    memory_gbytes: Option<f64>,
    /// With --broad-phase dram: the host link's bandwidth in GB/s each way
    /// [default: 0.5, the Versa's PCI Express Gen 2 x1].
    #[arg(long, value_name = "GB/S", allow_negative_numbers = true, value_parser = crate::input::parse_gbytes)]
    link_gbytes: Option<f64>,
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
    #[arg(long, value_name = "N", default_value_t = 10_000, allow_negative_numbers = true, value_parser = crate::input::parse_cycles)]
    vcd_max_cycles: u64,
}

/// Seconds of simulation allowed without `--max-cycles`.
const DEFAULT_MAX_SECONDS: f64 = 300.0;

/// Bytes of the system testbench's vectors per triangle sent.
const VECTOR_BYTES_PER_TRIANGLE: u64 = 90;

/// Bytes of the system's waveform per cycle (measured in Verilator: the
/// built-in scene, W = 24, P = 2, depth 256, 72.3 MB for 1,316 cycles).
const VCD_BYTES_PER_CYCLE: u64 = 55_000;

/// The design `tritri sim` runs (`--broad-phase`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Design {
    /// The accelerator with its scene in DRAM (`tritri_cosim::dram_query`).
    Dram,
    /// The on-chip octree broad phase.
    Octree,
    /// The thesis's flat common box.
    Flat,
}

/// Options of the on-chip design studies, by their ids, and of the DRAM
/// design: each refused by name under the other.
const STUDY_OPTIONS: [&str; 9] = [
    "width",
    "pipelines",
    "depth",
    "no_split",
    "grid_bits",
    "rare_cases",
    "broad_phase_top",
    "vcd",
    "vcd_max_cycles",
];
const DRAM_OPTIONS: [&str; 3] = ["data_bits", "memory_gbytes", "link_gbytes"];

/// An error naming the first option `given` on the command line that does
/// not apply to the chosen design.
fn refuse_options(design: Design, given: &[String]) -> Result<(), String> {
    let flag = |id: &str| format!("--{}", id.replace('_', "-"));
    let (refused, why) = match design {
        Design::Dram => (
            &STUDY_OPTIONS[..],
            "sets the on-chip design studies (--broad-phase octree or flat); the DRAM design is fixed: W = 16 on a 16-bit grid, one pipeline, depth 256, the rare pairs on a shared unit",
        ),
        Design::Octree | Design::Flat => (
            &DRAM_OPTIONS[..],
            "applies to --broad-phase dram, the design with its scene in DRAM",
        ),
    };
    match given.iter().find(|id| refused.contains(&id.as_str())) {
        Some(id) => Err(format!(
            "{} does not apply to --broad-phase {}: it {why}",
            flag(id),
            design
                .to_possible_value()
                .map_or(String::new(), |v| v.get_name().to_string())
        )),
        None => Ok(()),
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Indices {
    Triangles,
    Faces,
}

/// Default scene of `tritri sim` without `--scene`.
pub const DEFAULT_SCENE: [&str; 2] = ["@torus", "@sphere"];

/// Pairs above which the model's progress is shown.
const PROGRESS_THRESHOLD: u64 = 5_000_000;

pub fn run(args: Args, given: &[String]) -> anyhow::Result<ExitCode> {
    if let Err(e) = refuse_options(args.broad_phase, given) {
        eprintln!("error: {e}");
        return Ok(ExitCode::from(2));
    }
    let rare_cases = RareCasePath::parse(&args.rare_cases).unwrap_or_default();
    let accelerator = Accelerator {
        rare_cases,
        broad_phase: match args.broad_phase {
            Design::Flat => BroadPhase::Flat,
            Design::Octree | Design::Dram => BroadPhase::Octree,
        },
        ..args.hardware.accelerator()
    };
    let dram = dram::accelerator(&args, given);
    let checked = if args.broad_phase == Design::Dram {
        dram.validate()
    } else {
        accelerator.validate()
    };
    if let Err(e) = checked {
        eprintln!("error: {e}");
        return Ok(ExitCode::from(2));
    }
    if let (true, true, Err(e)) = (
        args.broad_phase != Design::Dram,
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
        && (!args.engine.is_hardware() || args.vcd.is_some() || args.broad_phase != Design::Octree)
    {
        eprintln!("error: --broad-phase-top runs the emitted top: it needs --engine rusthdl, icarus or verilator, the octree broad phase, and no --vcd");
        return Ok(ExitCode::from(2));
    }
    if args.vcd.is_some() && args.engine.simulator().is_none() {
        eprintln!("error: --vcd needs --engine icarus or verilator (the emitted Verilog), not --engine {}", args.engine.name());
        return Ok(ExitCode::from(2));
    }
    let inputs: Vec<&str> = args.scene.files();
    let reserve = |path: &str| OutputFile::reserve_apart(path, &inputs);
    let output = match args.out.as_deref().map(reserve).transpose() {
        Ok(output) => output,
        Err(e) => {
            eprintln!("error: --out: {e:#}");
            return Ok(ExitCode::from(2));
        }
    };
    let json = match args.json.as_deref().map(reserve).transpose() {
        Ok(json) => json,
        Err(e) => {
            eprintln!("error: --json: {e:#}");
            return Ok(ExitCode::from(2));
        }
    };
    let vcd = match args
        .vcd
        .as_deref()
        .filter(|p| *p != "-")
        .map(reserve)
        .transpose()
    {
        Ok(vcd) => vcd,
        Err(e) => {
            eprintln!("error: --vcd: {e:#}");
            return Ok(ExitCode::from(2));
        }
    };
    let png = match args
        .png
        .as_deref()
        .map(|p| crate::output_file::refuse_input(p, &inputs).and_then(|()| reserve_png(p)))
        .transpose()
    {
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
        Box::new(crate::stdout::Stdout)
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
    if args.verbose {
        writeln!(report, "box of A: {}", show_box(&scene_box(&a)))?;
        writeln!(report, "box of B: {}", show_box(&scene_box(&b)))?;
    }
    if args.broad_phase == Design::Dram {
        let files = dram::Files { output, json, png };
        return dram::run(&args, &dram, &a, &b, files, &mut report);
    }

    let prepared = match prepare_query(&a, &b, &accelerator) {
        Ok(prepared) => prepared,
        Err(QueryError::Scene(e @ tritri_geom::scene::SceneError::ExceedsDepth { .. }))
        | Err(QueryError::Scene(e @ tritri_geom::scene::SceneError::ZeroDepth)) => {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(2));
        }
        Err(QueryError::Unsupported(e)) => {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(2));
        }
        Err(e) => return Err(e.into()),
    };
    if prepared.scene.common.is_none() {
        writeln!(report, "no overlap: the bounding boxes of A and B do not meet, so no triangle pair can intersect; zero pairs tested")?;
        write_pairs(output, args.indices, &a, &b, &PairSet::new())?;
        write_render(png, &args, &a, &b, &PairSet::new(), &mut report)?;
        return Ok(ExitCode::SUCCESS);
    }
    if args.verbose {
        print_filter(&mut report, &prepared)?;
    }

    let model_cycles = prepared.model_cycles(args.broad_phase_top);
    if args.engine.is_hardware() {
        writeln!(
            report,
            "estimate: {}",
            estimate(args.engine, model_cycles, &prepared.scene)
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
            prepared.scene.pairs_tested(),
            args.engine.progress_unit(),
            PROGRESS_THRESHOLD,
        )
    };
    let options = QueryOptions {
        engine: args.engine,
        on_top: args.broad_phase_top,
        progress: &|n| progress.inc(n),
        vcd: vcd.as_ref().and_then(OutputFile::temporary),
        check: !args.no_compare,
    };
    let answer = prepared.run(&options);
    progress.finish();
    let answer = match answer {
        Ok(answer) => answer,
        Err(QueryError::Unsupported(e)) => {
            eprintln!("error: --engine {}: {e}", args.engine.name());
            return Ok(ExitCode::from(2));
        }
        Err(e) => {
            // A simulator that failed, or disagreed with its model on the
            // way: a bug, not bad usage.
            eprintln!("error: --engine {}: {e}", args.engine.name());
            return Ok(ExitCode::from(1));
        }
    };
    let Some(hardware) = &answer.hardware else {
        anyhow::bail!(
            "the boxes meet, yet the accelerator's run is missing from the answer (a bug)"
        );
    };
    if let (Some(vcd), Some(path)) = (vcd, &args.vcd) {
        let size = vcd.commit_written()?;
        writeln!(
            report,
            "waveform: {path} ({:.1} MB, {} cycles)",
            size as f64 / 1e6,
            hardware.run.cycles
        )?;
    }
    let written = if args.grid_verdicts {
        &hardware.run.pairs
    } else {
        &answer.pairs
    };
    if args.verbose {
        print_run(&mut report, &args, &answer, hardware)?;
    } else {
        print_summary(&mut report, &args, &answer, hardware)?;
    }
    write_pairs(output, args.indices, &a, &b, written)?;
    write_render(png, &args, &a, &b, written, &mut report)?;
    finish(
        json,
        || Ok(answer_json(&args, &answer, hardware)),
        &answer.faults,
        &mut report,
    )
}

/// The end of a run: `--json` written (when reserved), each fault named on
/// stderr; the status, 1 on a fault.
fn finish(
    json: Option<OutputFile>,
    value: impl FnOnce() -> anyhow::Result<serde_json::Value>,
    faults: &[tritri_cosim::fault::Fault],
    report: &mut dyn Write,
) -> anyhow::Result<ExitCode> {
    if let Some(json) = json {
        let value = value()?;
        json.commit(|w| {
            serde_json::to_writer_pretty(&mut *w, &value)?;
            writeln!(w)?;
            Ok(())
        })?;
    }
    let mut status = ExitCode::SUCCESS;
    for fault in faults {
        eprintln!("fault: {fault}");
        status = ExitCode::from(1);
    }
    report.flush()?;
    Ok(status)
}

/// The default report: the answer, the time against software, the checks.
fn print_summary(
    report: &mut dyn Write,
    args: &Args,
    answer: &SceneAnswer,
    hardware: &HardwareRun,
) -> anyhow::Result<()> {
    let grid = &hardware.run.pairs;
    let redecided = &hardware.redecided;
    writeln!(
        report,
        "exact pairs: {} (the grid's {} hits; {} verdicts without a certificate decided again on the original coordinates, {} changed){}",
        answer.pairs.len(),
        grid.len(),
        hardware.run.uncertain.len(),
        redecided.changed,
        if args.grid_verdicts { "; --out has the grid's verdicts" } else { "" }
    )?;
    let clock = answer.accelerator.clock;
    if let Some(whole) = answer.end_to_end() {
        let software = answer.check.as_ref().map(|c| c.software);
        let two_threads = answer.check.as_ref().map(|c| c.software_two_threads);
        let ratio = |t: Duration| {
            software.map_or(String::new(), |s| {
                format!(
                    ": {:.1} x",
                    s.as_secs_f64() / t.as_secs_f64().max(f64::MIN_POSITIVE)
                )
            })
        };
        writeln!(
            report,
            "time: accelerator {} cycles first triangle in to last pair out = {} at {} MHz ({}){}{}; end to end {} (host {}, re-decisions {}){}",
            whole.cycles,
            human(whole.accelerator),
            clock.mhz,
            clock.source.name(),
            ratio(whole.accelerator),
            software.zip(two_threads).map_or(String::new(), |(s, s2)| format!(" the software baseline {} (box sweep + exact predicates, one thread; {} on two)", human(s), human(s2))),
            human(whole.total()),
            human(whole.host),
            human(whole.redecide),
            ratio(whole.total()),
        )?;
    }
    print_check(report, answer.engine, answer.check.as_ref())?;
    writeln!(
        report,
        "details: --verbose (broad phase, binning, cycles, certificates); every figure: --json FILE"
    )?;
    Ok(())
}

/// The summary's check line, for both designs: the engine against the
/// exact model on the grid, the exact pairs against exact f64.
fn print_check(
    report: &mut dyn Write,
    engine: Engine,
    check: Option<&tritri_cosim::scene_query::Check>,
) -> anyhow::Result<()> {
    match check {
        Some(check) => writeln!(
            report,
            "check: {} = exact model on the grid ({}); exact pairs = exact f64 on the original coordinates ({} missing, {} extra)",
            engine.name(),
            if check.engine_vs_grid.is_empty() { "equal".to_string() } else { format!("{} missing, {} extra: a bug", check.engine_vs_grid.missing.len(), check.engine_vs_grid.extra.len()) },
            check.answer_vs_truth.missing.len(),
            check.answer_vs_truth.extra.len()
        )?,
        None => writeln!(report, "check: skipped (--no-compare)")?,
    }
    Ok(())
}

/// `--verbose`: the engine's run line by line.
fn print_run(
    report: &mut dyn Write,
    args: &Args,
    answer: &SceneAnswer,
    hardware: &HardwareRun,
) -> anyhow::Result<()> {
    let run = &hardware.run;
    let scene = &answer.scene;
    let clock = answer.accelerator.clock;
    let at = format!("{} MHz ({})", clock.mhz, clock.source.name());
    writeln!(
        report,
        "host: common box, quantization and broad phase in software took {} (this machine)",
        human(answer.host)
    )?;
    if let Some(top) = &hardware.top {
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
            if top.faults().is_empty() { "; its pairs equal its model's" } else { "" }
        )?;
    }
    writeln!(report, "engine: {}", args.engine.describe())?;
    if let Some(c) = run.counters {
        writeln!(
            report,
            "hardware: {} pairs tested by the hardware's counter (wraps at 2^32), {} hits, {} stall cycles; cycle model {}",
            c.pairs_tested, c.hits, c.stall_cycles, run.model_cycles
        )?;
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
    }
    writeln!(
        report,
        "intersecting pairs on the grid: {}",
        run.pairs.len()
    )?;
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
    writeln!(
        report,
        "exact pairs: the {} pairs without a certificate decided again on the original coordinates in {} ({} verdicts changed): {} intersecting pairs",
        run.uncertain.len(),
        human(hardware.redecided.host),
        hardware.redecided.changed,
        answer.pairs.len()
    )?;
    let cycles = &hardware.cycles;
    writeln!(
        report,
        "cycles: {} ({} pipelines, pipeline latency {}, banks overlapped), time at {at}: {}",
        cycles.narrow,
        answer.accelerator.pipelines,
        pipeline_latency(),
        human(answer.accelerator.time_of(cycles.narrow))
    )?;
    let rare = &hardware.rare;
    let simulated = match (answer.accelerator.rare_cases == RareCasePath::Shared, run.counters) {
        (true, Some(c)) => format!(
            "; simulated with them there ({}): {} stall cycles",
            args.engine.name(),
            c.stall_cycles
        ),
        (true, None) => "; the model engine does not simulate the stalls: the first-in-to-last-out count adds the bound".to_string(),
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
    let how = match cycles.count {
        WholeCount::NarrowPhase => "the flat system's narrow phase".to_string(),
        WholeCount::TopModel { top, filter } => format!("the broad-phase top: binning and narrow phase {top} + its owner filter at most {filter} cycles"),
        WholeCount::Sum { binning, narrow, owner } => format!("binning {binning} (cost formula) + narrow phase {narrow} + owner filter {owner} cycles, not overlapped"),
        WholeCount::SimulatedTop { binned_at } => format!("simulated: the broad-phase top in {}, binned at clock {binned_at}", args.engine.name()),
    };
    let stalls = if cycles.stall_bound > 0 {
        format!(
            " + at most {} stall cycles for the shared rare-case units",
            cycles.stall_bound
        )
    } else {
        String::new()
    };
    writeln!(
        report,
        "first triangle in to last pair out: {} cycles ({how}{stalls}), {} at {at}",
        cycles.whole,
        human(answer.accelerator.time_of(cycles.whole))
    )?;
    if let Some(whole) = answer.end_to_end() {
        writeln!(
            report,
            "end to end, first f64 triangle in to last exact pair out: host {} + accelerator {} + re-decisions {} = {} (the transfer to the board not counted)",
            human(whole.host),
            human(whole.accelerator),
            human(whole.redecide),
            human(whole.total())
        )?;
    }
    let Some(check) = &answer.check else {
        return Ok(());
    };
    if check.engine_vs_grid.is_empty() {
        writeln!(
            report,
            "check: engine = exact model on the quantized coordinates ({} pairs): equal",
            check.quantized.len()
        )?;
    } else {
        writeln!(
            report,
            "check: engine DIFFERS from the exact model on the quantized coordinates: {} missing, {} extra (a bug){}",
            check.engine_vs_grid.missing.len(),
            check.engine_vs_grid.extra.len(),
            examples(&check.engine_vs_grid)
        )?;
    }
    writeln!(
        report,
        "exact f64 on the original coordinates, all {} pairs ({} with overlapping triangle boxes decided): {} intersecting",
        scene.all_pairs(),
        check.truth.pairs_decided,
        check.truth.pairs.len()
    )?;
    writeln!(
        report,
        "work: pairs tested {} = {:.2} x the box-overlap pairs ({}) = {:.2e} of N1*N2",
        scene.pairs_tested(),
        scene.pairs_tested() as f64 / check.truth.pairs_decided.max(1) as f64,
        check.truth.pairs_decided,
        scene.pairs_tested() as f64 / scene.all_pairs().max(1) as f64
    )?;
    let ratio = |hardware: Duration| {
        check.software.as_secs_f64() / hardware.as_secs_f64().max(f64::MIN_POSITIVE)
    };
    let narrow = answer.accelerator.time_of(cycles.narrow);
    let whole = answer.accelerator.time_of(cycles.whole);
    writeln!(
        report,
        "speed: software (box sweep + exact predicates, one thread, triangles in memory) {}; the system's cycles {} at {at}: {:.1} x; first triangle in to last pair out {}: {:.1} x",
        human(check.software),
        human(narrow),
        ratio(narrow),
        human(whole),
        ratio(whole)
    )?;
    writeln!(
        report,
        "quantization error (grid of {} bits): {} pairs missing, {} extra against exact f64{}",
        answer.accelerator.grid_bits,
        check.grid_vs_truth.missing.len(),
        check.grid_vs_truth.extra.len(),
        examples(&check.grid_vs_truth)
    )?;
    writeln!(
        report,
        "exact pairs: {} missing, {} extra against exact f64{}",
        check.answer_vs_truth.missing.len(),
        check.answer_vs_truth.extra.len(),
        examples(&check.answer_vs_truth)
    )?;
    Ok(())
}

/// `--json`: every figure of the answer, for scripts.
fn answer_json(args: &Args, answer: &SceneAnswer, hardware: &HardwareRun) -> serde_json::Value {
    let pairs = |set: &PairSet| set.iter().map(|&(i, j)| [i, j]).collect::<Vec<_>>();
    let diff =
        |d: &PairDiff| serde_json::json!({ "missing": d.missing.len(), "extra": d.extra.len() });
    let acc = &answer.accelerator;
    let scene = &answer.scene;
    let whole = answer.end_to_end();
    let binning = match &answer.binning {
        Binning::None => serde_json::Value::Null,
        Binning::Unit(unit) => serde_json::json!({
            "model": "clock-exact",
            "cycles": unit.run.cycles,
            "leaves": unit.run.leaves.len(),
            "memory_bits": unit.config.memory_bits(),
        }),
        Binning::Formula { why, cycles, .. } => serde_json::json!({
            "model": "cost formula",
            "why": why.to_string(),
            "cycles": cycles,
        }),
    };
    serde_json::json!({
        "scene": {
            "a": answer_name(&args.scene, 0),
            "b": answer_name(&args.scene, 1),
            "triangles_a": scene.n_a,
            "triangles_b": scene.n_b,
            "kept_a": scene.kept_a.len(),
            "kept_b": scene.kept_b.len(),
            "pairs_tested": scene.pairs_tested(),
            "all_pairs": scene.all_pairs(),
            "leaves": scene.octree.as_ref().map(|o| o.leaves.len()),
        },
        "accelerator": {
            "width": acc.width,
            "grid_bits": acc.grid_bits,
            "pipelines": acc.pipelines,
            "depth": acc.depth,
            "broad_phase": if acc.broad_phase == BroadPhase::Octree { "octree" } else { "flat" },
            "rare_cases": acc.rare_cases.name(),
            "clock_mhz": acc.clock.mhz,
            "clock": acc.clock.source.name(),
        },
        "engine": answer.engine.name(),
        "pairs": pairs(&answer.pairs),
        "grid_pairs": pairs(&hardware.run.pairs),
        "uncertain": pairs(&hardware.run.uncertain),
        "changed": hardware.redecided.changed,
        "binning": binning,
        "cycles": {
            "narrow_phase": hardware.cycles.narrow,
            "first_in_to_last_out": hardware.cycles.whole,
            "stall_bound": hardware.cycles.stall_bound,
            "cycle_model": hardware.run.model_cycles,
        },
        "seconds": {
            "host": answer.host.as_secs_f64(),
            "accelerator": whole.map(|w| w.accelerator.as_secs_f64()),
            "redecide": hardware.redecided.host.as_secs_f64(),
            "end_to_end": whole.map(|w| w.total().as_secs_f64()),
            "software": answer.check.as_ref().map(|c| c.software.as_secs_f64()),
            "software_two_threads": answer.check.as_ref().map(|c| c.software_two_threads.as_secs_f64()),
        },
        "check": answer.check.as_ref().map(|c| serde_json::json!({
            "engine_vs_grid": diff(&c.engine_vs_grid),
            "grid_vs_exact_f64": diff(&c.grid_vs_truth),
            "pairs_vs_exact_f64": diff(&c.answer_vs_truth),
            "exact_f64_pairs": c.truth.pairs.len(),
        })),
        "faults": answer.faults.iter().map(|f| f.to_string()).collect::<Vec<_>>(),
    })
}

/// The name of object `k` as given (the built-in scene without `--scene`).
fn answer_name(scene: &SceneArgs, k: usize) -> String {
    scene
        .scene
        .as_ref()
        .map_or(DEFAULT_SCENE[k].to_string(), |v| v[k].clone())
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

fn print_filter(report: &mut dyn Write, prepared: &PreparedQuery) -> anyhow::Result<()> {
    let scene = &prepared.scene;
    writeln!(report, "common BV: {}", show_box(&scene.common))?;
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
            prepared.accelerator.grid_bits, frame.step, frame.centre
        )?;
        if let Some(local) = prepared.accelerator.local_frames() {
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
        match &prepared.binning {
            Binning::Unit(SceneBinning { config, run }) => writeln!(
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
            Binning::Formula { why, work, cycles } => writeln!(
                report,
                "binning unit: {why}; its cost formula: {} triangles in, {} entries classified in {} cells: {} cycles",
                work.triangles,
                work.entries,
                work.cells,
                cycles
            )?,
            Binning::None => {}
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
