//! `tritri bench [--width W]... [--pairs N] [--engines LIST]`
//!
//! Co-simulation throughput: the same stream of triangle pairs through the
//! fixed-point model (the baseline), the rust-hdl pipeline (direct-drive
//! harness) and the emitted Verilog in Verilator and Icarus. For each width
//! and engine it prints the pairs, the mismatches against the model, the
//! cycles measured against the thesis's N1 + N1·N2 + L, the simulation time
//! and pairs per second, and the speed as a ratio to the rust-hdl harness
//! measured in the same run (absolute times on a shared machine are noisy;
//! ratios much less so).
//!
//! The pairs: `N1` base triangles against `N2` streamed ones (`N1 = --bases`,
//! `N2 = ceil(N / N1)`), half of them uniform in the unit cube and half
//! near-degenerate (coarse-grid, shared vertices, coplanar: the coplanar and
//! degenerate paths of the pipeline run too), quantized into one W-bit frame.
//!
//! Verilator's time excludes its C++ build (printed separately, 0 when the
//! cached model is reused); Icarus's excludes its compile.
//!
//! Every verdict carries its certificate (`out_certain`), compared like the
//! verdict. A second table audits the certificates against the exact
//! verdicts on the original f64 coordinates: how many grid verdicts are
//! wrong, how many are uncertain, and how many are certain *and* wrong,
//! which must be none. An engine with no mismatch has the model's
//! certificates, so the audit holds for it too.
//!
//! Exit status: 0 no mismatch; 1 a mismatch, a cycle count off the formula,
//! a certain verdict that is wrong, or a tool failure; 2 bad usage (the
//! message names the value).

use crate::stdout::outln;
use anyhow::Context;
use std::process::ExitCode;
use std::time::Instant;
use tritri_cosim::engine::{run_pipeline, Engine};
use tritri_cosim::stream::{PairVerdict, TriangleStream};
use tritri_geom::certificate::certified_intersects;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::hard_cases::{random_near_degenerate_pairs, random_pairs};
use tritri_geom::quantize::Frame;
use tritri_geom::{exact_f64, Triangle};
use tritri_rtl::pipeline::pipeline_for_width::{check_width, PipelineInput};

#[derive(clap::Args)]
pub struct Args {
    /// Coordinate width in bits; repeat or separate with commas for several.
    #[arg(long, value_delimiter = ',', default_value = "24", value_parser = crate::input::whole::<usize>(tritri_geom::widths::MIN_WIDTH as usize..=tritri_geom::widths::MAX_WIDTH as usize))]
    width: Vec<usize>,
    /// Number of pairs per width (rounded up to a multiple of --bases).
    #[arg(long, default_value_t = 20_000, value_parser = crate::input::whole::<usize>(1..=100_000_000))]
    pairs: usize,
    /// Number of base triangles N1.
    #[arg(long, default_value_t = 50, value_parser = crate::input::whole::<usize>(1..=1_000_000))]
    bases: usize,
    /// Engines to run, the model always first as the baseline.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "rusthdl,verilator,icarus"
    )]
    engines: Vec<Engine>,
    /// Seed of the random triangles.
    #[arg(long, default_value_t = 2005, value_parser = crate::input::whole::<u64>(0..=u64::MAX))]
    seed: u64,
}

/// One engine's run on one width.
struct Measurement {
    engine: &'static str,
    pairs: usize,
    mismatches: usize,
    cycles: Option<u64>,
    seconds: f64,
    /// Build or compile time, not included in `seconds`.
    build_seconds: Option<f64>,
}

impl Measurement {
    fn pairs_per_second(&self) -> f64 {
        self.pairs as f64 / self.seconds.max(1e-9)
    }
}

/// The stream of the benchmark at `width` (see the module docs), and the
/// f64 triangles its bases and streamed triangles were quantized from.
struct BenchStream {
    stream: TriangleStream,
    bases: Vec<Triangle>,
    streamed: Vec<Triangle>,
}

fn stream_for(width: usize, pairs: usize, bases: usize, seed: u64) -> anyhow::Result<BenchStream> {
    let n1 = bases.min(pairs);
    let n2 = pairs.div_ceil(n1);
    let count = n1.max(n2);
    let mut raw = random_pairs(count.div_ceil(2), seed);
    raw.extend(random_near_degenerate_pairs(count / 2, seed + 1));
    // Interleave uniform and near-degenerate triangles so both kinds are bases.
    let half = count.div_ceil(2);
    let order: Vec<usize> = (0..count)
        .map(|i| if i % 2 == 0 { i / 2 } else { half + i / 2 })
        .collect();
    let frame = Frame::fit(raw.iter().flat_map(|p| [&p.t1, &p.t2]), width as u32)
        .context("fitting the frame")?;
    let originals = |n: usize, second: bool| -> Vec<Triangle> {
        order
            .iter()
            .take(n)
            .map(|&i| if second { raw[i].t2 } else { raw[i].t1 })
            .collect()
    };
    let (bases, streamed) = (originals(n1, false), originals(n2, true));
    let quantize =
        |ts: &[Triangle]| -> Vec<FixedTriangle> { ts.iter().map(|t| frame.quantize(t)).collect() };
    let stream = TriangleStream::from_triangles(&quantize(&bases), &quantize(&streamed));
    Ok(BenchStream {
        stream,
        bases,
        streamed,
    })
}

