//! Rung 4 of the verification ladder: the emitted Verilog of the pipeline,
//! run in Icarus and in Verilator with testbenches/tb_triangle_pipeline.sv,
//! gives `tritri_geom::fixed_point::intersects` for every pair (pair ids in
//! order, 0 mismatches) and takes exactly `N1 + N1 N2 + L` cycles.
//!
//! The pairs: random triangles quantized into one W-bit frame (general
//! position), small integer coordinates (coplanar, collinear, degenerate and
//! touching configurations are frequent) and coordinates at the ends of the
//! W-bit range (the widest intermediate values).
//!
//! The hard-case suite runs too, in all 72 orderings: the very vectors of
//! the rust-hdl test `rusthdl_pipeline::hard_case_suite_in_all_orderings_*`.
//!
//! Scale: `TRITRI_RTL_PAIRS` (default 100 000) pairs per Verilator run;
//! Icarus runs a tenth as many (it is ~100 times slower). A missing
//! simulator fails the test with the package to install.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;
use tritri_cosim::engine::{run_pipeline, Engine};
use tritri_cosim::pipeline_rtl::{
    pipeline_dut, pipeline_dut_for, pipeline_dut_with, run_schedule, run_schedule_on, run_stream,
    RtlDut, RtlRun,
};
use tritri_cosim::simulator::Simulator;
use tritri_cosim::stream::{group_schedule, shared_path_cost, StreamResult, TriangleStream};
use tritri_cosim::suites::{hard_case_count, hard_case_groups};
use tritri_geom::certificate::certified_intersects;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::hard_cases::{random_near_degenerate_pairs, random_pairs};
use tritri_geom::quantize::Frame;
use tritri_geom::scene::TaggedTriangle;
use tritri_rtl::emit::dsp_mapping::{MultiplierMapping, ECP5_MODEL_FILE};
use tritri_rtl::emit::memory_mapping::{map_delay_lines, DelayLineMapping};
use tritri_rtl::pipeline::RareCasePath;

