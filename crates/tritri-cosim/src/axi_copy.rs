//! Drives the AXI copy unit ([`tritri_rtl::axi::axi_copy`]) against the
//! memory model, in rust-hdl (the Rust memory model,
//! [`tritri_rtl::axi::memory_model`]) and in Icarus or Verilator (its
//! Verilog twin, `testbenches/axi_memory.sv`, with
//! `testbenches/tb_axi_copy.sv`), and beside them the clock-exact model
//! ([`tritri_rtl::axi::transfer_machine`]): all three give a
//! [`CopyOutcome`], so they compare with `==`.

use crate::axi_drive::{drive_from_memory, manager_signals};
use crate::simulator::{compile, Simulator, Testbench, WorkDir};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use std::fmt::Write as _;
use tritri_rtl::axi::axi_copy::{AxiCopy, COPY_QUEUE_ADDRESS_BITS};
use tritri_rtl::axi::memory_model::{AxiMemory, MemoryParams};
use tritri_rtl::axi::transfer_machine::copy_cycles;
use tritri_rtl::emit::axi_copy_unit::{emit_axi_copy, AxiCopyConfig};
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

/// The Verilog memory model and the copy unit's testbench.
pub const AXI_MEMORY: &str = include_str!("../../../testbenches/axi_memory.sv");
pub const COPY_TESTBENCH: &str = include_str!("../../../testbenches/tb_axi_copy.sv");

/// One copy: the unit, the memory and its bytes, and the region.
#[derive(Clone, Debug)]
pub struct CopyCase {
    pub config: AxiCopyConfig,
    pub params: MemoryParams,
    pub bytes: Vec<u8>,
    pub source: u64,
    pub destination: u64,
    pub beats: u64,
    /// Clocks to wait for `done`.
    pub limit: u64,
}

/// What a copy gave.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CopyOutcome {
    /// Clocks from `start` (clock 0) to the first clock with `done`.
    pub cycles: u64,
    /// Clocks the memory stalled in that time.
    pub stalled: u64,
    pub error: bool,
    /// Protocol faults the memory saw.
    pub faults: usize,
    /// The memory afterwards.
    pub bytes: Vec<u8>,
}

/// The clock-exact model's copy.
pub fn run_model(case: &CopyCase) -> anyhow::Result<CopyOutcome> {
    let region = (case.source, case.destination, case.beats);
    let Some((run, memory)) = copy_cycles(
        case.config.transfer(),
        case.params,
        case.bytes.clone(),
        region,
        case.limit,
    ) else {
        bail!("the model's copy did not end within {} clocks", case.limit);
    };
    Ok(CopyOutcome {
        cycles: run.cycles,
        stalled: run.stalled,
        error: run.error,
        faults: memory.faults().len(),
        bytes: memory.bytes,
    })
}

pub(crate) fn bits_of<const N: usize>(bytes: &[u8]) -> Bits<N> {
    let mut b = Bits::<N>::default();
    for (i, chunk) in bytes.chunks(8).enumerate() {
        let mut word = [0u8; 8];
        word[..chunk.len()].copy_from_slice(chunk);
        b.set_bits::<64>(64 * i, u64::from_le_bytes(word).into());
    }
    b
}

pub(crate) fn bytes_of<const N: usize>(b: Bits<N>) -> Vec<u8> {
    (0..N / 64)
        .flat_map(|i| b.get_bits::<64>(64 * i).to_u64().to_le_bytes())
        .collect()
}

/// The rust-hdl unit's copy, against the Rust memory model.
pub fn run_rusthdl(case: &CopyCase) -> anyhow::Result<CopyOutcome> {
    case.config.transfer().check().map_err(anyhow::Error::msg)?;
    fn run<const DW: usize, const S: usize>(case: &CopyCase) -> anyhow::Result<CopyOutcome> {
        let c = &case.config;
        let mut uut = AxiCopy::<DW, S, COPY_QUEUE_ADDRESS_BITS>::new(c.max_burst, c.outstanding);
        uut.connect_all();
        let mut memory = AxiMemory::new(case.params, case.bytes.clone());
        reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
        uut.source.next = (case.source).into();
        uut.destination.next = (case.destination).into();
        uut.beats.next = (case.beats).into();
        let mut cycles = 0u64;
        loop {
            let out = memory.outputs();
            uut.start.next = cycles == 0;
            drive_from_memory!(uut, &out, DW);
            settle(&mut uut);
            let manager = manager_signals!(uut, DW);
            memory.edge(&manager);
            clock_cycle(&mut uut, |u| &mut u.clock);
            cycles += 1;
            if uut.done.val() {
                break;
            }
            if cycles >= case.limit {
                bail!("the rust-hdl copy did not end within {} clocks", case.limit);
            }
        }
        Ok(CopyOutcome {
            cycles,
            stalled: memory.stalled,
            error: uut.error.val(),
            faults: memory.faults().len(),
            bytes: memory.bytes,
        })
    }
    match case.config.data_bits {
        64 => run::<64, 8>(case),
        128 => run::<128, 16>(case),
        256 => run::<256, 32>(case),
        _ => run::<512, 64>(case),
    }
}

