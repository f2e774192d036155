//! Drives the leaf reader ([`tritri_rtl::broad_phase::leaf_reader`]) against
//! the memory model: in rust-hdl (the Rust memory model), in Icarus or
//! Verilator (`testbenches/axi_memory.sv` with `testbenches/tb_leaf_reader.sv`),
//! and beside them the clock-exact model
//! ([`tritri_rtl::broad_phase::leaf_reader_machine`]). All three give a
//! [`LeafOutcome`], every word of the stream with the clock it was taken
//! in, so they compare with `==`; [`LeafCase::expected_words`] is the
//! stream without clocks, from the lists themselves.

use crate::axi_copy::AXI_MEMORY;
use crate::axi_drive::{
    drive_from_memory, manager_signals, memory_parameters, parse_status, write_memory_hex,
};
use crate::binning_unit::{grid_value, signed_grid_value};
use crate::simulator::{compile, signed_hex_fields, Simulator, Testbench, WorkDir};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::cell::Cell;
use tritri_rtl::axi::memory_model::{AxiMemory, MemoryParams};
use tritri_rtl::broad_phase::leaf_reader::LeafReader;
use tritri_rtl::broad_phase::leaf_reader_machine::{read_leaf, LeafRequest, LeafWord};
use tritri_rtl::broad_phase::list_entry::{unpack, ENTRY_BYTES};
use tritri_rtl::broad_phase::list_pass_machine::ListPassConfig;
use tritri_rtl::emit::leaf_reader_unit::{
    emit_leaf_reader, leaf_reader_unit_name, with_leaf_reader, LeafReaderVisitor,
};
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

/// The leaf reader's testbench.
pub const LEAF_READER_TESTBENCH: &str = include_str!("../../../testbenches/tb_leaf_reader.sv");

/// One leaf: the unit, the memory, the leaf's cell and lists, and how often
/// the stream's reader is ready.
#[derive(Clone, Debug)]
pub struct LeafCase {
    pub config: ListPassConfig,
    pub params: MemoryParams,
    pub cell: Cell,
    /// Object `k`'s list of entries ([`tritri_rtl::broad_phase::list_entry`]).
    pub lists: [Vec<[u8; ENTRY_BYTES]>; 2],
    /// `out_ready` in clock `t` is `(7 t + 3) mod 10 < ready_tenths`
    /// (10: always), the testbench's rule.
    pub ready_tenths: u64,
    /// Clocks to wait for `busy` to fall.
    pub limit: u64,
}

/// A word of the leaf stream as the unit's ports show it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StreamWord {
    Header {
        corner: [i64; 3],
        level: u64,
        counts: [u64; 2],
    },
    Entry {
        object: bool,
        index: u32,
        triangle: FixedTriangle,
    },
}

/// What reading the leaf gave.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LeafOutcome {
    /// Every word taken, with its clock (`start`'s is 0).
    pub words: Vec<(u64, StreamWord)>,
    /// The first clock with `reading` low.
    pub read_cycles: u64,
    /// The first clock with `busy` low.
    pub cycles: u64,
    pub stalled: u64,
    pub error: bool,
    /// Protocol faults the memory saw.
    pub faults: usize,
}

impl LeafCase {
    /// `out_ready` in clock `t`.
    pub fn ready(&self, t: u64) -> bool {
        (7 * t + 3) % 10 < self.ready_tenths
    }

    /// A's list at 0 and B's after it, with a gap, so that a read past
    /// A's end shows (the gap is not an entry of either).
    pub fn request(&self) -> LeafRequest {
        let a_bytes = (self.lists[0].len() * ENTRY_BYTES) as u64;
        let b_base = (a_bytes + 4096).next_multiple_of(4096) + 3 * ENTRY_BYTES as u64;
        LeafRequest {
            cell: self.cell,
            lists: [
                (0, self.lists[0].len() as u64),
                (b_base, self.lists[1].len() as u64),
            ],
        }
    }

    /// The memory: the two lists, 0xa5 elsewhere.
    pub fn memory(&self) -> Vec<u8> {
        let request = self.request();
        let end = request.lists[1].0 as usize + self.lists[1].len() * ENTRY_BYTES + 4096;
        let mut bytes = vec![0xa5; end];
        for (k, list) in self.lists.iter().enumerate() {
            let at = request.lists[k].0 as usize;
            for (i, entry) in list.iter().enumerate() {
                bytes[at + i * ENTRY_BYTES..at + (i + 1) * ENTRY_BYTES].copy_from_slice(entry);
            }
        }
        bytes
    }

