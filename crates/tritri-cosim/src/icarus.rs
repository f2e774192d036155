//! Runs emitted Verilog in Icarus Verilog (`iverilog -g2012`, `vvp`) on the
//! vectors of a stream, with `testbenches/tb_triangle_pipeline.sv`.
//!
//! Each run compiles into a fresh temporary directory: Icarus compiles in
//! well under a second, so there is nothing worth caching. A run can dump a
//! VCD waveform of the emitted Verilog (testbench macro `TRITRI_VCD`).

use crate::rtl_sim::{write_sources, RtlDut, RtlRun, WorkDir, TESTBENCH_TOP};
use crate::stream::TriangleStream;
use crate::vectors::{parse_outputs, vectors};
use anyhow::Context as _;
use std::path::Path;
use std::time::Instant;
use tritri_rtl::tools::{run, IVERILOG, VVP};

/// Simulates `dut` on `stream` in Icarus.
pub fn run_icarus_dut(dut: &RtlDut, stream: &TriangleStream) -> anyhow::Result<RtlRun> {
    run_icarus_on_vectors(dut, &vectors(stream, dut.width, dut.id_bits), None)
}

/// Runs an arbitrary schedule of input cycles on the emitted `width`-bit
/// pipeline in Icarus (see `rusthdl_harness::run_schedule_on`); with `vcd`,
/// writes the waveform of every signal there.
pub fn run_icarus_schedule(
    width: usize,
    schedule: &[crate::stream::InputCycle],
    vcd: Option<&Path>,
) -> anyhow::Result<crate::stream::StreamResult> {
    let dut = crate::rtl_sim::pipeline_dut(width)?;
    let text = crate::vectors::vectors_for_schedule(schedule, dut.width, dut.id_bits);
    Ok(run_icarus_on_vectors(&dut, &text, vcd)?.result)
}

fn run_icarus_on_vectors(dut: &RtlDut, vector_text: &str, vcd: Option<&Path>) -> anyhow::Result<RtlRun> {
    let iverilog = IVERILOG.locate()?;
    let vvp = VVP.locate()?;
    let work = WorkDir::new("icarus").context("creating the Icarus work directory")?;
    let sources = write_sources(dut, &work.path).context("writing the Verilog sources")?;
    let build = Instant::now();
    let image = work.join("tb.vvp");
    let mut compile = std::process::Command::new(iverilog);
    compile
        .arg("-g2012")
        .arg("-o")
        .arg(&image)
        .arg("-s")
        .arg(TESTBENCH_TOP)
        .arg(format!("-DTRITRI_DUT={}", dut.design.top))
        .arg(format!("-P{TESTBENCH_TOP}.W={}", dut.width))
        .arg(format!("-P{TESTBENCH_TOP}.ID_WIDTH={}", dut.id_bits))
        .args(vcd.map(|_| "-DTRITRI_VCD"))
        .args(&sources);
    run(&mut compile)?;
    let build_seconds = build.elapsed().as_secs_f64();

    let vectors_path = work.join("vectors.txt");
    let outputs_path = work.join("outputs.txt");
    std::fs::write(&vectors_path, vector_text)?;
    let simulate = Instant::now();
    let mut sim = std::process::Command::new(vvp);
    sim.arg("-n")
        .arg(&image)
        .arg(format!("+vectors={}", vectors_path.display()))
        .arg(format!("+outputs={}", outputs_path.display()))
        .args(vcd.map(|path| format!("+vcd={}", path.display())));
    let output = run(&mut sim)?;
    let simulate_seconds = simulate.elapsed().as_secs_f64();
    let text = std::fs::read_to_string(&outputs_path).with_context(|| {
        format!("the testbench wrote no outputs; vvp said:\n{}", String::from_utf8_lossy(&output.stdout))
    })?;
    let (result, timed) = parse_outputs(&text)?;
    Ok(RtlRun { result, timed, build_seconds, simulate_seconds })
}

/// Runs `stream` on the emitted `width`-bit pipeline in Icarus.
pub fn run_icarus_stream(width: usize, stream: &TriangleStream) -> anyhow::Result<crate::stream::StreamResult> {
    let dut = crate::rtl_sim::pipeline_dut(width)?;
    Ok(run_icarus_dut(&dut, stream)?.result)
}

/// Runs `bases` (each loaded once with `bset`) against `streamed` on the
/// emitted `width`-bit pipeline in Icarus; the same result as
/// [`crate::rusthdl_harness::run_pairs`].
pub fn run_icarus(
    width: usize,
    bases: &[(u32, tritri_geom::fixed_point::FixedTriangle)],
    streamed: &[(u32, tritri_geom::fixed_point::FixedTriangle)],
) -> anyhow::Result<crate::rusthdl_harness::RunResult> {
    Ok(run_icarus_stream(width, &crate::rtl_sim::stream_of(bases, streamed))?.into())
}
