//! Drives a cell's pass over lists in external memory
//! ([`tritri_rtl::broad_phase::list_pass`]) against the memory model: in
//! rust-hdl (the Rust memory model, [`tritri_rtl::axi::memory_model`]), in
//! Icarus or Verilator (its Verilog twin, `testbenches/axi_memory.sv`, with
//! `testbenches/tb_list_pass.sv`), and beside them the clock-exact model
//! ([`tritri_rtl::broad_phase::list_pass_machine`]). All three give a
//! [`PassOutcome`], so they compare with `==`; [`PassCase::child_lists`]
//! reads the children's lists out of the memory afterwards, to compare with
//! the software answer ([`tritri_rtl::broad_phase::list_pass_machine::child_lists`]).

use crate::axi_copy::AXI_MEMORY;
use crate::axi_drive::{
    clock_until_done, drive_from_memory, manager_signals, memory_parameters, parse_status,
    read_memory_dump, write_memory_hex,
};
use crate::binning_unit::grid_value;
use crate::simulator::{compile, Simulator, Testbench, WorkDir};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::octree::cell::Cell;
use tritri_rtl::axi::memory_model::{AxiMemory, MemoryParams};
use tritri_rtl::broad_phase::list_entry::ENTRY_BYTES;
use tritri_rtl::broad_phase::list_pass::{ListPass, CHILDREN};
use tritri_rtl::broad_phase::list_pass_machine::{run_pass, ListPassConfig, PassRequest};
use tritri_rtl::emit::list_pass_unit::{
    emit_list_pass, list_pass_unit_name, with_list_pass, ListPassVisitor,
};
use tritri_rtl::sim_drive::reset_one_clock;

/// The pass unit's testbench.
pub const LIST_PASS_TESTBENCH: &str = include_str!("../../../testbenches/tb_list_pass.sv");

/// What the memory holds where nothing was written: a child list that
/// runs past its count shows.
const UNWRITTEN: u8 = 0xa5;

/// One pass: the unit, the memory, the cell and its two lists.
#[derive(Clone, Debug)]
pub struct PassCase {
    pub config: ListPassConfig,
    pub params: MemoryParams,
    pub cell: Cell,
    /// Object `k`'s list of entries ([`tritri_rtl::broad_phase::list_entry`]).
    pub lists: [Vec<[u8; ENTRY_BYTES]>; 2],
    /// Clocks to wait for `done`.
    pub limit: u64,
}

/// What a pass gave.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PassOutcome {
    /// Clocks from `start` (clock 0) to the first clock with `done`.
    pub cycles: u64,
    /// Clocks the memory stalled in that time.
    pub stalled: u64,
    pub error: bool,
    /// Protocol faults the memory saw.
    pub faults: usize,
    /// Entries written to child `8k + o`.
    pub child_counts: [u64; CHILDREN],
    /// The memory afterwards.
    pub bytes: Vec<u8>,
}

impl PassCase {
    /// Where everything lies, as the controller would allocate it: A's list
    /// at 0, B's after it, then each object's eight child lists, each
    /// starting on a write burst and as long as the cell's list (a child
    /// holds at most every entry), at least one burst.
    pub fn request(&self) -> PassRequest {
        let burst = self.config.burst_bytes();
        let round_up = |n: u64| n.div_ceil(burst) * burst;
        let bytes = |k: usize| (self.lists[k].len() * ENTRY_BYTES) as u64;
        let b_list = bytes(0);
        let mut next = round_up(b_list + bytes(1));
        let mut children = [(0, 0); 2];
        for (k, child) in children.iter_mut().enumerate() {
            let stride = round_up(bytes(k)).max(burst);
            *child = (next, stride);
            next += 8 * stride;
        }
        PassRequest {
            cell: self.cell,
            lists: [
                (0, self.lists[0].len() as u64),
                (b_list, self.lists[1].len() as u64),
            ],
            children,
        }
    }

