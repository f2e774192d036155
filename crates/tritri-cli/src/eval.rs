//! `tritri eval [--json] [--widths 8,12,16,20,24,32] FILE...`
//!
//! For each file (one batch: fixed-point quantizes all of it into one frame)
//! and in total, for every arithmetic (exact, f64, f32, moller, fixed at
//! each width): how many verdicts differ from the exact one (false
//! positives: reported intersecting but not; false negatives: the reverse)
//! and the time per pair.
//!
//! Timing: each arithmetic runs over the whole batch repeatedly for at least
//! `--min-time-ms` (default 50 ms), in samples of about 1 ms; the reported
//! ns/pair is the fastest sample, which stays stable when other work shares
//! the machine. `ns/pair`
//! is the whole `classify` call (for fixed: fitting the frame, quantizing,
//! deciding); `kernel` is fixed point's integer test alone on the already
//! quantized pairs, the part the hardware replaces. `÷f64` divides by the
//! f64 row's ns/pair.
//!
//! For fixed point, `uncert` counts the verdicts without a certificate
//! (`docs/certificates.md`: a sign on the decision path could change when
//! the coordinates move by half a grid step), which the host decides again
//! on the original coordinates; `recheck` is that host work, the exact
//! predicates on the uncertain pairs alone, in ns per pair of the batch.
//! With it the answer is exact: a certified answer that differs from the
//! exact one is a bug (exit status 1), like a `grid` disagreement.
//!
//! For fixed point, `grid` counts the pairs where it disagrees with the
//! exact model run on the same quantized coordinates; anything but 0 is a
//! bug (exit status 1). Its `wrong` columns are therefore quantization
//! error alone.
//!
//! A file with a record that cannot be read stops everything (exit status
//! 2, each bad record named): a total over part of the input would read as
//! the whole.
//!
//! `@hard` stands for the hard-case suite of `tritri_geom::hard_cases`, one
//! batch per category; `@hard/<category>` for one category.

use crate::input;
use crate::stdout::outln;
use anyhow::bail;
use serde::Serialize;
use std::collections::BTreeMap;
use std::hint::black_box;
use std::path::Path;
use std::process::ExitCode;
use std::time::{Duration, Instant};
use tritri_geom::arithmetic::{classify, quantize_pairs, Arithmetic};
use tritri_geom::certificate::{certified_intersects, recheck, CertifiedVerdict};
use tritri_geom::{exact_f64, fixed_point, hard_cases, TrianglePair};

#[derive(clap::Args)]
pub struct Args {
    /// Print one JSON document instead of tables.
    #[arg(long)]
    json: bool,
    /// Coordinate widths of the fixed-point rows (8 to 32 bits each).
    #[arg(long, value_delimiter = ',', value_parser = input::parse_width, default_values_t = [8, 12, 16, 20, 24, 32])]
    widths: Vec<u32>,
    /// Minimum time spent timing each arithmetic on each file, in ms.
    #[arg(long, default_value_t = 50, allow_hyphen_values = true, value_parser = input::parse_min_time_ms)]
    min_time_ms: u64,
    /// Pair files (18 numbers per line, or a JSON array of {t1, t2}); `-` for standard input, `@hard` for the hard-case suite.
    #[arg(required = true)]
    files: Vec<String>,
}

/// A named set of pairs evaluated together (one fixed-point frame).
pub struct Batch {
    pub name: String,
    pub pairs: Vec<TrianglePair>,
}

#[derive(Serialize, Clone)]
pub struct Row {
    pub arithmetic: String,
    pub wrong: usize,
    pub false_positives: usize,
    pub false_negatives: usize,
    pub ns_per_pair: f64,
    /// Fixed point only: the integer test on pre-quantized pairs.
    pub kernel_ns_per_pair: Option<f64>,
    /// Fixed point only: disagreements with exact on the quantized pairs (must be 0).
    pub grid_exact_disagreements: Option<usize>,
    /// Fixed point only: verdicts without a certificate (`out_certain = 0`).
    pub uncertain: Option<usize>,
    /// Fixed point only: the host's exact re-check of the uncertain pairs,
    /// in ns per pair of the batch.
    pub recheck_ns_per_pair: Option<f64>,
    /// Fixed point only: certified answers (certain grid verdicts, the rest
    /// re-checked) that differ from the exact one (must be 0).
    pub certified_wrong: Option<usize>,
    /// Fixed point only: the grid step h of the batch's frame.
    pub step: Option<f64>,
}

