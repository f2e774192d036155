//! Large co-simulation run of the rust-hdl pipeline against the fixed-point
//! model, with the harness's throughput:
//! `TRITRI_PAIRS=100000 TRITRI_WIDTH=24 cargo run --release -p tritri-cosim --example rusthdl_throughput`
//!
//! The pairs: random triangles in the unit cube quantized into one W-bit
//! frame, `N1` bases against `N2` streamed triangles (`N1 N2 >= pairs`).

use std::time::Instant;
use tritri_cosim::rusthdl_harness::{run_stream_on, HarnessOptions};
use tritri_cosim::stream::TriangleStream;
use tritri_geom::fixed_point::{intersects, FixedTriangle};
use tritri_geom::hard_cases::random_pairs;
use tritri_geom::quantize::Frame;
use tritri_rtl::configurations::pipeline_for_width;

fn env(name: &str, default: usize) -> usize {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn main() -> anyhow::Result<()> {
    let pairs = env("TRITRI_PAIRS", 100_000);
    let width = env("TRITRI_WIDTH", 24);
    let n1 = env("TRITRI_BASES", 50).min(pairs).max(1);
    let n2 = pairs.div_ceil(n1);
    let raw = random_pairs(n1.max(n2), 2005);
    let frame = Frame::fit(raw.iter().flat_map(|p| [&p.t1, &p.t2]), width as u32)?;
    let bases: Vec<FixedTriangle> = raw.iter().take(n1).map(|p| frame.quantize(&p.t1)).collect();
    let streamed: Vec<FixedTriangle> = raw.iter().take(n2).map(|p| frame.quantize(&p.t2)).collect();
    let stream = TriangleStream::from_triangles(&bases, &streamed);
    let mut pipeline = pipeline_for_width(width)?;
    let start = Instant::now();
    let result = run_stream_on(pipeline.as_mut(), &stream, &HarnessOptions::default())?;
    let elapsed = start.elapsed().as_secs_f64();
    let expected = stream.expected(intersects);
    let mismatches = result.mismatches(&expected);
    let hits = expected.iter().filter(|v| v.hit).count();
    println!(
        "W = {width}: {} pairs ({n1} x {n2}), {hits} hits, {mismatches} mismatches; {} cycles (expected {}); \
         {elapsed:.1} s, {:.0} pairs/s",
        expected.len(),
        result.cycles,
        stream.expected_cycles(pipeline.latency() as u64),
        expected.len() as f64 / elapsed
    );
    println!(
        "delta cycles per clock: {:.1}",
        tritri_rtl::sim_drive::DELTA_CYCLES.load(std::sync::atomic::Ordering::Relaxed) as f64 / result.cycles as f64
    );
    anyhow::ensure!(mismatches == 0, "{mismatches} mismatches");
    Ok(())
}