    /// The memory before the pass: the two lists, and the children's
    /// regions (and a burst beyond) unwritten.
    pub fn memory(&self) -> Vec<u8> {
        let request = self.request();
        let (base, stride) = request.children[1];
        let mut bytes = vec![UNWRITTEN; (base + 8 * stride + self.config.burst_bytes()) as usize];
        for (k, list) in self.lists.iter().enumerate() {
            let at = request.lists[k].0 as usize;
            for (i, entry) in list.iter().enumerate() {
                bytes[at + i * ENTRY_BYTES..at + (i + 1) * ENTRY_BYTES].copy_from_slice(entry);
            }
        }
        bytes
    }

    /// The children's lists in `out`'s memory, `out.child_counts` long; an
    /// error if a byte outside them changed.
    pub fn child_lists(&self, out: &PassOutcome) -> anyhow::Result<[Vec<Vec<u8>>; CHILDREN]> {
        let request = self.request();
        let before = self.memory();
        if out.bytes.len() != before.len() {
            bail!(
                "the memory is {} bytes, not {}",
                out.bytes.len(),
                before.len()
            );
        }
        let mut written = vec![false; before.len()];
        let mut lists: [Vec<Vec<u8>>; CHILDREN] = Default::default();
        for (i, list) in lists.iter_mut().enumerate() {
            let (base, stride) = request.children[i / 8];
            let at = (base + (i % 8) as u64 * stride) as usize;
            let count = out.child_counts[i] as usize;
            if (count * ENTRY_BYTES) as u64 > stride {
                bail!("child {i} has {count} entries, more than its region holds");
            }
            for e in 0..count {
                let range = at + e * ENTRY_BYTES..at + (e + 1) * ENTRY_BYTES;
                written[range.clone()].iter_mut().for_each(|w| *w = true);
                list.push(out.bytes[range].to_vec());
            }
        }
        if let Some(i) = (0..before.len()).find(|&i| !written[i] && out.bytes[i] != before[i]) {
            bail!("byte {i:#x}, outside every child list, changed");
        }
        Ok(lists)
    }
}

/// The clock-exact model's pass.
pub fn run_model(case: &PassCase) -> anyhow::Result<PassOutcome> {
    case.config.check().map_err(anyhow::Error::msg)?;
    let mut memory = AxiMemory::new(case.params, case.memory());
    let Some(run) = run_pass(case.config, &mut memory, &case.request(), case.limit) else {
        bail!("the model's pass did not end within {} clocks", case.limit);
    };
    Ok(PassOutcome {
        cycles: run.cycles,
        stalled: run.stalled,
        error: run.error,
        faults: memory.faults().len(),
        child_counts: run.child_counts,
        bytes: memory.bytes,
    })
}

/// The rust-hdl unit's pass, against the Rust memory model.
pub fn run_rusthdl(case: &PassCase) -> anyhow::Result<PassOutcome> {
    with_list_pass(&case.config, RustHdlPass(case)).map_err(anyhow::Error::msg)?
}

struct RustHdlPass<'c>(&'c PassCase);

impl ListPassVisitor for RustHdlPass<'_> {
    type Output = anyhow::Result<PassOutcome>;
    fn visit<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
    >(
        self,
        mut uut: ListPass<G, V, N, T, DW, S>,
    ) -> Self::Output {
        let case = self.0;
        let request = case.request();
        uut.connect_all();
        let mut memory = AxiMemory::new(case.params, case.memory());
        reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
        uut.corner_x.next = grid_value::<G>(request.cell.lo[0]);
        uut.corner_y.next = grid_value::<G>(request.cell.lo[1]);
        uut.corner_z.next = grid_value::<G>(request.cell.lo[2]);
        uut.level.next = u64::from(request.cell.level).into();
        for k in 0..2 {
            uut.list_base[k].next = request.lists[k].0.into();
            uut.list_count[k].next = request.lists[k].1.into();
            uut.child_base[k].next = request.children[k].0.into();
            uut.child_stride[k].next = request.children[k].1.into();
        }
        let cycles = clock_until_done!(uut, memory, DW, case.limit, "pass");
        let mut child_counts = [0u64; CHILDREN];
        for (i, c) in child_counts.iter_mut().enumerate() {
            *c = uut.child_count[i].val().to_u64();
        }
        Ok(PassOutcome {
            cycles,
            stalled: memory.stalled,
            error: uut.error.val(),
            faults: memory.faults().len(),
            child_counts,
            bytes: memory.bytes,
        })
    }
}