/// What the certificates say against the exact verdicts on the originals.
struct Audit {
    pairs: usize,
    wrong: usize,
    uncertain: usize,
    certain_and_wrong: usize,
}

fn audit(bench: &BenchStream, expected: &[PairVerdict]) -> Audit {
    let mut a = Audit {
        pairs: expected.len(),
        wrong: 0,
        uncertain: 0,
        certain_and_wrong: 0,
    };
    for v in expected {
        let exact = exact_f64::intersects(
            &bench.bases[v.base_id as usize],
            &bench.streamed[v.stream_id as usize],
        );
        a.wrong += (v.hit != exact) as usize;
        a.uncertain += !v.certain as usize;
        a.certain_and_wrong += (v.certain && v.hit != exact) as usize;
    }
    a
}

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    for &w in &args.width {
        if let Err(e) = check_width(w) {
            eprintln!("error: --width {w}: {e}");
            return Ok(ExitCode::from(2));
        }
    }
    let mut failed = false;
    outln!("| W | engine | pairs | mismatches | cycles (N1+N1*N2+L) | build s | run s | pairs/s | speed / rusthdl |")?;
    outln!("|---:|---|---:|---:|---|---:|---:|---:|---:|")?;
    let mut audits = Vec::new();
    for &width in &args.width {
        let bench = stream_for(width, args.pairs, args.bases, args.seed)?;
        let stream = &bench.stream;
        let latency = tritri_rtl::pipeline::triangle_pipeline::latency() as u64;
        let formula = stream.expected_cycles(latency);

        // Baseline: the fixed-point model, timed on its own.
        let started = Instant::now();
        let expected = stream.expected(certified_intersects);
        let model = Measurement {
            engine: "model",
            pairs: expected.len(),
            mismatches: 0,
            cycles: None,
            seconds: started.elapsed().as_secs_f64(),
            build_seconds: None,
        };
        let audited = audit(&bench, &expected);
        failed |= audited.certain_and_wrong != 0;
        audits.push((width, audited));
        let mut rows = vec![model];
        let schedule: Vec<PipelineInput> = stream.schedule().collect();
        for &engine in args.engines.iter().filter(|&&e| e != Engine::Model) {
            eprintln!(
                "W = {width}: {} pairs through {} ...",
                expected.len(),
                engine.name()
            );
            let run = run_pipeline(engine, width, &schedule, None)
                .with_context(|| format!("running {}", engine.name()))?;
            rows.push(Measurement {
                engine: engine.name(),
                pairs: run.result.verdicts.len(),
                mismatches: run.result.mismatches(&expected),
                cycles: Some(run.result.cycles),
                seconds: run.simulate_seconds,
                build_seconds: engine.simulator().map(|_| run.build_seconds),
            });
        }
        let reference = rows
            .iter()
            .find(|m| m.engine == Engine::Rusthdl.name())
            .map(Measurement::pairs_per_second);
        for m in &rows {
            let cycles = match m.cycles {
                Some(c) if c == formula => format!("{c} (= formula)"),
                Some(c) => {
                    failed = true;
                    format!("{c} (formula {formula})")
                }
                None => "-".into(),
            };
            failed |= m.mismatches != 0 || m.pairs != expected.len();
            outln!(
                "| {width} | {} | {} | {} | {cycles} | {} | {:.2} | {:.0} | {} |",
                m.engine,
                m.pairs,
                m.mismatches,
                m.build_seconds.map_or("-".into(), |s| format!("{s:.1}")),
                m.seconds,
                m.pairs_per_second(),
                reference.map_or("-".into(), |r| format!("{:.2}", m.pairs_per_second() / r)),
            )?;
        }
    }
    outln!()?;
    outln!("| W | pairs | grid verdicts wrong on the originals | uncertain (out_certain = 0) | certain and wrong |")?;
    outln!("|---:|---:|---:|---:|---:|")?;
    for (width, a) in &audits {
        let percent = |n: usize| 100.0 * n as f64 / a.pairs.max(1) as f64;
        outln!(
            "| {width} | {} | {} ({:.3} %) | {} ({:.3} %) | {} |",
            a.pairs,
            a.wrong,
            percent(a.wrong),
            a.uncertain,
            percent(a.uncertain),
            a.certain_and_wrong
        )?;
    }
    if failed {
        eprintln!("error: an engine disagreed with the model or with the cycle formula, or a certain verdict is wrong (see the tables)");
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}
