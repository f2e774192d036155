//! `tritri report [PAIR FILES...] [--scene A B [--pose-b ...]] [--widths W,...]
//! [--pipelines P] [--measurements FILE] --out DIR`
//!
//! Speed against error in one place: for each coordinate width W,
//!
//! - **error**, on the pair files (`@hard` for the hard-case suite): wrong
//!   verdicts, false positives and false negatives of the grid without
//!   certificates; the verdicts without a certificate and the host's time
//!   to decide them again with them (the same figures `tritri eval`
//!   prints, from the same code);
//! - **hardware cost**: Xilinx LUT / FF / DSP48E1 / CARRY4 / SRL, and the
//!   ECP5 post-route Fmax with LUT4 / FF / MULT18X18D / EBR where the
//!   pipeline was routed, from `rtl-out/measurements.json` (what `tritri gen
//!   --synth` printed; built in, or `--measurements FILE`), so a report
//!   never re-routes;
//! - **speed**: pairs/s at Fmax x P (P at most what fits the ECP5-85's
//!   multipliers), pairs/s per multiplier, and the
//!   widths on the Pareto front of throughput per multiplier against error;
//!   the software baselines (f64 and f32 Devillers–Guigue, Möller) timed on
//!   this machine in the same run;
//! - **a scene** (`--scene A B`, as `tritri sim` takes it): the octree broad
//!   phase's pairs and leaves, cycles, the time at the routed clock (or
//!   100 MHz, said so, where W has no post-route clock), against the one-
//!   thread software box sweep with exact predicates, and the error against
//!   exact f64 on the original coordinates (the same figures `tritri sim`
//!   prints, from the same code).
//!
//! Writes `DIR/report.html` (one self-contained page: tables and SVG
//! plots, each plot beside its numbers), `DIR/report.json` (everything),
//! and CSV tables (`errors.csv`, `widths.csv`, `scene.csv`), then prints a
//! summary. Exit status: 0 done; 1 a check failed (a grid or certificate
//! bug, as in `eval`) or an I/O failure; 2 bad input (nothing written).

mod page;
mod plots;
mod scene;

use crate::eval::{self, Batch, BatchReport};
use crate::input;
use crate::scene_input::SceneArgs;
use crate::stdout::outln;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;
use tritri_geom::arithmetic::Arithmetic;
use tritri_rtl::measured::{device, Device, Ecp5Row, Measurements, XilinxRow};
use tritri_rtl::pipeline::pipeline_unit::pipeline_unit_name_for;
use tritri_rtl::pipeline::RareCasePath;
use tritri_rtl::system::system_for_width::PipelineKind;
use tritri_rtl::system::system_unit::system_unit_name;
use tritri_rtl::system::SystemConfig;

/// The device the ECP5 figures were routed for.
pub fn ecp5_device() -> &'static Device {
    device("ecp5-85").expect("the device table has the ECP5-85")
}

pub use scene::SceneSection;

