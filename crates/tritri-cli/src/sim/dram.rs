//! `tritri sim --broad-phase dram` (the default): the accelerator that fits
//! the ECP5-85 on the scene, through the library's route
//! (`tritri_cosim::dram_query::find_pairs_in_dram`). This module only
//! builds the route's options from the command line and prints its answer.

use super::{examples, finish, print_check, write_pairs, write_render, Args};
use crate::output_file::OutputFile;
use crate::scene_input::human;
use serde_json::json;
use std::io::Write;
use std::process::ExitCode;
use std::time::Duration;
use tritri_cosim::dram_query::{
    find_pairs_in_dram, DramAccelerator, DramAnswer, DramQueryOptions, DramRun, BANDWIDTHS,
    TABLE_WORDS,
};
use tritri_cosim::engine::Engine;
use tritri_cosim::scene_query::{Clock, ClockSource, QueryError};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::reference::{PairDiff, PairSet};
use tritri_geom::two_objects;

/// The files reserved before any work.
pub(super) struct Files {
    pub output: Option<OutputFile>,
    pub json: Option<OutputFile>,
    pub png: Option<OutputFile>,
}

/// The DRAM design the options describe: the port of `--data-bits` at its
/// post-route clock (or `--clock-mhz`, assumed, when given), the memory
/// and link of `--memory-gbytes` and `--link-gbytes`.
pub(super) fn accelerator(args: &Args, given: &[String]) -> DramAccelerator {
    let mut dram = DramAccelerator::with_port(args.data_bits.unwrap_or(256));
    if given.iter().any(|id| id == "clock_mhz") {
        dram.clock = Clock {
            mhz: args.hardware.clock_mhz,
            source: ClockSource::Assumed,
        };
    }
    if let Some(g) = args.memory_gbytes {
        dram.memory_gbytes = g;
    }
    if let Some(g) = args.link_gbytes {
        dram.link_gbytes = g;
    }
    dram
}

/// Runs the route and prints it; the status is 1 on a fault.
pub(super) fn run(
    args: &Args,
    dram: &DramAccelerator,
    a: &SceneObject,
    b: &SceneObject,
    files: Files,
    report: &mut dyn Write,
) -> anyhow::Result<ExitCode> {
    if args.engine.is_hardware() {
        writeln!(
            report,
            "running {} in {} against the AXI4 memory model (the top's model first, then the emitted design cycle by cycle: seconds to minutes)",
            dram.unit_name(),
            args.engine.name()
        )?;
    }
    let options = DramQueryOptions {
        engine: args.engine,
        check: !args.no_compare,
        max_clocks: args.max_cycles,
        ..DramQueryOptions::default()
    };
    let answer = match find_pairs_in_dram(a, b, dram, &options) {
        Ok(answer) => answer,
        Err(e @ (QueryError::Unsupported(_) | QueryError::Scene(_))) => {
            eprintln!("error: --broad-phase dram: {e}");
            return Ok(ExitCode::from(2));
        }
        Err(e) => {
            eprintln!("error: --engine {}: {e}", args.engine.name());
            return Ok(ExitCode::from(1));
        }
    };
    let Some(run) = &answer.run else {
        writeln!(report, "no overlap: the bounding boxes of A and B do not meet, so no triangle pair can intersect; zero pairs tested")?;
        write_pairs(files.output, args.indices, a, b, &PairSet::new())?;
        write_render(files.png, args, a, b, &PairSet::new(), report)?;
        return Ok(ExitCode::SUCCESS);
    };
    let grid = answer.grid_pairs();
    let written = if args.grid_verdicts {
        &grid
    } else {
        &answer.pairs
    };
    print_summary(report, args, &answer, run)?;
    if args.verbose {
        print_details(report, args, &answer, run)?;
    } else {
        writeln!(
            report,
            "details: --verbose (host, the design, DRAM traffic, the walk, memories of 0.4 to 25.6 GB/s); every figure: --json FILE"
        )?;
    }
    write_pairs(files.output, args.indices, a, b, written)?;
    write_render(files.png, args, a, b, written, report)?;
    finish(
        files.json,
        || answer_json(args, &answer, run),
        &answer.faults,
        report,
    )
}