#[derive(Serialize)]
pub struct BatchReport {
    pub name: String,
    pub pairs: usize,
    pub exact_intersecting: usize,
    pub rows: Vec<Row>,
}

#[derive(Serialize)]
struct Report {
    batches: Vec<BatchReport>,
    total: BatchReport,
}

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let arithmetics = Arithmetic::all(&args.widths)?;
    let min_time = Duration::from_millis(args.min_time_ms);
    let batches = match load_batches(&args.files, "evaluated") {
        Ok(b) => b,
        Err(code) => return Ok(code),
    };

    let mut reports = Vec::new();
    for batch in &batches {
        reports.push(evaluate(batch, &arithmetics, min_time)?);
        if !args.json {
            print_table(reports.last().unwrap())?;
        }
    }
    let total = total(&reports, &arithmetics);
    let grid_bugs: usize = total
        .rows
        .iter()
        .filter_map(|r| r.grid_exact_disagreements)
        .sum();
    let certificate_bugs: usize = total.rows.iter().filter_map(|r| r.certified_wrong).sum();
    if args.json {
        let report = Report {
            batches: reports,
            total,
        };
        outln!("{}", serde_json::to_string_pretty(&report)?)?;
    } else if reports.len() > 1 {
        print_table(&total)?;
    }

    if grid_bugs > 0 {
        eprintln!("error: fixed point disagrees with the exact model on the quantized coordinates for {grid_bugs} pairs: a bug");
        return Ok(ExitCode::from(1));
    }
    if certificate_bugs > 0 {
        eprintln!("error: {certificate_bugs} certified verdicts differ from the exact ones: a certificate was given where a sign could change (a bug)");
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

/// The pair files and `@hard` suites named, one batch each. A record or
/// file that cannot be read stops everything (status 2, each one named,
/// then "nothing {done}"): a figure over part of the input would read as
/// the whole.
pub fn load_batches(files: &[String], done: &str) -> Result<Vec<Batch>, ExitCode> {
    let mut errors = 0;
    let mut batches = Vec::new();
    for name in files {
        if let Some(selector) = name.strip_prefix('@') {
            match suite_batches(selector) {
                Ok(b) => batches.extend(b),
                Err(e) => {
                    eprintln!("error: {e}");
                    return Err(ExitCode::from(2));
                }
            }
            continue;
        }
        let loaded = input::load(Path::new(name));
        errors += loaded.errors;
        if loaded.file.is_some() {
            batches.push(Batch {
                name: name.clone(),
                pairs: loaded.good_pairs(),
            });
        }
    }
    if errors > 0 {
        eprintln!("error: nothing {done}: {errors} record(s) or file(s) could not be read");
        return Err(ExitCode::from(2));
    }
    Ok(batches)
}

/// `hard` (every category, one batch each) or `hard/<category>`.
fn suite_batches(selector: &str) -> anyhow::Result<Vec<Batch>> {
    let (suite, only) = match selector.split_once('/') {
        Some((s, c)) => (s, Some(c)),
        None => (selector, None),
    };
    if suite != "hard" {
        bail!("unknown suite `@{selector}`: the only suite is @hard (or @hard/<category>)");
    }
    let mut by_category: BTreeMap<String, Vec<TrianglePair>> = BTreeMap::new();
    for case in hard_cases::hard_case_suite() {
        let category = case.name.split(['/', '#']).next().unwrap_or("").to_string();
        by_category.entry(category).or_default().push(case.pair);
    }
    if let Some(c) = only {
        if !by_category.contains_key(c) {
            let known: Vec<_> = by_category.keys().cloned().collect();
            bail!(
                "unknown hard-case category `{c}`: known are {}",
                known.join(", ")
            );
        }
        by_category.retain(|k, _| k == c);
    }
    Ok(by_category
        .into_iter()
        .map(|(c, pairs)| Batch {
            name: format!("@hard/{c}"),
            pairs,
        })
        .collect())
}

/// Every arithmetic's errors and speed on one batch.
pub fn evaluate(
    batch: &Batch,
    arithmetics: &[Arithmetic],
    min_time: Duration,
) -> anyhow::Result<BatchReport> {
    let pairs = &batch.pairs;
    let exact = classify(Arithmetic::Exact, pairs)?.verdicts;
    let mut rows = Vec::new();
    for &arith in arithmetics {
        let c = classify(arith, pairs)?;
        let (false_positives, false_negatives) = compare(&c.verdicts, &exact);
        let ns_per_pair = time_per_pair(pairs.len(), min_time, || {
            let _ = black_box(classify(arith, black_box(pairs)).map(|c| c.verdicts));
        });
        let (mut kernel_ns_per_pair, mut grid_exact_disagreements) = (None, None);
        let (mut uncertain, mut recheck_ns_per_pair, mut certified_wrong) = (None, None, None);
        if let Arithmetic::Fixed(width) = arith {
            let (_, quantized) = quantize_pairs(pairs, width)?;
            kernel_ns_per_pair = Some(time_per_pair(pairs.len(), min_time, || {
                black_box(
                    black_box(&quantized)
                        .iter()
                        .map(|q| fixed_point::intersects(&q[0], &q[1]))
                        .collect::<Vec<_>>(),
                );
            }));
            let as_f64 = |t: &fixed_point::FixedTriangle| t.map(|p| p.map(|c| c as f64));
            let on_grid = quantized
                .iter()
                .map(|q| exact_f64::intersects(&as_f64(&q[0]), &as_f64(&q[1])));
            grid_exact_disagreements =
                Some(on_grid.zip(&c.verdicts).filter(|(a, b)| a != *b).count());
            let grid: Vec<CertifiedVerdict> = quantized
                .iter()
                .map(|q| certified_intersects(&q[0], &q[1]))
                .collect();
            let run = recheck(pairs, &grid);
            let doubtful: Vec<&TrianglePair> = pairs
                .iter()
                .zip(&grid)
                .filter(|(_, v)| !v.certain)
                .map(|(p, _)| p)
                .collect();
            uncertain = Some(run.uncertain);
            let (extra, missing) = compare(&run.verdicts, &exact);
            certified_wrong = Some(extra + missing);
            recheck_ns_per_pair = Some(time_per_pair(pairs.len(), min_time, || {
                black_box(
                    doubtful
                        .iter()
                        .map(|p| exact_f64::intersects(&p.t1, &p.t2))
                        .collect::<Vec<_>>(),
                );
            }));
        }
        rows.push(Row {
            arithmetic: arith.to_string(),
            wrong: false_positives + false_negatives,
            false_positives,
            false_negatives,
            ns_per_pair,
            kernel_ns_per_pair,
            grid_exact_disagreements,
            uncertain,
            recheck_ns_per_pair,
            certified_wrong,
            step: c.frame.map(|f| f.step),
        });
    }
    Ok(BatchReport {
        name: batch.name.clone(),
        pairs: pairs.len(),
        exact_intersecting: exact.iter().filter(|&&v| v).count(),
        rows,
    })
}

/// (false positives, false negatives) of `verdicts` against `exact`.
fn compare(verdicts: &[bool], exact: &[bool]) -> (usize, usize) {
    let fp = verdicts
        .iter()
        .zip(exact)
        .filter(|&(&v, &e)| v && !e)
        .count();
    let fn_ = verdicts
        .iter()
        .zip(exact)
        .filter(|&(&v, &e)| !v && e)
        .count();
    (fp, fn_)
}

/// Fastest sample of `run` (one pass over `n` pairs), in ns per pair. Each
/// sample repeats `run` for about 1 ms (shorter than a scheduler time slice,
/// so that some samples run undisturbed on a busy machine); samples
/// continue until `min_time` has passed and at least three exist.
fn time_per_pair(n: usize, min_time: Duration, mut run: impl FnMut()) -> f64 {
    if n == 0 {
        return 0.0;
    }
    let t = Instant::now();
    run();
    let once = t.elapsed().as_secs_f64().max(1e-9);
    let sample = 1e-3;
    let repeats = (sample / once).ceil().max(1.0) as u32;
    let start = Instant::now();
    let (mut best, mut samples) = (f64::INFINITY, 0);
    while samples < 3 || start.elapsed() < min_time {
        let t = Instant::now();
        for _ in 0..repeats {
            run();
        }
        best = best.min(t.elapsed().as_secs_f64() / f64::from(repeats));
        samples += 1;
    }
    best * 1e9 / n as f64
}

/// Sums over batches; times are weighted by the batches' pair counts.
pub fn total(reports: &[BatchReport], arithmetics: &[Arithmetic]) -> BatchReport {
    let pairs: usize = reports.iter().map(|r| r.pairs).sum();
    let weighted = |f: &dyn Fn(&BatchReport) -> Option<f64>| -> Option<f64> {
        if pairs == 0 {
            return None;
        }
        let mut sum = 0.0;
        for r in reports {
            sum += f(r)? * r.pairs as f64;
        }
        Some(sum / pairs as f64)
    };
    let rows = arithmetics
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let fixed = matches!(a, Arithmetic::Fixed(_));
            let sum =
                |f: &dyn Fn(&Row) -> usize| reports.iter().map(|r| f(&r.rows[i])).sum::<usize>();
            Row {
                arithmetic: a.to_string(),
                wrong: sum(&|r| r.wrong),
                false_positives: sum(&|r| r.false_positives),
                false_negatives: sum(&|r| r.false_negatives),
                ns_per_pair: weighted(&|r| Some(r.rows[i].ns_per_pair)).unwrap_or(0.0),
                kernel_ns_per_pair: weighted(&|r| r.rows[i].kernel_ns_per_pair),
                grid_exact_disagreements: fixed
                    .then(|| sum(&|r| r.grid_exact_disagreements.unwrap_or(0))),
                uncertain: fixed.then(|| sum(&|r| r.uncertain.unwrap_or(0))),
                recheck_ns_per_pair: weighted(&|r| r.rows[i].recheck_ns_per_pair),
                certified_wrong: fixed.then(|| sum(&|r| r.certified_wrong.unwrap_or(0))),
                step: None,
            }
        })
        .collect();
    BatchReport {
        name: "total".into(),
        pairs,
        exact_intersecting: reports.iter().map(|r| r.exact_intersecting).sum(),
        rows,
    }
}