#[derive(clap::Args)]
pub struct Args {
    /// Pair files (as `tritri eval` takes them; `@hard` for the hard-case
    /// suite, `@hard/<category>` for one category).
    files: Vec<String>,
    #[command(flatten)]
    scene: SceneArgs,
    /// Coordinate widths W to report (each 8 to 32; the hardware is built
    /// at 8, 12, 16, 18, 20, 24, 28 and 32).
    #[arg(long, value_delimiter = ',', value_parser = input::parse_width, default_values_t = [8, 12, 16, 18, 20, 24, 28, 32])]
    widths: Vec<u32>,
    /// Pipelines P of the system whose speed is reported (pairs/s = Fmax x P).
    #[arg(long, default_value_t = 2, value_parser = crate::input::whole::<u32>(1..=tritri_rtl::system::MAX_PIPELINES as u32))]
    pipelines: u32,
    /// The measurements of synthesis and place and route to read [default:
    /// the built-in copy of rtl-out/measurements.json].
    #[arg(long, value_name = "FILE")]
    measurements: Option<PathBuf>,
    /// Minimum time spent timing each arithmetic on each pair file, in ms.
    #[arg(long, default_value_t = 50, allow_hyphen_values = true, value_parser = input::parse_min_time_ms)]
    min_time_ms: u64,
    /// The directory the report is written to (created if missing).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// Everything the report shows (`report.json`).
#[derive(Serialize)]
pub struct Report {
    /// The command line that made it.
    pub command: String,
    pub pipelines: u32,
    /// Where the hardware figures come from, and when they were measured.
    pub measurements: String,
    pub measured: String,
    /// `tritri eval` on the pair files: every batch and the total.
    pub errors: Option<Errors>,
    /// One row per width: error, cost and speed side by side.
    pub widths: Vec<WidthRow>,
    /// The software baselines on the pair files (exact, f64, f32, Möller).
    pub baselines: Vec<eval::Row>,
    pub scene: Option<SceneSection>,
}

#[derive(Serialize)]
pub struct Errors {
    pub inputs: Vec<String>,
    pub batches: Vec<BatchReport>,
    pub total: BatchReport,
}

/// Speed against error at one width.
#[derive(Serialize, Clone)]
pub struct WidthRow {
    pub width: u32,
    /// The fixed-point row of the pair files' total (`None` without files).
    pub error: Option<eval::Row>,
    /// Pairs evaluated (the denominators of the rates).
    pub pairs: usize,
    /// Where the pipeline of this row tests its rare pairs (`parallel` or
    /// `shared`): the one routed on ECP5 ([`Measurements::ecp5_pipeline`]),
    /// parallel where none was.
    pub rare_cases: RareCasePath,
    /// That pipeline under `synth_xilinx`, where measured.
    pub xilinx: Option<XilinxRow>,
    /// That pipeline placed and routed on ECP5, where measured.
    pub ecp5: Option<Ecp5Row>,
    /// Pipelines of this width that fit the ECP5-85's multipliers, at most
    /// P (`None` when not one fits).
    pub ecp5_pipelines: Option<u32>,
    /// The post-route clock of the system of those pipelines
    /// (`tritri_system_w<W>_p<P>_d256`, `_shared` with the shared unit),
    /// where it was routed: pipelines that crowd the device route slower
    /// together than one alone (W = 16, P = 2).
    pub system_fmax_mhz: Option<f64>,
    /// The clock x those pipelines (one pair per clock each): the clock is
    /// [`WidthRow::clock_mhz`].
    pub pairs_per_second: Option<f64>,
    /// `pairs_per_second` over those pipelines' MULT18X18D blocks.
    pub pairs_per_second_per_multiplier: Option<f64>,
    /// On the Pareto front of throughput per multiplier against wrong verdicts.
    pub pareto: bool,
}

impl WidthRow {
    /// The post-route clock of this width's hardware: its system of
    /// `ecp5_pipelines` where that was routed, else its pipeline alone.
    pub fn clock_mhz(&self) -> Option<f64> {
        self.system_fmax_mhz
            .or(self.ecp5.as_ref().map(|r| r.fmax_mhz))
    }

    /// Wrong verdicts without certificates, as a fraction of the pairs.
    pub fn wrong_rate(&self) -> Option<f64> {
        self.error
            .as_ref()
            .map(|e| e.wrong as f64 / self.pairs.max(1) as f64)
    }

    /// Verdicts without a certificate, as a fraction of the pairs.
    pub fn uncertain_rate(&self) -> Option<f64> {
        self.error
            .as_ref()
            .and_then(|e| e.uncertain)
            .map(|u| u as f64 / self.pairs.max(1) as f64)
    }
}

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let (measurements, source) = match &args.measurements {
        None => (
            Measurements::committed(),
            "rtl-out/measurements.json (built in)".to_string(),
        ),
        Some(path) => match std::fs::read_to_string(path)
            .map_err(anyhow::Error::from)
            .and_then(|t| Measurements::parse(&t).map_err(anyhow::Error::msg))
        {
            Ok(m) => (m, path.display().to_string()),
            Err(e) => {
                eprintln!("error: --measurements {}: {e}", path.display());
                return Ok(ExitCode::from(2));
            }
        },
    };
    if args.files.is_empty() && args.scene.scene.is_none() {
        eprintln!("error: nothing to report on: give pair files (or @hard), --scene A B, or both");
        return Ok(ExitCode::from(2));
    }
    if args.out.exists() && !args.out.is_dir() {
        eprintln!(
            "error: --out {}: exists and is not a directory",
            args.out.display()
        );
        return Ok(ExitCode::from(2));
    }
    // Before the measurements, which take minutes.
    if let Err(e) = crate::output_file::check_directory(&args.out) {
        eprintln!("error: --out {}: {e:#}", args.out.display());
        return Ok(ExitCode::from(2));
    }
    let batches = match eval::load_batches(&args.files, "reported") {
        Ok(b) => b,
        Err(code) => return Ok(code),
    };
    let scene_objects = match &args.scene.scene {
        None => None,
        Some(_) => match args.scene.load(crate::sim::DEFAULT_SCENE) {
            Ok(objects) => Some(objects),
            Err(e) => {
                eprintln!("error: {e}");
                return Ok(ExitCode::from(2));
            }
        },
    };