/// `software / t` as "R x", or nothing without the check.
fn ratio(answer: &DramAnswer, t: Duration) -> String {
    answer.check.as_ref().map_or(String::new(), |c| {
        format!(
            ": {:.2} x",
            c.software.as_secs_f64() / t.as_secs_f64().max(f64::MIN_POSITIVE)
        )
    })
}

/// The clock, named by where it comes from.
fn clock_name(clock: &Clock) -> String {
    format!("{:.1} MHz ({})", clock.mhz, clock.source.name())
}

/// The default lines: the answer, the time against software, the checks.
fn print_summary(
    report: &mut dyn Write,
    args: &Args,
    answer: &DramAnswer,
    run: &DramRun,
) -> anyhow::Result<()> {
    writeln!(
        report,
        "exact pairs: {} (the grid's {} hits; {} verdicts without a certificate decided again on the original coordinates, {} changed){}",
        answer.pairs.len(),
        run.top.pairs.len(),
        run.top.uncertain.len(),
        run.redecided.changed,
        if args.grid_verdicts { "; --out has the grid's verdicts" } else { "" }
    )?;
    let dram = &answer.dram;
    if let Some(whole) = answer.end_to_end() {
        let software = answer.check.as_ref().map_or(String::new(), |c| {
            format!(
                " the software baseline {} (box sweep + exact predicates, one thread; {} on two)",
                human(c.software),
                human(c.software_two_threads)
            )
        });
        writeln!(
            report,
            "time: the top {} clocks start to last pair out = {} at {}, {}-bit AXI4 port, {} GB/s of DRAM{}{software}; end to end {} (host {}, {} KiB in over a {} GB/s link {}, pairs back {}, re-decisions {}){}",
            whole.clocks,
            human(whole.accelerator),
            clock_name(&dram.clock),
            dram.data_bits,
            dram.memory_gbytes,
            ratio(answer, whole.accelerator),
            human(whole.total()),
            human(whole.host),
            run.bytes_in() / 1024,
            dram.link_gbytes,
            human(whole.link_in),
            human(whole.link_back),
            human(whole.redecide),
            ratio(answer, whole.total()),
        )?;
    }
    print_check(report, answer.engine, answer.check.as_ref())?;
    Ok(())
}

