//! Runs emitted Verilog in Verilator 5 (`verilator --binary`, timing on) on
//! the vectors of a stream, with `testbenches/tb_triangle_pipeline.sv`.
//!
//! The C++ build takes tens of seconds, so the executable is cached: under
//! `$TRITRI_CACHE_DIR/verilator/<key>` (default: `$XDG_CACHE_HOME/tritri`,
//! else `~/.cache/tritri`), the key a hash of the emitted Verilog, the
//! testbench, W, the id width and the Verilator version. A run with the same
//! design reuses the executable. Builds go to a private directory first and
//! are renamed into place, so parallel runs never see half a build.
//!
//! A run that asks for a VCD waveform uses a second build of the same
//! design with `--trace` (and the testbench macro `TRITRI_VCD`), cached
//! under its own key: tracing slows every cycle, so the plain build stays
//! the fast one.

use crate::rtl_sim::{write_sources, RtlDut, RtlRun, WorkDir, TESTBENCH_TOP};
use crate::stream::TriangleStream;
use crate::vectors::{parse_outputs, vectors};
use anyhow::Context as _;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tritri_rtl::tools::{run, VERILATOR};

/// Name of the executable `--binary` builds.
fn executable_name() -> String {
    format!("V{TESTBENCH_TOP}")
}

/// The cache root (see the module docs).
pub fn cache_root() -> PathBuf {
    if let Some(dir) = std::env::var_os("TRITRI_CACHE_DIR") {
        return PathBuf::from(dir);
    }
    if let Some(dir) = std::env::var_os("XDG_CACHE_HOME") {
        return PathBuf::from(dir).join("tritri");
    }
    if let Some(home) = std::env::var_os("HOME") {
        return PathBuf::from(home).join(".cache").join("tritri");
    }
    std::env::temp_dir().join("tritri-cache")
}

