//! Drives the AXI copy unit ([`tritri_rtl::axi::axi_copy`]) against the
//! memory model, in rust-hdl (the Rust memory model,
//! [`tritri_rtl::axi::memory_model`]) and in Icarus or Verilator (its
//! Verilog twin, `testbenches/axi_memory.sv`, with
//! `testbenches/tb_axi_copy.sv`), and beside them the clock-exact model
//! ([`tritri_rtl::axi::transfer_machine`]): all three give a
//! [`CopyOutcome`], so they compare with `==`.

use crate::axi_drive::{
    clock_until_done, drive_from_memory, manager_signals, memory_parameters, parse_status,
    read_memory_dump, write_memory_hex,
};
use crate::simulator::{compile, Simulator, Testbench, WorkDir};
use anyhow::bail;
use rust_hdl::prelude::*;
use tritri_rtl::axi::axi_copy::{AxiCopy, COPY_QUEUE_ADDRESS_BITS};
use tritri_rtl::axi::memory_model::{AxiMemory, MemoryParams};
use tritri_rtl::axi::transfer_machine::copy_cycles;
use tritri_rtl::emit::axi_copy_unit::{emit_axi_copy, AxiCopyConfig};
use tritri_rtl::sim_drive::reset_one_clock;

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
        let cycles = clock_until_done!(uut, memory, DW, case.limit, "copy");
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
    let mut parameters = vec![("DATA_BITS".to_string(), case.config.data_bits.to_string())];
    parameters.extend(memory_parameters(&case.params, case.bytes.len() as u64));
    parameters.push(("LIMIT".to_string(), case.limit.to_string()));
    let testbench = Testbench {
        top: "tb_axi_copy".to_string(),
        files,
        defines: vec![format!("TRITRI_DUT={}", case.config.unit_name())],
        parameters,
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &testbench)?;
    let work = WorkDir::new("axi-copy")?;
    let memory_in = work.join("memory.hex");
    let memory_out = work.join("memory_out.hex");
    write_memory_hex(&memory_in, &case.bytes)?;
    let output = compiled.run(&[
        format!("+memory={}", memory_in.display()),
        format!("+out={}", memory_out.display()),
        format!("+source={}", case.source),
        format!("+destination={}", case.destination),
        format!("+beats={}", case.beats),
    ])?;
    let status = parse_status(&String::from_utf8_lossy(&output.stdout))?;
    if !status.done {
        bail!("the emitted copy did not end within {} clocks", case.limit);
    }
    let bytes = read_memory_dump(&memory_out, case.bytes.len())?;
    Ok(CopyOutcome {
        cycles: status.cycles,
        stalled: status.stalled,
        error: status.error,
        faults: status.faults,
        bytes,
    })
}