/// `--verbose`: the route step by step.
fn print_details(
    report: &mut dyn Write,
    args: &Args,
    answer: &DramAnswer,
    run: &DramRun,
) -> anyhow::Result<()> {
    let (dram, scene) = (&answer.dram, &answer.scene);
    let host_threads = two_objects::threads(scene.n_a + scene.n_b);
    writeln!(
        report,
        "host: cull to the common box, quantize onto the 16-bit grid and pack the root lists (32-byte entries) in {} (this machine, {} thread{}): A {} of {} triangles kept, B {} of {}; written into DRAM, {} KiB",
        human(answer.host),
        host_threads,
        if host_threads == 1 { "" } else { "s" },
        scene.kept_a.len(),
        scene.n_a,
        scene.kept_b.len(),
        scene.n_b,
        run.bytes_in() / 1024
    )?;
    writeln!(
        report,
        "design: {} (tritri gen --dram-broad-phase --width 16 --pipelines 1 --rare-cases shared --triangles 8192 --slots 8192 --data-bits {}) at {}",
        dram.unit_name(),
        dram.data_bits,
        clock_name(&dram.clock)
    )?;
    let memory = run.memory();
    let (num, den) = memory.bytes_per_clock;
    writeln!(
        report,
        "memory: {} GB/s at {:.1} MHz = {:.2} bytes a clock, reads and writes together; at most a {}-byte beat each way a clock; latency {} clocks",
        dram.memory_gbytes,
        dram.clock.mhz,
        num as f64 / den as f64,
        memory.beat_bytes,
        memory.read_latency
    )?;
    writeln!(report, "engine: {}", engine_description(args.engine))?;
    let top = &run.top;
    writeln!(
        report,
        "walk: {}{} passes, {} leaves; binned at clock {}, last verdict at {}{}; {} pairs tested in the leaves",
        match run.cases.len() {
            1 => String::new(),
            n => format!("the common box cut into {n} regions, each within the owner filter's tables of {TABLE_WORDS} (run one after another, the clocks summed); "),
        },
        top.passes,
        top.leaves,
        top.binned_at,
        top.tested_at,
        if args.engine.is_hardware() {
            format!(
                ", done at {} (its model: binned at {}, last verdict at {})",
                top.cycles, run.model.binned_at, run.model.tested_at
            )
        } else {
            String::new()
        },
        run.pairs_tested
    )?;
    let (read, written) = run.dram_bytes();
    let bound = run.memory_bound();
    writeln!(
        report,
        "DRAM: {} KiB read, {} KiB written; that traffic takes at least {} clocks on this memory; the top {} clocks, {:.2} x that bound",
        read / 1024,
        written / 1024,
        bound,
        run.clocks(),
        run.clocks() as f64 / bound.max(1) as f64
    )?;
    writeln!(
        report,
        "exact pairs: {} hits on the grid and {} without a certificate, streamed once each; the {} decided again on the original coordinates in {} ({} changed): {} intersecting pairs",
        top.pairs.len(),
        top.uncertain.len(),
        top.uncertain.len(),
        human(run.redecided.host),
        run.redecided.changed,
        answer.pairs.len()
    )?;
    if let Some(whole) = answer.end_to_end() {
        writeln!(
            report,
            "end to end, first f64 triangle in to last exact pair out: host {} + {} KiB in {} + the top {} + {} B of pairs back {} + re-decisions {} = {}",
            human(whole.host),
            run.bytes_in() / 1024,
            human(whole.link_in),
            human(whole.accelerator),
            run.bytes_back(),
            human(whole.link_back),
            human(whole.redecide),
            human(whole.total())
        )?;
    }
    if let Some(check) = &answer.check {
        writeln!(
            report,
            "check: engine against the exact model on the quantized coordinates ({} pairs): {}",
            check.quantized.len(),
            if check.engine_vs_grid.is_empty() {
                "equal".to_string()
            } else {
                format!(
                    "{} missing, {} extra (a bug){}",
                    check.engine_vs_grid.missing.len(),
                    check.engine_vs_grid.extra.len(),
                    examples(&check.engine_vs_grid)
                )
            }
        )?;
        writeln!(
            report,
            "exact f64 on the original coordinates ({} pairs with overlapping triangle boxes decided): {} intersecting; quantization error on the 16-bit grid: {} missing, {} extra{}; exact pairs: {} missing, {} extra{}",
            check.truth.pairs_decided,
            check.truth.pairs.len(),
            check.grid_vs_truth.missing.len(),
            check.grid_vs_truth.extra.len(),
            examples(&check.grid_vs_truth),
            check.answer_vs_truth.missing.len(),
            check.answer_vs_truth.extra.len(),
            examples(&check.answer_vs_truth)
        )?;
    }
    writeln!(
        report,
        "over memory bandwidth (the top's model, {} at {}):",
        "clocks to the last verdict",
        clock_name(&dram.clock)
    )?;
    for row in answer.over_bandwidth(&BANDWIDTHS)? {
        writeln!(
            report,
            "  {:>5} GB/s: {} clocks, {}{}",
            row.gbytes,
            row.clocks,
            human(row.time),
            ratio(answer, row.time)
        )?;
    }
    Ok(())
}