    /// The stream the leaf must give: the header, A's entries, B's.
    pub fn expected_words(&self) -> Vec<StreamWord> {
        let g = self.config.grid_bits;
        let mut words = vec![StreamWord::Header {
            corner: self.cell.lo,
            level: u64::from(self.cell.level),
            counts: [self.lists[0].len() as u64, self.lists[1].len() as u64],
        }];
        for (k, list) in self.lists.iter().enumerate() {
            for entry in list {
                let (index, triangle) = unpack(entry, g);
                words.push(StreamWord::Entry {
                    object: k == 1,
                    index,
                    triangle,
                });
            }
        }
        words
    }
}

/// The clock-exact model's run.
pub fn run_model(case: &LeafCase) -> anyhow::Result<LeafOutcome> {
    case.config.check().map_err(anyhow::Error::msg)?;
    let g = case.config.grid_bits;
    let mut memory = AxiMemory::new(case.params, case.memory());
    let Some(run) = read_leaf(
        case.config,
        &mut memory,
        &case.request(),
        |t| case.ready(t),
        case.limit,
    ) else {
        bail!("the model's leaf did not end within {} clocks", case.limit);
    };
    let words = run
        .words
        .into_iter()
        .map(|(t, word)| {
            let word = match word {
                LeafWord::Header { cell, counts } => StreamWord::Header {
                    corner: cell.lo,
                    level: u64::from(cell.level),
                    counts,
                },
                LeafWord::Entry { object, entry } => {
                    let (index, triangle) = unpack(&entry, g);
                    StreamWord::Entry {
                        object,
                        index,
                        triangle,
                    }
                }
            };
            (t, word)
        })
        .collect();
    Ok(LeafOutcome {
        words,
        read_cycles: run.read_cycles,
        cycles: run.cycles,
        stalled: run.stalled,
        error: run.error,
        faults: memory.faults().len(),
    })
}

/// The rust-hdl unit's run, against the Rust memory model.
pub fn run_rusthdl(case: &LeafCase) -> anyhow::Result<LeafOutcome> {
    with_leaf_reader(&case.config, RustHdlLeaf(case)).map_err(anyhow::Error::msg)?
}

struct RustHdlLeaf<'c>(&'c LeafCase);

impl LeafReaderVisitor for RustHdlLeaf<'_> {
    type Output = anyhow::Result<LeafOutcome>;
    fn visit<const G: usize, const T: usize, const DW: usize, const S: usize>(
        self,
        mut uut: LeafReader<G, T, DW, S>,
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
        }
        let mut words = Vec::new();
        let mut read_cycles = None;
        let mut t = 0u64;
        loop {
            if t > 0 && !uut.reading.val() && read_cycles.is_none() {
                read_cycles = Some(t);
            }
            if t > 0 && !uut.busy.val() {
                break;
            }
            if t >= case.limit {
                bail!("the rust-hdl leaf did not end within {} clocks", case.limit);
            }
            let out = memory.outputs();
            uut.start.next = t == 0;
            uut.out_ready.next = case.ready(t);
            drive_from_memory!(uut, &out, DW);
            settle(&mut uut);
            if uut.out_valid.val() && uut.out_ready.val() {
                let signed = |v: Bits<G>| signed_grid_value(v.to_u64(), G);
                let word = if uut.out_header.val() {
                    StreamWord::Header {
                        corner: [
                            signed(uut.out_x.val()),
                            signed(uut.out_y.val()),
                            signed(uut.out_z.val()),
                        ],
                        level: uut.out_level.val().to_u64(),
                        counts: [
                            uut.out_count_a.val().to_u64(),
                            uut.out_count_b.val().to_u64(),
                        ],
                    }
                } else {
                    let vertices = uut.out_vertices.val();
                    let mut triangle = [[0i64; 3]; 3];
                    for k in 0..9 {
                        triangle[k / 3][k % 3] = signed(vertices.get_bits::<G>(k * G));
                    }
                    StreamWord::Entry {
                        object: uut.out_object.val(),
                        index: uut.out_index.val().to_u64() as u32,
                        triangle,
                    }
                };
                words.push((t, word));
            }
            let manager = manager_signals!(uut, DW);
            memory.edge(&manager);
            clock_cycle(&mut uut, |u| &mut u.clock);
            t += 1;
        }
        Ok(LeafOutcome {
            words,
            read_cycles: read_cycles.unwrap_or(t),
            cycles: t,
            stalled: memory.stalled,
            error: uut.error.val(),
            faults: memory.faults().len(),
        })
    }
}