/// The emitted unit's pass in `simulator`, against `axi_memory.sv`.
pub fn run_simulator(simulator: Simulator, case: &PassCase) -> anyhow::Result<PassOutcome> {
    let design = emit_list_pass(&case.config)?;
    let mut files = vec![
        (
            "tb_list_pass.sv".to_string(),
            LIST_PASS_TESTBENCH.to_string(),
        ),
        ("axi_memory.sv".to_string(), AXI_MEMORY.to_string()),
    ];
    for f in design.verilog_files() {
        files.push((f.path.clone(), f.contents.clone()));
    }
    let memory = case.memory();
    let mut parameters = vec![
        ("GRID_BITS".to_string(), case.config.grid_bits.to_string()),
        ("DATA_BITS".to_string(), case.config.data_bits.to_string()),
    ];
    // A power of two, so that cases of about one size share one Verilator
    // build; the bytes past the case's memory are not compared.
    let bytes = (memory.len() as u64).next_power_of_two().max(1 << 16);
    parameters.extend(memory_parameters(&case.params, bytes));
    parameters.push(("LIMIT".to_string(), case.limit.to_string()));
    let testbench = Testbench {
        top: "tb_list_pass".to_string(),
        files,
        defines: vec![format!("TRITRI_DUT={}", list_pass_unit_name(&case.config))],
        parameters,
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &testbench)?;
    let work = WorkDir::new("list-pass")?;
    let memory_in = work.join("memory.hex");
    let memory_out = work.join("memory_out.hex");
    write_memory_hex(&memory_in, &memory)?;
    let request = case.request();
    let g = case.config.grid_bits;
    let corner = |v: i64| (v as u64) & ((1u64 << g) - 1);
    let mut plusargs = vec![
        format!("+memory={}", memory_in.display()),
        format!("+out={}", memory_out.display()),
        format!("+corner_x={}", corner(request.cell.lo[0])),
        format!("+corner_y={}", corner(request.cell.lo[1])),
        format!("+corner_z={}", corner(request.cell.lo[2])),
        format!("+level={}", request.cell.level),
    ];
    for k in 0..2 {
        plusargs.push(format!("+list_base_{k}={}", request.lists[k].0));
        plusargs.push(format!("+list_count_{k}={}", request.lists[k].1));
        plusargs.push(format!("+child_base_{k}={}", request.children[k].0));
        plusargs.push(format!("+child_stride_{k}={}", request.children[k].1));
    }
    let output = compiled.run(&plusargs)?;
    let text = String::from_utf8_lossy(&output.stdout);
    let status = parse_status(&text)?;
    if !status.done {
        bail!("the emitted pass did not end within {} clocks", case.limit);
    }
    let counts: Vec<u64> = text
        .lines()
        .find_map(|l| l.strip_prefix("# counts "))
        .with_context(|| format!("the testbench printed no child counts:\n{text}"))?
        .split_whitespace()
        .map(|w| w.parse().with_context(|| format!("child count {w:?}")))
        .collect::<anyhow::Result<_>>()?;
    let child_counts: [u64; CHILDREN] = counts.try_into().map_err(|c: Vec<u64>| {
        anyhow::anyhow!(
            "the testbench printed {} child counts, not {CHILDREN}",
            c.len()
        )
    })?;
    let bytes = read_memory_dump(&memory_out, memory.len())?;
    Ok(PassOutcome {
        cycles: status.cycles,
        stalled: status.stalled,
        error: status.error,
        faults: status.faults,
        child_counts,
        bytes,
    })
}
