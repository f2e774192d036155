//! Runs the emitted system Verilog in Verilator 5 (`verilator --binary`)
//! with `testbenches/tb_collision_system.sv`, on the same batches and host
//! behaviour as the rust-hdl harness ([`crate::system_harness`]); the two
//! must return the same pairs in the same order, the same cycle count and
//! the same counters.
//!
//! Vector format (testbenches/README.md, "Collision system"): one host word
//! per line (no comments), eleven hex fields `kind id x0 y0 z0 x1 y1 z1 x2 y2 z2`, kind 0
//! = triangle of A, 1 = triangle of B, 2 = end of batch; coordinates as W-bit
//! two's complement. Output: one `id_a id_b` line (hex) per pair, then
//! `# cycles N`, `# pairs_tested N`, `# hits N`, `# stall_cycles N`,
//! `# overflow 0|1`.
//!
//! The model is built once per design and cached like the pipeline's (see
//! [`crate::verilator::cache_root`]); overlap and the reader are plusargs.

use crate::rtl_sim::WorkDir;
use crate::system_harness::{host_words, Batch, ReaderBehaviour, SystemResult};
use anyhow::Context as _;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use tritri_rtl::emit::EmittedDesign;
use tritri_rtl::system::system_for_width::PipelineKind;
use tritri_rtl::system::system_unit::emit_system;
use tritri_rtl::system::SystemConfig;
use tritri_rtl::tools::{run, VERILATOR};

/// The testbench, compiled into the library so runs need no checkout.
pub const SYSTEM_TESTBENCH: &str = include_str!("../../../testbenches/tb_collision_system.sv");
/// Its top module.
pub const SYSTEM_TESTBENCH_TOP: &str = "tb_collision_system";

/// The vector file of `batches` (module docs).
pub fn system_vectors(batches: &[Batch], width: usize) -> String {
    let mask = if width >= 64 { u64::MAX } else { (1u64 << width) - 1 };
    let mut text = String::new();
    for batch in batches {
        for word in host_words(batch) {
            let kind = if word.end { 2 } else if word.object_b { 1 } else { 0 };
            let _ = write!(text, "{kind} {:x}", word.id);
            for c in word.coordinates {
                let _ = write!(text, " {:x}", (c as u64) & mask);
            }
            text.push('\n');
        }
    }
    text
}

/// Parses the testbench's output file.
pub fn parse_system_outputs(text: &str) -> anyhow::Result<SystemResult> {
    let mut result = SystemResult::default();
    let mut saw_cycles = false;
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        if let Some(rest) = line.strip_prefix('#') {
            let mut words = rest.split_whitespace();
            let key = words.next().unwrap_or("");
            anyhow::ensure!(key != "timeout", "the testbench timed out");
            let value: u64 = words.next().with_context(|| format!("line {}: `{line}`", n + 1))?.parse()?;
            match key {
                "cycles" => {
                    result.cycles = value;
                    saw_cycles = true;
                }
                "pairs_tested" => result.pairs_tested = value,
                "hits" => result.hits = value,
                "stall_cycles" => result.stall_cycles = value,
                "overflow" => result.overflow = value != 0,
                _ => anyhow::bail!("line {}: unknown summary `{line}`", n + 1),
            }
            continue;
        }
        let mut words = line.split_whitespace();
        let mut id = || -> anyhow::Result<u32> {
            let w = words.next().with_context(|| format!("line {}: `{line}` needs two ids", n + 1))?;
            Ok(u32::from_str_radix(w, 16)?)
        };
        let pair = (id()?, id()?);
        result.pairs.push(pair);
    }
    anyhow::ensure!(saw_cycles, "the testbench output has no `# cycles` line");
    Ok(result)
}

