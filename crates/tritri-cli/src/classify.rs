//! `tritri classify [--arith A] [--width W] FILE`
//!
//! Prints one line per pair, in file order: `1` when the closed triangles
//! intersect, `0` when not. A file with a record that cannot be read gets
//! no verdict at all: every bad record is named on stderr (file and line)
//! and the exit status is 2, so a partial answer is never mistaken for the
//! file's.
//! With `--arith fixed` the whole file is quantized into one W-bit frame,
//! whose step is printed on stderr as a note, and every verdict whose
//! certificate (the pipeline's `out_certain`) is 0 is decided again with
//! exact predicates on the file's coordinates, so the answer is the exact
//! answer; a note says how many pairs went back to the host and what that
//! took. `--grid-verdicts` prints the grid's own verdicts instead.

use crate::input;
use anyhow::Context;
use clap::ValueEnum;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use tritri_cosim::engine::{run_pipeline, Engine};
use tritri_geom::arithmetic::{classify, fit_frame, Arithmetic, Classification, DEFAULT_WIDTH};
use tritri_geom::certificate::{certified_intersects, recheck, CertifiedVerdict};
use tritri_geom::scene::TaggedTriangle;
use tritri_rtl::pipeline::pipeline_for_width::PipelineInput;

#[derive(clap::Args)]
pub struct Args {
    /// Arithmetic that decides the pairs.
    #[arg(long, value_enum, default_value_t = ArithName::Exact)]
    arith: ArithName,
    /// Coordinate width for `--arith fixed` (8 to 32 bits) [default: 24].
    #[arg(long, value_parser = input::parse_width)]
    width: Option<u32>,
    /// Who decides the fixed-point pairs: the software model, the rust-hdl
    /// simulation of the pipeline, or its emitted Verilog in Icarus or Verilator.
    #[arg(long, value_enum, default_value_t = Engine::Model)]
    engine: Engine,
    /// With a hardware engine: write a VCD waveform of the run (of the rust-hdl
    /// signals, or of the emitted Verilog in Icarus or Verilator); keep the file small.
    #[arg(long, value_name = "FILE")]
    vcd: Option<PathBuf>,
    /// The default, kept for scripts: with `--arith fixed`, every verdict
    /// without a certificate (`out_certain = 0`) is decided again on the
    /// original coordinates.
    #[arg(long, hide = true, conflicts_with = "grid_verdicts")]
    certified: bool,
    /// With `--arith fixed`: print the grid's raw verdicts instead of the
    /// exact answer, for studying quantization.
    #[arg(long)]
    grid_verdicts: bool,
    /// Pair file: 18 numbers per line, or a JSON array of {t1, t2}; `-` reads standard input.
    file: PathBuf,
}