/// What runs the top on `engine`.
fn engine_description(engine: Engine) -> &'static str {
    match engine {
        Engine::Model => "model: the top's clock-exact model (binning, leaf reads, the system's banks; a lower bound where the shared rare-case unit holds) and the bit-exact narrow phase on its leaves",
        Engine::Rusthdl => "rusthdl: the top in rust-hdl against the Rust AXI4 memory model, cycle by cycle",
        Engine::Icarus => "icarus: the emitted top in Icarus Verilog against axi_memory.sv, cycle by cycle",
        Engine::Verilator => "verilator: the emitted top in Verilator against axi_memory.sv, cycle by cycle",
    }
}

/// `--json`: every figure of the answer, for scripts.
fn answer_json(
    args: &Args,
    answer: &DramAnswer,
    run: &DramRun,
) -> anyhow::Result<serde_json::Value> {
    let pairs = |set: &PairSet| set.iter().map(|&(i, j)| [i, j]).collect::<Vec<_>>();
    let diff = |d: &PairDiff| json!({ "missing": d.missing.len(), "extra": d.extra.len() });
    let (dram, scene) = (&answer.dram, &answer.scene);
    let whole = answer.end_to_end();
    let (read, written) = run.dram_bytes();
    let seconds = |d: Option<Duration>| d.map(|d| d.as_secs_f64());
    let bandwidth: Vec<_> = answer
        .over_bandwidth(&BANDWIDTHS)?
        .iter()
        .map(|r| json!({ "gbytes": r.gbytes, "clocks": r.clocks, "seconds": r.time.as_secs_f64() }))
        .collect();
    Ok(json!({
        "scene": {
            "a": super::answer_name(&args.scene, 0),
            "b": super::answer_name(&args.scene, 1),
            "triangles_a": scene.n_a,
            "triangles_b": scene.n_b,
            "kept_a": scene.kept_a.len(),
            "kept_b": scene.kept_b.len(),
        },
        "accelerator": {
            "broad_phase": "dram",
            "unit": dram.unit_name(),
            "data_bits": dram.data_bits,
            "clock_mhz": dram.clock.mhz,
            "clock": dram.clock.source.name(),
            "memory_gbytes": dram.memory_gbytes,
            "link_gbytes": dram.link_gbytes,
        },
        "engine": answer.engine.name(),
        "pairs": pairs(&answer.pairs),
        "grid_pairs": pairs(&answer.grid_pairs()),
        "uncertain": run.top.uncertain.iter().map(|&(i, j)| [i, j]).collect::<Vec<_>>(),
        "changed": run.redecided.changed,
        "walk": {
            "regions": run.cases.len(),
            "passes": run.top.passes,
            "leaves": run.top.leaves,
            "pairs_tested": run.pairs_tested,
            "binned_at": run.top.binned_at,
            "tested_at": run.top.tested_at,
            "model_binned_at": run.model.binned_at,
            "model_tested_at": run.model.tested_at,
        },
        "clocks": run.clocks(),
        "dram": {
            "bytes_read": read,
            "bytes_written": written,
            "memory_bound_clocks": run.memory_bound(),
            "bytes_in": run.bytes_in(),
            "bytes_back": run.bytes_back(),
        },
        "seconds": {
            "host": answer.host.as_secs_f64(),
            "link_in": seconds(whole.map(|w| w.link_in)),
            "accelerator": seconds(whole.map(|w| w.accelerator)),
            "link_back": seconds(whole.map(|w| w.link_back)),
            "redecide": run.redecided.host.as_secs_f64(),
            "end_to_end": seconds(whole.map(|w| w.total())),
            "software": seconds(answer.check.as_ref().map(|c| c.software)),
            "software_two_threads": seconds(answer.check.as_ref().map(|c| c.software_two_threads)),
        },
        "over_bandwidth": bandwidth,
        "check": answer.check.as_ref().map(|c| json!({
            "engine_vs_grid": diff(&c.engine_vs_grid),
            "grid_vs_exact_f64": diff(&c.grid_vs_truth),
            "pairs_vs_exact_f64": diff(&c.answer_vs_truth),
            "exact_f64_pairs": c.truth.pairs.len(),
        })),
        "faults": answer.faults.iter().map(|f| f.to_string()).collect::<Vec<_>>(),
    }))
}