/// A `9 g`-bit vertices word printed in hex, as a triangle.
fn triangle_from_hex(hex: &str, g: usize) -> anyhow::Result<FixedTriangle> {
    let c = signed_hex_fields(hex, g, 9).with_context(|| format!("vertices {hex:?}"))?;
    Ok(std::array::from_fn(|i| {
        std::array::from_fn(|k| c[3 * i + k] as i64)
    }))
}

/// The emitted unit's run in `simulator`, against `axi_memory.sv`.
pub fn run_simulator(simulator: Simulator, case: &LeafCase) -> anyhow::Result<LeafOutcome> {
    let design = emit_leaf_reader(&case.config)?;
    let mut files = vec![
        (
            "tb_leaf_reader.sv".to_string(),
            LEAF_READER_TESTBENCH.to_string(),
        ),
        ("axi_memory.sv".to_string(), AXI_MEMORY.to_string()),
    ];
    for f in design.verilog_files() {
        files.push((f.path.clone(), f.contents.clone()));
    }
    let memory = case.memory();
    let g = case.config.grid_bits;
    let mut parameters = vec![
        ("GRID_BITS".to_string(), g.to_string()),
        ("DATA_BITS".to_string(), case.config.data_bits.to_string()),
    ];
    // A power of two, so that cases of about one size share one build.
    let bytes = (memory.len() as u64).next_power_of_two().max(1 << 16);
    parameters.extend(memory_parameters(&case.params, bytes));
    parameters.push(("READY_TENTHS".to_string(), case.ready_tenths.to_string()));
    parameters.push(("LIMIT".to_string(), case.limit.to_string()));
    let testbench = Testbench {
        top: "tb_leaf_reader".to_string(),
        files,
        defines: vec![format!(
            "TRITRI_DUT={}",
            leaf_reader_unit_name(&case.config)
        )],
        parameters,
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &testbench)?;
    let work = WorkDir::new("leaf-reader")?;
    let memory_in = work.join("memory.hex");
    write_memory_hex(&memory_in, &memory)?;
    let request = case.request();
    let corner = |v: i64| (v as u64) & ((1u64 << g) - 1);
    let mut plusargs = vec![
        format!("+memory={}", memory_in.display()),
        format!("+corner_x={}", corner(request.cell.lo[0])),
        format!("+corner_y={}", corner(request.cell.lo[1])),
        format!("+corner_z={}", corner(request.cell.lo[2])),
        format!("+level={}", request.cell.level),
    ];
    for k in 0..2 {
        plusargs.push(format!("+list_base_{k}={}", request.lists[k].0));
        plusargs.push(format!("+list_count_{k}={}", request.lists[k].1));
    }
    let output = compiled.run(&plusargs)?;
    let text = String::from_utf8_lossy(&output.stdout);
    let status = parse_status(&text)?;
    if !status.done {
        bail!(
            "the emitted leaf reader did not end within {} clocks",
            case.limit
        );
    }
    let number = |w: Option<&str>, what: &str, line: &str| -> anyhow::Result<u64> {
        w.and_then(|w| w.parse().ok())
            .with_context(|| format!("no {what} in {line:?}"))
    };
    let mut words = Vec::new();
    let mut read_cycles = None;
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("# header ") {
            let mut w = rest.split_whitespace();
            let mut next = |what: &str| number(w.next(), what, line);
            let t = next("clock")?;
            let raw = [next("x")?, next("y")?, next("z")?];
            let level = next("level")?;
            let counts = [next("count a")?, next("count b")?];
            let corner = raw.map(|v| signed_grid_value(v, g));
            words.push((
                t,
                StreamWord::Header {
                    corner,
                    level,
                    counts,
                },
            ));
        } else if let Some(rest) = line.strip_prefix("# entry ") {
            let mut w = rest.split_whitespace();
            let t = number(w.next(), "clock", line)?;
            let object = number(w.next(), "object", line)? == 1;
            let index = number(w.next(), "index", line)? as u32;
            let hex = w
                .next()
                .with_context(|| format!("no vertices in {line:?}"))?;
            words.push((
                t,
                StreamWord::Entry {
                    object,
                    index,
                    triangle: triangle_from_hex(hex, g)?,
                },
            ));
        } else if let Some(rest) = line.strip_prefix("# read ") {
            read_cycles = Some(number(Some(rest.trim()), "clock", line)?);
        }
    }
    Ok(LeafOutcome {
        words,
        read_cycles: read_cycles
            .with_context(|| format!("the testbench printed no read:\n{text}"))?,
        cycles: status.cycles,
        stalled: status.stalled,
        error: status.error,
        faults: status.faults,
    })
}