    let mut widths = args.widths.clone();
    widths.sort_unstable();
    widths.dedup();
    let errors = if batches.is_empty() {
        None
    } else {
        Some(evaluate(
            &batches,
            &widths,
            Duration::from_millis(args.min_time_ms),
        )?)
    };
    let rows = width_rows(&widths, errors.as_ref(), &measurements, args.pipelines);
    let baselines = errors.as_ref().map_or(Vec::new(), |e| {
        e.total
            .rows
            .iter()
            .filter(|r| !r.arithmetic.starts_with("fixed"))
            .cloned()
            .collect()
    });
    let scene = match &scene_objects {
        Some((a, b)) => Some(scene::measure(
            a,
            b,
            &args.scene,
            &widths,
            args.pipelines,
            &rows,
        )?),
        None => None,
    };
    let report = Report {
        command: std::env::args().collect::<Vec<_>>().join(" "),
        pipelines: args.pipelines,
        measurements: source,
        measured: measurements.measured.clone(),
        errors,
        widths: rows,
        baselines,
        scene,
    };
    page::write_all(&args.out, &report)?;
    print_summary(&args.out, &report)?;

    let bugs: usize = report
        .widths
        .iter()
        .filter_map(|w| w.error.as_ref())
        .map(|e| e.grid_exact_disagreements.unwrap_or(0) + e.certified_wrong.unwrap_or(0))
        .sum();
    if bugs > 0 {
        eprintln!("error: {bugs} fixed-point verdicts disagree with the exact model on the grid, or certified verdicts with the exact answer: a bug");
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

/// `tritri eval` on the batches, every arithmetic.
fn evaluate(batches: &[Batch], widths: &[u32], min_time: Duration) -> anyhow::Result<Errors> {
    let arithmetics = Arithmetic::all(widths)?;
    let mut reports = Vec::new();
    for (i, batch) in batches.iter().enumerate() {
        eprintln!(
            "report: errors and speed on {} ({} pairs; {} of {})",
            batch.name,
            batch.pairs.len(),
            i + 1,
            batches.len()
        );
        reports.push(eval::evaluate(batch, &arithmetics, min_time)?);
    }
    let total = eval::total(&reports, &arithmetics);
    Ok(Errors {
        inputs: batches.iter().map(|b| b.name.clone()).collect(),
        batches: reports,
        total,
    })
}

/// Error, cost and speed per width, and the Pareto front.
fn width_rows(
    widths: &[u32],
    errors: Option<&Errors>,
    measurements: &Measurements,
    pipelines: u32,
) -> Vec<WidthRow> {
    let mut rows: Vec<WidthRow> = widths
        .iter()
        .map(|&width| {
            let routed = measurements.ecp5_pipeline(width);
            let rare_cases = routed.map_or(RareCasePath::Parallel, |(path, _)| path);
            let unit = pipeline_unit_name_for(width as usize, rare_cases);
            let ecp5 = routed.map(|(_, row)| row.clone());
            // A width whose pipeline does not fit the device has no throughput.
            let fitting = ecp5
                .as_ref()
                .map(|r| pipelines.min((ecp5_device().dsps / r.mult18x18d.max(1)) as u32))
                .filter(|&p| p >= 1);
            let system_fmax_mhz = fitting.and_then(|p| {
                let config = SystemConfig::new(width as usize, p as usize);
                measurements
                    .ecp5(&system_unit_name(config, PipelineKind::from(rare_cases)))
                    .map(|r| r.fmax_mhz)
            });
            let mut row = WidthRow {
                width,
                rare_cases,
                error: errors.and_then(|e| {
                    e.total
                        .rows
                        .iter()
                        .find(|r| r.arithmetic == format!("fixed{width}"))
                        .cloned()
                }),
                pairs: errors.map_or(0, |e| e.total.pairs),
                xilinx: measurements.xilinx(&unit).cloned(),
                ecp5,
                ecp5_pipelines: fitting,
                system_fmax_mhz,
                pairs_per_second: None,
                pairs_per_second_per_multiplier: None,
                pareto: false,
            };
            row.pairs_per_second = row
                .clock_mhz()
                .zip(fitting)
                .map(|(f, p)| f * 1e6 * p as f64);
            row.pairs_per_second_per_multiplier = row
                .ecp5
                .as_ref()
                .zip(row.pairs_per_second)
                .zip(fitting)
                .map(|((r, p), n)| p / (r.mult18x18d * n as u64).max(1) as f64);
            row
        })
        .collect();
    let points: Vec<(usize, f64, f64)> = rows
        .iter()
        .enumerate()
        .filter_map(|(i, r)| Some((i, r.wrong_rate()?, r.pairs_per_second_per_multiplier?)))
        .collect();
    for &(i, error, speed) in &points {
        let dominated = points
            .iter()
            .any(|&(j, e, s)| j != i && e <= error && s >= speed && (e < error || s > speed));
        rows[i].pareto = !dominated;
    }
    rows
}

fn print_summary(dir: &Path, report: &Report) -> std::io::Result<()> {
    outln!("report: {}", dir.join("report.html").display())?;
    if let Some(e) = &report.errors {
        outln!(
            "pairs: {} in {} batch(es) ({} intersect, exact)",
            e.total.pairs,
            e.batches.len(),
            e.total.exact_intersecting
        )?;
    }
    outln!(
        "  {:>3} {:>8} {:>7} {:>8} {:>9} {:>8} {:>6} {:>9} {:>12}",
        "W",
        "rare",
        "wrong",
        "uncert",
        "uncert %",
        "LUT",
        "DSP",
        "Fmax MHz",
        "pairs/s"
    )?;
    let dash = || "-".to_string();
    for w in &report.widths {
        outln!(
            "  {:>3} {:>8} {:>7} {:>8} {:>9} {:>8} {:>6} {:>9} {:>12}{}",
            w.width,
            w.rare_cases.name(),
            w.error.as_ref().map_or_else(dash, |e| e.wrong.to_string()),
            w.error
                .as_ref()
                .and_then(|e| e.uncertain)
                .map_or_else(dash, |u| u.to_string()),
            w.uncertain_rate()
                .map_or_else(dash, |r| format!("{:.3}", 100.0 * r)),
            w.xilinx.as_ref().map_or_else(dash, |x| x.lut.to_string()),
            w.xilinx
                .as_ref()
                .map_or_else(dash, |x| x.dsp48e1.to_string()),
            w.ecp5
                .as_ref()
                .map_or_else(dash, |r| format!("{:.1}", r.fmax_mhz)),
            w.pairs_per_second.map_or_else(dash, |p| format!("{p:.3e}")),
            if w.pareto { "  (Pareto)" } else { "" }
        )?;
    }
    if let Some(s) = &report.scene {
        outln!(
            "scene: {} x {}: software {:.3} ms",
            s.a,
            s.b,
            1e3 * s.software_seconds
        )?;
        for r in &s.rows {
            outln!(
                "  W = {:>2}: {} pairs tested, {} leaves, {} cycles{}, {:.3} ms at {:.1} MHz ({}), {} software; {} uncertain; {} missing / {} extra against exact f64",
                r.width,
                r.pairs_tested,
                r.leaves,
                r.whole_cycles,
                match r.rare_cases {
                    RareCasePath::Parallel => String::new(),
                    RareCasePath::Shared => format!(" ({} stalls at most, rare cases shared)", r.stall_cycles),
                },
                1e3 * r.whole_seconds,
                r.clock_mhz,
                r.clock.name(),
                r.speedup
                    .map_or_else(|| "no time, so no ratio to".to_string(), |x| format!("{x:.1} x")),
                r.uncertain,
                r.missing,
                r.extra
            )?;
        }
    }
    Ok(())
}