#[derive(Clone, Copy, ValueEnum)]
enum ArithName {
    /// Exact predicates on the f64 coordinates (ground truth).
    Exact,
    /// The published Guigue-Devillers code in double precision.
    F64,
    /// The published code in single precision.
    F32,
    /// Moller 1997 with its epsilon 1e-6.
    Moller,
    /// Quantized to W-bit integers (one frame per file), exact integer predicates.
    Fixed,
}

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let arith = match (args.arith, args.width) {
        (ArithName::Fixed, width) => Arithmetic::Fixed(width.unwrap_or(DEFAULT_WIDTH)),
        (_, Some(w)) => {
            eprintln!("error: --width {w} applies only to --arith fixed");
            return Ok(ExitCode::from(2));
        }
        (ArithName::Exact, None) => Arithmetic::Exact,
        (ArithName::F64, None) => Arithmetic::F64,
        (ArithName::F32, None) => Arithmetic::F32,
        (ArithName::Moller, None) => Arithmetic::Moller,
    };
    if (args.engine != Engine::Model || args.vcd.is_some() || args.certified || args.grid_verdicts)
        && !matches!(arith, Arithmetic::Fixed(_))
    {
        eprintln!(
            "error: --engine, --vcd, --certified and --grid-verdicts apply only to --arith fixed"
        );
        return Ok(ExitCode::from(2));
    }
    if let (Arithmetic::Fixed(width), true) = (arith, args.engine.is_hardware()) {
        if let Err(e) = tritri_rtl::pipeline::pipeline_for_width::check_width(width as usize) {
            eprintln!(
                "error: --width {width} --engine {}: {e} (the model takes 8 to 32)",
                args.engine.name()
            );
            return Ok(ExitCode::from(2));
        }
    }
    if let (Some(vcd), Engine::Model) = (&args.vcd, args.engine) {
        eprintln!("error: --vcd {}: the model has no waveform; choose --engine rusthdl, icarus or verilator", vcd.display());
        return Ok(ExitCode::from(2));
    }
    let loaded = input::load(&args.file);
    if loaded.errors > 0 {
        // A file that could not be read at all has said so already.
        if loaded.file.is_some() {
            eprintln!(
                "error: {}: no verdicts: {} record(s) could not be read",
                args.file.display(),
                loaded.errors
            );
        }
        return Ok(ExitCode::from(2));
    }
    let pairs = loaded.good_pairs();
    if pairs.is_empty() {
        // Not an error (an empty list has an empty answer), but said, so
        // that a wrong file name or an empty export is not mistaken for
        // "no pair intersects".
        eprintln!(
            "note: {}: no pairs in the file, so no verdicts",
            args.file.display()
        );
    }
    // The grid's verdicts from the model alone are `classify`'s. Every
    // other fixed-point answer is decided below, with its certificates:
    // here only the frame is fitted, so that no pair is decided twice.
    let model_alone = args.engine == Engine::Model && args.grid_verdicts;
    let mut result = match arith {
        Arithmetic::Fixed(width) if !model_alone => {
            fit_frame(&pairs, width).map(|frame| Classification {
                verdicts: Vec::new(),
                frame: Some(frame),
            })
        }
        _ => classify(arith, &pairs),
    }
    .with_context(|| format!("{}", args.file.display()))?;
    if let (Arithmetic::Fixed(width), Some(frame), false) = (arith, result.frame, model_alone) {
        let grid: Vec<CertifiedVerdict> = if args.engine == Engine::Model {
            pairs
                .iter()
                .map(|p| certified_intersects(&frame.quantize(&p.t1), &frame.quantize(&p.t2)))
                .collect()
        } else {
            run_engine(
                args.engine,
                width as usize,
                &frame,
                &pairs,
                args.vcd.as_deref(),
            )?
        };
        result.verdicts = grid.iter().map(|v| v.hit).collect();
        if !args.grid_verdicts {
            let started = std::time::Instant::now();
            let run = recheck(&pairs, &grid);
            eprintln!(
                "note: {}: exact answer: {} of {} verdicts without a certificate ({:.3} %), decided again on the original coordinates in {:.3} ms; {} of them changed (--grid-verdicts prints the grid's own)",
                args.file.display(),
                run.uncertain,
                pairs.len(),
                100.0 * run.uncertain as f64 / pairs.len().max(1) as f64,
                started.elapsed().as_secs_f64() * 1e3,
                run.changed
            );
            result.verdicts = run.verdicts;
        }
    }
    if let Some(frame) = result.frame {
        eprintln!(
            "note: {}: {arith}: {} pairs quantized into one frame, step h = {:e}, centre {:?}",
            args.file.display(),
            pairs.len(),
            frame.step,
            frame.centre
        );
    }
    let mut out = BufWriter::new(crate::stdout::Stdout);
    for v in &result.verdicts {
        writeln!(out, "{}", u8::from(*v))?;
    }
    out.flush()?;
    Ok(ExitCode::SUCCESS)
}

/// Decides the quantized pairs on a hardware engine: per pair one `bset`
/// cycle loads t1 and the next cycle tests t2, both tagged with the pair's
/// index; the verdicts come back in order and their ids are checked.
fn run_engine(
    engine: Engine,
    width: usize,
    frame: &tritri_geom::quantize::Frame,
    pairs: &[tritri_geom::TrianglePair],
    vcd: Option<&std::path::Path>,
) -> anyhow::Result<Vec<CertifiedVerdict>> {
    let schedule: Vec<PipelineInput> = pairs
        .iter()
        .enumerate()
        .flat_map(|(i, p)| {
            let id = i as u32;
            [
                PipelineInput::load_base(&TaggedTriangle {
                    id,
                    triangle: frame.quantize(&p.t1),
                }),
                PipelineInput::test(&TaggedTriangle {
                    id,
                    triangle: frame.quantize(&p.t2),
                }),
            ]
        })
        .collect();
    if let Some(path) = vcd {
        // The simulator overwrites it; removed first so that a run writing
        // nothing is caught below instead of leaving an old waveform.
        let _ = std::fs::remove_file(path);
    }
    let result = run_pipeline(engine, width, &schedule, vcd)?.result;
    if let Some(path) = vcd {
        anyhow::ensure!(
            path.is_file(),
            "the simulation wrote no waveform to {}",
            path.display()
        );
    }
    anyhow::ensure!(
        result.verdicts.len() == pairs.len(),
        "the engine returned {} verdicts for {} pairs",
        result.verdicts.len(),
        pairs.len()
    );
    for (i, v) in result.verdicts.iter().enumerate() {
        anyhow::ensure!(
            v.base_id == i as u32 && v.stream_id == i as u32,
            "verdict {i} carries ids ({}, {})",
            v.base_id,
            v.stream_id
        );
    }
    Ok(result
        .verdicts
        .iter()
        .map(|v| CertifiedVerdict {
            hit: v.hit,
            certain: v.certain,
        })
        .collect())
}