fn print_table(r: &BatchReport) -> std::io::Result<()> {
    outln!(
        "{}: {} pairs, {} intersect (exact)",
        r.name,
        r.pairs,
        r.exact_intersecting
    )?;
    outln!(
        "  {:<10} {:>6} {:>7} {:>7} {:>9} {:>6} {:>9} {:>5} {:>7} {:>8} {:>10}",
        "arithmetic",
        "wrong",
        "false+",
        "false-",
        "ns/pair",
        "÷f64",
        "kernel",
        "grid",
        "uncert",
        "recheck",
        "step h"
    )?;
    let f64_ns = r
        .rows
        .iter()
        .find(|row| row.arithmetic == "f64")
        .map(|row| row.ns_per_pair);
    let dash = || "-".to_string();
    for row in &r.rows {
        let ratio = f64_ns
            .filter(|&f| f > 0.0)
            .map(|f| format!("{:.2}", row.ns_per_pair / f))
            .unwrap_or_else(dash);
        outln!(
            "  {:<10} {:>6} {:>7} {:>7} {:>9.1} {:>6} {:>9} {:>5} {:>7} {:>8} {:>10}",
            row.arithmetic,
            row.wrong,
            row.false_positives,
            row.false_negatives,
            row.ns_per_pair,
            ratio,
            row.kernel_ns_per_pair
                .map(|k| format!("{k:.1}"))
                .unwrap_or_else(dash),
            row.grid_exact_disagreements
                .map(|g| g.to_string())
                .unwrap_or_else(dash),
            row.uncertain.map(|u| u.to_string()).unwrap_or_else(dash),
            row.recheck_ns_per_pair
                .map(|k| format!("{k:.1}"))
                .unwrap_or_else(dash),
            row.step.map(|s| format!("{s:.2e}")).unwrap_or_else(dash),
        )?;
    }
    outln!()
}
