//! Runs the emitted system Verilog in Icarus or Verilator
//! ([`crate::simulator`]) with `testbenches/tb_collision_system.sv`, on
//! the same batches and host
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
//! Overlap, the reader, progress reports and the waveform are plusargs;
//! the vectors are written into a named pipe as the simulator reads them
//! ([`run_on_vector_stream`]), so a long run stores no vector file.

use crate::simulator::{compile, run_on_vector_stream, Compiled, Simulator, Testbench};
use crate::system_harness::{host_words, Batch, ReaderBehaviour, SystemResult};
use anyhow::Context as _;
use std::io::Write;
use std::path::Path;
use tritri_rtl::emit::EmittedDesign;
use tritri_rtl::system::system_for_width::PipelineKind;
use tritri_rtl::system::system_unit::emit_system;
use tritri_rtl::system::SystemConfig;

/// The testbench, compiled into the library so runs need no checkout.
pub const SYSTEM_TESTBENCH: &str = include_str!("../../../testbenches/tb_collision_system.sv");
/// Its top module.
pub const SYSTEM_TESTBENCH_TOP: &str = "tb_collision_system";

/// Writes the vectors of `batches` (module docs) to `out`, word by word.
pub fn write_system_vectors(
    out: &mut dyn Write,
    batches: &[Batch],
    width: usize,
) -> std::io::Result<()> {
    let mask = if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    };
    for batch in batches {
        for word in host_words(batch) {
            let kind = if word.end {
                2
            } else if word.object_b {
                1
            } else {
                0
            };
            write!(out, "{kind} {:x}", word.id)?;
            for c in word.coordinates {
                write!(out, " {:x}", (c as u64) & mask)?;
            }
            writeln!(out)?;
        }
    }
    Ok(())
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
            let value: u64 = words
                .next()
                .with_context(|| format!("line {}: `{line}`", n + 1))?
                .parse()?;
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
        let mut field = || -> anyhow::Result<u32> {
            let w = words.next().with_context(|| {
                format!("line {}: `{line}` needs two ids, hit and certain", n + 1)
            })?;
            Ok(u32::from_str_radix(w, 16)?)
        };
        let (id_a, id_b, hit, certain) = (field()?, field()?, field()?, field()?);
        result.record(id_a, id_b, hit != 0, certain != 0);
    }
    anyhow::ensure!(saw_cycles, "the testbench output has no `# cycles` line");
    Ok(result)
}

/// The testbench around the emitted system `design` of `width`-bit
/// coordinates; `trace`: built to dump a waveform (`+vcd=FILE`).
pub fn system_testbench(design: &EmittedDesign, width: usize, trace: bool) -> Testbench {
    let mut files = vec![(
        format!("{SYSTEM_TESTBENCH_TOP}.sv"),
        SYSTEM_TESTBENCH.to_string(),
    )];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    Testbench {
        top: SYSTEM_TESTBENCH_TOP.into(),
        files,
        defines: vec![format!("TRITRI_SYSTEM={}", design.top)],
        parameters: vec![("W".into(), width.to_string())],
        // The system is large: a faster C++ build, at little cost per cycle.
        c_optimization: 1,
        trace,
    }
}

/// Cycles between two progress reports of the testbench.
pub const PROGRESS_PERIOD: u64 = 1 << 16;

/// How a system run reports and records, beyond its result.
#[derive(Clone, Copy, Default)]
pub struct SystemRunOptions<'a> {
    /// Told the cycles simulated since its last call, every
    /// [`PROGRESS_PERIOD`] cycles.
    pub progress: Option<&'a (dyn Fn(u64) + Sync)>,
    /// Dump the run's waveform here (a traced build: slower).
    pub vcd: Option<&'a Path>,
}

/// Runs a compiled system testbench on `batches`.
pub fn run_compiled_system(
    compiled: &Compiled,
    width: usize,
    batches: &[Batch],
    overlap: bool,
    reader: ReaderBehaviour,
    options: SystemRunOptions,
) -> anyhow::Result<SystemResult> {
    let period = match reader {
        ReaderBehaviour::AlwaysReady => 1,
        ReaderBehaviour::OneIn(k) => k.max(1),
    };
    let mut extra = vec![
        format!("+overlap={}", overlap as u8),
        format!("+reader_period={period}"),
    ];
    if options.progress.is_some() {
        extra.push(format!("+progress={PROGRESS_PERIOD}"));
    }
    if let Some(vcd) = options.vcd {
        extra.push(format!("+vcd={}", vcd.display()));
    }
    let mut reported = 0u64;
    let mut on_line = |line: &str| {
        if let (Some(progress), Some(cycle)) = (
            options.progress,
            line.strip_prefix("# progress ")
                .and_then(|c| c.trim().parse::<u64>().ok()),
        ) {
            progress(cycle.saturating_sub(reported));
            reported = reported.max(cycle);
        }
    };
    let mut write = |out: &mut dyn Write| write_system_vectors(out, batches, width);
    let (text, _) = run_on_vector_stream(compiled, "system-run", &mut write, &extra, &mut on_line)?;
    parse_system_outputs(&text)
}

/// Emits the system for `config`, compiles it in `simulator` (Verilator:
/// or reuses the cached model) and runs `batches` through it.
pub fn run_system_rtl(
    simulator: Simulator,
    config: SystemConfig,
    kind: PipelineKind,
    batches: &[Batch],
    overlap: bool,
    reader: ReaderBehaviour,
) -> anyhow::Result<SystemResult> {
    run_system_rtl_with(
        simulator,
        config,
        kind,
        batches,
        overlap,
        reader,
        SystemRunOptions::default(),
    )
}

/// [`run_system_rtl`] with progress reports or a waveform.
pub fn run_system_rtl_with(
    simulator: Simulator,
    config: SystemConfig,
    kind: PipelineKind,
    batches: &[Batch],
    overlap: bool,
    reader: ReaderBehaviour,
    options: SystemRunOptions,
) -> anyhow::Result<SystemResult> {
    let design = emit_system(config, kind)?;
    let compiled = compile(
        simulator,
        &system_testbench(&design, config.coordinate_bits, options.vcd.is_some()),
    )?;
    run_compiled_system(
        &compiled,
        config.coordinate_bits,
        batches,
        overlap,
        reader,
        options,
    )
}