fn env_usize(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn random_triangle(rng: &mut ChaCha8Rng, lo: i64, hi: i64) -> FixedTriangle {
    [0; 3].map(|_| [0; 3].map(|_| rng.gen_range(lo..=hi)))
}

/// `n1` bases against `n2` streamed triangles, drawn from three families.
fn mixed_stream(width: u32, n1: usize, n2: usize, seed: u64) -> TriangleStream {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // Random and near-degenerate f64 pairs, quantized into one frame.
    let pairs: Vec<_> = random_pairs(n1 + n2, seed)
        .into_iter()
        .chain(random_near_degenerate_pairs(n1 + n2, seed + 1))
        .collect();
    let all: Vec<_> = pairs.iter().flat_map(|p| [p.t1, p.t2]).collect();
    let frame = Frame::fit(all.iter(), width).unwrap();
    let quantized: Vec<FixedTriangle> = all.iter().map(|t| frame.quantize(t)).collect();
    let max = (1i64 << (width - 1)) - 1;
    let min = -(1i64 << (width - 1));
    let extremes = [min, max, 0, 1, -1, min + 1, max - 1, max / 2, min / 2];
    let pick = |k: usize, rng: &mut ChaCha8Rng| -> FixedTriangle {
        match k % 3 {
            0 => quantized[rng.gen_range(0..quantized.len())],
            1 => random_triangle(rng, -3, 3),
            _ => [0; 3].map(|_| [0; 3].map(|_| extremes[rng.gen_range(0..extremes.len())])),
        }
    };
    let bases = (0..n1)
        .map(|k| TaggedTriangle {
            id: 1000 + k as u32,
            triangle: pick(k, &mut rng),
        })
        .collect();
    // Stream ids near the top of the 32-bit range: the id path is checked too.
    let streamed = (0..n2)
        .map(|k| TaggedTriangle {
            id: u32::MAX - k as u32,
            triangle: pick(k, &mut rng),
        })
        .collect();
    TriangleStream { bases, streamed }
}

fn check(engine: &str, width: usize, stream: &TriangleStream, run: &RtlRun, latency: u64) {
    let expected = stream.expected(certified_intersects);
    let mismatches = run.result.mismatches(&expected);
    let hits = expected.iter().filter(|v| v.hit).count();
    let pairs = expected.len();
    eprintln!(
        "{engine} W={width}: {pairs} pairs ({hits} hits), {mismatches} mismatches, {} cycles (expected {}), \
         build {:.1} s, simulate {:.2} s = {:.0} pairs/s",
        run.result.cycles,
        stream.expected_cycles(latency),
        run.build_seconds,
        run.simulate_seconds,
        pairs as f64 / run.simulate_seconds
    );
    assert_eq!(
        run.result.verdicts.len(),
        pairs,
        "{engine}: one verdict per pair"
    );
    if let Some(k) = (0..pairs).find(|&k| run.result.verdicts[k] != expected[k]) {
        panic!(
            "{engine} W={width}: first mismatch at output {k}: {:?}, expected {:?}",
            run.result.verdicts[k], expected[k]
        );
    }
    assert_eq!(mismatches, 0);
    assert_eq!(
        run.result.cycles,
        stream.expected_cycles(latency),
        "{engine}: N1 + N1 N2 + L cycles"
    );
    // Every verdict leaves exactly L cycles after its triangle entered.
    let n2 = stream.streamed.len() as u64;
    for (k, t) in run.timed.iter().enumerate() {
        let k = k as u64;
        let entered = (k / n2) * (n2 + 1) + 1 + k % n2;
        assert_eq!(
            t.cycle,
            entered + latency,
            "{engine}: verdict {k} leaves L cycles after its input"
        );
    }
}

/// Icarus at W = 24 (the thesis's configuration) and W = 8.
#[test]
fn icarus_matches_fixed_point_model() {
    let total = env_usize("TRITRI_RTL_PAIRS", 100_000) / 10;
    for (width, seed) in [(24usize, 1u64), (8, 2)] {
        let dut = pipeline_dut(width).unwrap();
        let n1 = 10;
        let stream = mixed_stream(width as u32, n1, (total / n1).max(1), seed);
        let run = run_stream(Simulator::Icarus, &dut, &stream).unwrap_or_else(|e| panic!("{e:#}"));
        check("icarus", width, &stream, &run, dut.latency);
    }
}

/// Verilator at W = 24 and W = 8; a second run reuses the cached model.
#[test]
fn verilator_matches_fixed_point_model() {
    let total = env_usize("TRITRI_RTL_PAIRS", 100_000);
    for (width, seed) in [(24usize, 3u64), (8, 4)] {
        let dut = pipeline_dut(width).unwrap();
        let n1 = 20;
        let stream = mixed_stream(width as u32, n1, (total / n1).max(1), seed);
        let run =
            run_stream(Simulator::Verilator, &dut, &stream).unwrap_or_else(|e| panic!("{e:#}"));
        check("verilator", width, &stream, &run, dut.latency);
        let started = Instant::now();
        let small = mixed_stream(width as u32, 2, 50, seed + 10);
        let again = run_stream(Simulator::Verilator, &dut, &small).unwrap();
        assert_eq!(
            again.build_seconds, 0.0,
            "the second run uses the cached model"
        );
        check("verilator (cached)", width, &small, &again, dut.latency);
        eprintln!("cached run: {:.2} s", started.elapsed().as_secs_f64());
    }
}

/// The pipeline with its multipliers on ECP5 MULT18X18D blocks (`tritri gen
/// --dsp ecp5`), on the primitive's simulation model: Verilator at W = 16
/// (17 x 17 products on one block, 17 x 33 on two) and W = 8, Icarus at
/// W = 12, the same verdicts and cycles as the model.
#[test]
fn ecp5_dsp_mapping_matches_fixed_point_model() {
    let total = env_usize("TRITRI_RTL_PAIRS", 100_000);
    for (simulator, width, pairs, seed) in [
        (Simulator::Verilator, 16usize, total, 21u64),
        (Simulator::Verilator, 8, total / 4, 22),
        (Simulator::Icarus, 12, total / 20, 23),
    ] {
        let dut = pipeline_dut_with(width, MultiplierMapping::Ecp5).unwrap();
        assert!(
            dut.design.file(ECP5_MODEL_FILE).is_some(),
            "the primitive's model is emitted"
        );
        let instances = dut
            .design
            .verilog_files()
            .map(|f| f.contents.matches("MULT18X18D #(").count())
            .sum::<usize>();
        assert!(
            instances >= 1,
            "W={width}: the multipliers instantiate MULT18X18D"
        );
        let n1 = 20;
        let stream = mixed_stream(width as u32, n1, (pairs / n1).max(1), seed);
        let run = run_stream(simulator, &dut, &stream).unwrap_or_else(|e| panic!("{e:#}"));
        check(
            &format!("{simulator:?} (--dsp ecp5)"),
            width,
            &stream,
            &run,
            dut.latency,
        );
    }
}

/// `dut` with its delay lines in memories (`tritri gen --delay-lines
/// memory`).
fn with_delay_lines_in_memory(dut: &RtlDut) -> RtlDut {
    let mut dut = dut.clone();
    let mapped = map_delay_lines(&mut dut.design, DelayLineMapping::Memory);
    let memories = dut
        .design
        .verilog_files()
        .filter(|f| f.contents.contains("read_q <= words[read_at];"))
        .count();
    assert!(
        mapped >= 5 && memories == mapped,
        "W={}: {mapped} delay lines mapped, {memories} with a memory",
        dut.width
    );
    dut
}

/// The pipeline as `tritri gen --synth ecp5` emits it, its long delay
/// lines in memories (a power of two words, at least `N - 1`): W = 16 with
/// the rare cases shared and the multipliers on MULT18X18D in Verilator on
/// the hard cases (every verdict the model's, and the clocks held the
/// model's count), and W = 8's parallel pipeline in Icarus on a mixed
/// stream (verdicts and cycles).
#[test]
fn delay_lines_in_memory_match_the_model() {
    let width = 16;
    let dut = pipeline_dut_for(width, MultiplierMapping::Ecp5, RareCasePath::Shared)
        .unwrap_or_else(|e| panic!("{e:#}"));
    let dut = with_delay_lines_in_memory(&dut);
    let groups = hard_case_groups(width as u32, 1);
    let (schedule, expected) = group_schedule(&groups, certified_intersects);
    let result = run_schedule_on(Simulator::Verilator, &dut, &schedule, None)
        .map(|r| r.result)
        .unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(
        result.held,
        shared_path_cost(&groups).stall_cycles,
        "clocks held"
    );
    check_schedule(
        "Verilator, delay lines in memory",
        "W=16 hard cases x 72 orderings",
        &result,
        &expected,
        schedule.len() + result.held as usize,
    );

    let width = 8;
    let dut = with_delay_lines_in_memory(&pipeline_dut(width).unwrap());
    let stream = mixed_stream(width as u32, 20, 200, 31);
    let run = run_stream(Simulator::Icarus, &dut, &stream).unwrap_or_else(|e| panic!("{e:#}"));
    check(
        "Icarus (--delay-lines memory)",
        width,
        &stream,
        &run,
        dut.latency,
    );
}

/// The route's one entry point gives the same result on every engine (same
/// verdicts, same ids, same cycles), the model included.
#[test]
fn every_engine_of_the_route_gives_the_same_result() {
    let stream = mixed_stream(16, 3, 40, 5);
    let schedule: Vec<_> = stream.schedule().collect();
    let model = run_pipeline(Engine::Model, 16, &schedule, None)
        .unwrap()
        .result;
    assert_eq!(model.verdicts, stream.expected(certified_intersects));
    assert_eq!(
        model.cycles,
        stream.expected_cycles(tritri_rtl::pipeline::triangle_pipeline::latency() as u64)
    );
    for engine in [Engine::Rusthdl, Engine::Icarus, Engine::Verilator] {
        let run = run_pipeline(engine, 16, &schedule, None)
            .unwrap_or_else(|e| panic!("{}: {e:#}", engine.name()));
        assert_eq!(run.result, model, "{}", engine.name());
    }
}

/// Checks a run of a group schedule: every verdict (ids included) equals the
/// model's, and the run takes one cycle per input plus the latency.
fn check_schedule(
    engine: &str,
    what: &str,
    result: &StreamResult,
    expected: &[tritri_cosim::stream::PairVerdict],
    inputs: usize,
) {
    let latency = tritri_rtl::pipeline::triangle_pipeline::latency() as u64;
    let mismatches = result.mismatches(expected);
    let hits = expected.iter().filter(|v| v.hit).count();
    eprintln!(
        "{engine} {what}: {} pairs ({hits} hits), {mismatches} mismatches, {} cycles",
        expected.len(),
        result.cycles
    );
    if let Some(k) = (0..expected.len()).find(|&k| result.verdicts.get(k) != Some(&expected[k])) {
        panic!(
            "{engine} {what}: first mismatch at output {k}: {:?}, expected {:?}",
            result.verdicts.get(k),
            expected[k]
        );
    }
    assert_eq!(mismatches, 0, "{engine} {what}: extra verdicts");
    assert_eq!(
        result.cycles,
        inputs as u64 + latency,
        "{engine} {what}: one cycle per input plus the latency"
    );
}

/// The whole hard-case suite in all 72 orderings (340,128 pairs a width) in
/// Verilator at W = 16, 24 and 32.
#[test]
fn verilator_matches_fixed_point_model_on_the_hard_case_suite() {
    for width in [16, 24, 32] {
        let (schedule, expected) =
            group_schedule(&hard_case_groups(width, 1), certified_intersects);
        let result = run_schedule(Simulator::Verilator, width as usize, &schedule, None)
            .map(|r| r.result)
            .unwrap_or_else(|e| panic!("{e:#}"));
        let what = format!(
            "W={width} hard cases ({} x 72 orderings)",
            hard_case_count()
        );
        check_schedule("verilator", &what, &result, &expected, schedule.len());
    }
}

/// Every 16th hard case in all 72 orderings in Icarus at W = 24 (Icarus is
/// about a hundred times slower than Verilator).
#[test]
fn icarus_matches_fixed_point_model_on_the_hard_case_suite() {
    let width = 24;
    let (schedule, expected) = group_schedule(&hard_case_groups(width, 16), certified_intersects);
    let result = run_schedule(Simulator::Icarus, width as usize, &schedule, None)
        .map(|r| r.result)
        .unwrap_or_else(|e| panic!("{e:#}"));
    check_schedule(
        "icarus",
        "W=24 hard cases (every 16th x 72 orderings)",
        &result,
        &expected,
        schedule.len(),
    );
}

/// The pipeline with the rare cases on the shared unit (`tritri gen
/// --rare-cases shared`), emitted: the whole hard-case suite in all 72
/// orderings at W = 16 in Verilator, every 16th case in Icarus. Every
/// verdict is the model's, and the run holds exactly the clocks
/// `system::rare_case_model` counts, the count the rust-hdl test
/// `rusthdl_pipeline::shared_rare_case_path_gives_the_models_verdicts_and_holds`
/// asserts for rust-hdl.
#[test]
fn shared_rare_case_pipeline_matches_the_model_and_its_stall_count() {
    let width = 16;
    let dut = pipeline_dut_for(width, MultiplierMapping::Inferred, RareCasePath::Shared)
        .unwrap_or_else(|e| panic!("{e:#}"));
    for (simulator, every) in [(Simulator::Verilator, 1), (Simulator::Icarus, 16)] {
        let groups = hard_case_groups(width as u32, every);
        let (schedule, expected) = group_schedule(&groups, certified_intersects);
        let result = run_schedule_on(simulator, &dut, &schedule, None)
            .map(|r| r.result)
            .unwrap_or_else(|e| panic!("{e:#}"));
        let cost = shared_path_cost(&groups);
        let engine = format!("{simulator:?}, shared rare cases");
        let what = format!("W={width} hard cases (every {every}) x 72 orderings");
        eprintln!(
            "{engine} {what}: {} rare pairs ({} coplanar), {} clocks held",
            cost.coplanar + cost.segments,
            cost.coplanar,
            result.held
        );
        assert_eq!(result.held, cost.stall_cycles, "{engine}: clocks held");
        assert!(cost.stall_cycles > 1000, "{engine}: the unit is busy");
        check_schedule(
            &engine,
            &what,
            &result,
            &expected,
            schedule.len() + result.held as usize,
        );
    }
}