fn verilator_version() -> anyhow::Result<String> {
    let out = run(VERILATOR.command()?.arg("--version"))?;
    Ok(String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// Whether a build can write a VCD waveform.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tracing {
    Off,
    Vcd,
}

/// The executable for `dut`, built unless cached; returns it and the build time.
pub fn build(dut: &RtlDut, tracing: Tracing) -> anyhow::Result<(PathBuf, f64)> {
    VERILATOR.locate()?;
    let version = verilator_version()?;
    let suffix = match tracing {
        Tracing::Off => "",
        Tracing::Vcd => "-vcd",
    };
    let key = format!("w{}-{:016x}{suffix}", dut.width, dut.fingerprint(&version));
    let dir = cache_root().join("verilator").join(&key);
    let exe = dir.join(executable_name());
    if exe.is_file() {
        return Ok((exe, 0.0));
    }
    let started = Instant::now();
    std::fs::create_dir_all(dir.parent().unwrap()).context("creating the Verilator cache directory")?;
    let staging = WorkDir::new(&format!("verilator-build-{key}"))?;
    let sources = write_sources(dut, &staging.path)?;
    let jobs = std::thread::available_parallelism().map_or(2, |n| n.get()).to_string();
    let mut cmd = VERILATOR.command()?;
    // The compiler's temporary files go into the staging directory too, so
    // an interrupted build leaves nothing behind (`tools::interrupt`).
    cmd.current_dir(&staging.path)
        .env("TMPDIR", &staging.path)
        .args(["--binary", "-j", &jobs, "--top-module", TESTBENCH_TOP, "-Mdir", "obj"])
        .arg(format!("-DTRITRI_DUT={}", dut.design.top))
        .arg(format!("-GW={}", dut.width))
        .arg(format!("-GID_WIDTH={}", dut.id_bits))
        // Optimize the model for run time; the build is cached.
        .args(["-O3", "--x-assign", "fast", "--x-initial", "fast", "-CFLAGS", "-O2"])
        .args(if tracing == Tracing::Vcd { &["--trace", "-DTRITRI_VCD"][..] } else { &[] })
        .args(&sources);
    run(&mut cmd).context("building the Verilator model")?;
    let built = staging.path.join("obj").join(executable_name());
    anyhow::ensure!(built.is_file(), "verilator --binary did not produce {}", built.display());
    // Publish: copy the executable into a fresh directory, then rename it into place.
    let publish = dir.with_extension(format!("tmp{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&publish);
    std::fs::create_dir_all(&publish)?;
    std::fs::copy(&built, publish.join(executable_name()))?;
    if std::fs::rename(&publish, &dir).is_err() {
        // Someone else published the same key first: theirs is as good.
        let _ = std::fs::remove_dir_all(&publish);
    }
    anyhow::ensure!(exe.is_file(), "the Verilator cache entry {} is incomplete", dir.display());
    Ok((exe, started.elapsed().as_secs_f64()))
}

/// Runs a built executable on `stream`.
pub fn run_executable(exe: &Path, dut: &RtlDut, stream: &TriangleStream) -> anyhow::Result<(RtlRun, f64)> {
    run_executable_on_vectors(exe, &vectors(stream, dut.width, dut.id_bits), None)
}

/// Runs an arbitrary schedule of input cycles on the emitted `width`-bit
/// pipeline in Verilator (see `rusthdl_harness::run_schedule_on`); with
/// `vcd`, writes the waveform of every signal there (from the traced build).
pub fn run_verilator_schedule(
    width: usize,
    schedule: &[crate::stream::InputCycle],
    vcd: Option<&Path>,
) -> anyhow::Result<crate::stream::StreamResult> {
    let dut = crate::rtl_sim::pipeline_dut(width)?;
    let (exe, _) = build(&dut, if vcd.is_some() { Tracing::Vcd } else { Tracing::Off })?;
    let text = crate::vectors::vectors_for_schedule(schedule, dut.width, dut.id_bits);
    Ok(run_executable_on_vectors(&exe, &text, vcd)?.0.result)
}

fn run_executable_on_vectors(exe: &Path, vector_text: &str, vcd: Option<&Path>) -> anyhow::Result<(RtlRun, f64)> {
    let work = WorkDir::new("verilator-run")?;
    let vectors_path = work.join("vectors.txt");
    let outputs_path = work.join("outputs.txt");
    std::fs::write(&vectors_path, vector_text)?;
    let started = Instant::now();
    let mut cmd = std::process::Command::new(exe);
    cmd.arg(format!("+vectors={}", vectors_path.display()))
        .arg(format!("+outputs={}", outputs_path.display()))
        .args(vcd.map(|path| format!("+vcd={}", path.display())));
    let output = run(&mut cmd)?;
    let seconds = started.elapsed().as_secs_f64();
    let text = std::fs::read_to_string(&outputs_path).with_context(|| {
        format!("the testbench wrote no outputs; the model said:\n{}", String::from_utf8_lossy(&output.stdout))
    })?;
    let (result, timed) = parse_outputs(&text)?;
    Ok((RtlRun { result, timed, build_seconds: 0.0, simulate_seconds: seconds }, seconds))
}

/// Simulates `dut` on `stream` in Verilator (building or reusing the cached model).
pub fn run_verilator_dut(dut: &RtlDut, stream: &TriangleStream) -> anyhow::Result<RtlRun> {
    let (exe, build_seconds) = build(dut, Tracing::Off)?;
    let (mut run, _) = run_executable(&exe, dut, stream)?;
    run.build_seconds = build_seconds;
    Ok(run)
}

/// Runs `stream` on the emitted `width`-bit pipeline in Verilator.
pub fn run_verilator_stream(width: usize, stream: &TriangleStream) -> anyhow::Result<crate::stream::StreamResult> {
    let dut = crate::rtl_sim::pipeline_dut(width)?;
    Ok(run_verilator_dut(&dut, stream)?.result)
}

/// Runs `bases` (each loaded once with `bset`) against `streamed` on the
/// emitted `width`-bit pipeline in Verilator; the same result as
/// [`crate::rusthdl_harness::run_pairs`].
pub fn run_verilator(
    width: usize,
    bases: &[(u32, tritri_geom::fixed_point::FixedTriangle)],
    streamed: &[(u32, tritri_geom::fixed_point::FixedTriangle)],
) -> anyhow::Result<crate::rusthdl_harness::RunResult> {
    Ok(run_verilator_stream(width, &crate::rtl_sim::stream_of(bases, streamed))?.into())
}