/// The emitted unit's copy in `simulator`, against `axi_memory.sv`.
pub fn run_simulator(simulator: Simulator, case: &CopyCase) -> anyhow::Result<CopyOutcome> {
    let design = emit_axi_copy(&case.config)?;
    let mut files = vec![
        ("tb_axi_copy.sv".to_string(), COPY_TESTBENCH.to_string()),
        ("axi_memory.sv".to_string(), AXI_MEMORY.to_string()),
    ];
    for f in design.verilog_files() {
        files.push((f.path.clone(), f.contents.clone()));
    }
    let p = &case.params;
    let parameters = [
        ("DATA_BITS", case.config.data_bits as u64),
        ("BYTES", case.bytes.len() as u64),
        ("READ_LATENCY", p.read_latency),
        ("WRITE_LATENCY", p.write_latency),
        ("OUTSTANDING", p.outstanding as u64),
        ("BPC_NUM", p.bytes_per_clock.0),
        ("BPC_DEN", p.bytes_per_clock.1),
        ("STALL_PERCENT", u64::from(p.stall_percent)),
        ("SEED", u64::from(p.seed)),
        ("LIMIT", case.limit),
    ];
    let testbench = Testbench {
        top: "tb_axi_copy".to_string(),
        files,
        defines: vec![format!("TRITRI_DUT={}", case.config.unit_name())],
        parameters: parameters
            .iter()
            .map(|(n, v)| (n.to_string(), v.to_string()))
            .collect(),
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &testbench)?;
    let work = WorkDir::new("axi-copy")?;
    let memory_in = work.join("memory.hex");
    let memory_out = work.join("memory_out.hex");
    let mut hex = String::with_capacity(3 * case.bytes.len());
    for b in &case.bytes {
        let _ = writeln!(hex, "{b:02x}");
    }
    std::fs::write(&memory_in, hex)?;
    let output = compiled.run(&[
        format!("+memory={}", memory_in.display()),
        format!("+out={}", memory_out.display()),
        format!("+source={}", case.source),
        format!("+destination={}", case.destination),
        format!("+beats={}", case.beats),
    ])?;
    let text = String::from_utf8_lossy(&output.stdout);
    let line = text
        .lines()
        .find(|l| l.starts_with("# cycles "))
        .with_context(|| format!("the testbench printed no cycles:\n{text}"))?;
    let field = |name: &str| -> anyhow::Result<u64> {
        let mut words = line.split_whitespace();
        while let Some(w) = words.next() {
            if w == name {
                return words
                    .next()
                    .and_then(|v| v.parse().ok())
                    .with_context(|| format!("no number after {name} in {line:?}"));
            }
        }
        bail!("no {name} in {line:?}")
    };
    if field("done")? != 1 {
        bail!("the emitted copy did not end within {} clocks", case.limit);
    }
    let bytes = read_memory_dump(&memory_out, case.bytes.len())?;
    Ok(CopyOutcome {
        cycles: field("cycles")?,
        stalled: field("stalled")?,
        error: field("error")? != 0,
        faults: field("faults")? as usize,
        bytes,
    })
}

/// The first `bytes` bytes of a memory written by `$writememh`, a byte a
/// line (the rest, which the testbench never loaded, may be unknown).
pub(crate) fn read_memory_dump(path: &std::path::Path, bytes: usize) -> anyhow::Result<Vec<u8>> {
    std::fs::read_to_string(path)
        .with_context(|| format!("the memory dump {}", path.display()))?
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("//") && !l.starts_with('@'))
        .take(bytes)
        .map(|l| u8::from_str_radix(l, 16).with_context(|| format!("memory dump line {l:?}")))
        .collect()
}