/// FNV-1a over the strings (the cache key must be the same in every build).
fn fingerprint<'a>(parts: impl IntoIterator<Item = &'a str>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for part in parts {
        for &b in part.as_bytes().iter().chain(b"\0") {
            h ^= b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

/// The Verilator executable of `design` with the system testbench, built
/// unless cached.
pub fn build_system_model(design: &EmittedDesign, width: usize) -> anyhow::Result<PathBuf> {
    VERILATOR.locate()?;
    let version = String::from_utf8_lossy(&run(VERILATOR.command()?.arg("--version"))?.stdout).trim().to_string();
    let width_text = width.to_string();
    let mut parts: Vec<&str> = vec![SYSTEM_TESTBENCH, &version, &width_text];
    for f in design.verilog_files() {
        parts.push(&f.path);
        parts.push(&f.contents);
    }
    let key = format!("system-{}-{:016x}", design.top, fingerprint(parts));
    let dir = crate::verilator::cache_root().join("verilator").join(&key);
    let exe_name = format!("V{SYSTEM_TESTBENCH_TOP}");
    let exe = dir.join(&exe_name);
    if exe.is_file() {
        return Ok(exe);
    }
    std::fs::create_dir_all(dir.parent().unwrap()).context("creating the Verilator cache directory")?;
    let staging = WorkDir::new(&format!("verilator-build-{key}"))?;
    let mut sources = vec![staging.join("tb_collision_system.sv")];
    std::fs::write(&sources[0], SYSTEM_TESTBENCH)?;
    for f in design.verilog_files() {
        let p = staging.join(&f.path);
        std::fs::write(&p, &f.contents)?;
        sources.push(p);
    }
    let jobs = std::thread::available_parallelism().map_or(2, |n| n.get()).to_string();
    let mut cmd = VERILATOR.command()?;
    // The compiler's temporary files go into the staging directory too, so
    // an interrupted build leaves nothing behind (`tools::interrupt`).
    cmd.current_dir(&staging.path)
        .env("TMPDIR", &staging.path)
        .args(["--binary", "-j", &jobs, "--top-module", SYSTEM_TESTBENCH_TOP, "-Mdir", "obj"])
        .arg(format!("-DTRITRI_SYSTEM={}", design.top))
        .arg(format!("-GW={width}"))
        .args(["-Wno-fatal", "-O3", "--x-assign", "fast", "--x-initial", "fast", "-CFLAGS", "-O1"])
        .args(&sources);
    run(&mut cmd).context("building the Verilator model of the system")?;
    let built = staging.path.join("obj").join(&exe_name);
    anyhow::ensure!(built.is_file(), "verilator --binary did not produce {}", built.display());
    let publish = dir.with_extension(format!("tmp{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&publish);
    std::fs::create_dir_all(&publish)?;
    std::fs::copy(&built, publish.join(&exe_name))?;
    if std::fs::rename(&publish, &dir).is_err() {
        let _ = std::fs::remove_dir_all(&publish);
    }
    anyhow::ensure!(exe.is_file(), "the Verilator cache entry {} is incomplete", dir.display());
    Ok(exe)
}

/// Runs a built model on `batches`.
pub fn run_system_model(
    exe: &Path,
    width: usize,
    batches: &[Batch],
    overlap: bool,
    reader: ReaderBehaviour,
) -> anyhow::Result<SystemResult> {
    let work = WorkDir::new("system-verilator-run")?;
    let vectors_path = work.join("vectors.txt");
    let outputs_path = work.join("outputs.txt");
    std::fs::write(&vectors_path, system_vectors(batches, width))?;
    let period = match reader {
        ReaderBehaviour::AlwaysReady => 1,
        ReaderBehaviour::OneIn(k) => k.max(1),
    };
    let mut cmd = std::process::Command::new(exe);
    cmd.arg(format!("+vectors={}", vectors_path.display()))
        .arg(format!("+outputs={}", outputs_path.display()))
        .arg(format!("+overlap={}", overlap as u8))
        .arg(format!("+reader_period={period}"));
    let output = run(&mut cmd)?;
    let text = std::fs::read_to_string(&outputs_path).with_context(|| {
        format!("the testbench wrote no outputs; the model said:\n{}", String::from_utf8_lossy(&output.stdout))
    })?;
    parse_system_outputs(&text)
}

/// Emits the system for `config`, builds (or reuses) its Verilator model
/// and runs `batches` through it.
pub fn run_system_verilator(
    config: SystemConfig,
    kind: PipelineKind,
    batches: &[Batch],
    overlap: bool,
    reader: ReaderBehaviour,
) -> anyhow::Result<SystemResult> {
    let design = emit_system(config, kind)?;
    let exe = build_system_model(&design, config.coordinate_bits)?;
    run_system_model(&exe, config.coordinate_bits, batches, overlap, reader)
}
