//! The broad phase's binning with every list in external memory, on a
//! prepared scene: the host's lists written into the memory, the
//! controller's clock-exact model
//! ([`tritri_rtl::broad_phase::dram_binning_machine`]) run over the list pass
//! unit's (co-simulated in tests/list_pass.rs) against the memory model,
//! and its leaves held to the planner's for a binner that streams its
//! leaves ([`DramSplitRule`]), cell for cell and triangle for triangle.
//!
//! The controller itself (`tritri_rtl::broad_phase::dram_binning_unit`) runs on
//! the same case in rust-hdl against the Rust memory model
//! ([`run_rusthdl`]) and, emitted, in Verilator or Icarus against
//! `axi_memory.sv` ([`run_simulator`]); [`UnitRun::check_against`] holds
//! either to the model.
//!
//! The memory: A's root list at 0, B's after it on a write burst, then
//! the arena for the children's lists.

use crate::axi_copy::AXI_MEMORY;
use crate::axi_drive::{
    drive_from_memory, manager_signals, memory_parameters, parse_status, read_memory_dump,
    write_memory_hex,
};
use crate::binning_unit::{grid_value, signed_grid_value};
use crate::simulator::{compile, Simulator, Testbench, WorkDir};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::octree::cell::Cell;
use tritri_geom::scene::octree::{schedule, OctreeSchedule};
use tritri_geom::scene::{PreparedScene, TaggedTriangle};
use tritri_rtl::axi::memory_model::{AxiMemory, ManagerSignals, MemoryOutputs, MemoryParams};
use tritri_rtl::broad_phase::binning_machine::BinningParams;
use tritri_rtl::broad_phase::dram_binning_machine::{
    read_list, run_dram_binning_beside, Beside, DramBinningConfig, DramBinningRun, DramLeaf,
    DramSplitRule, ListPlace, TakesEveryLeaf,
};
use tritri_rtl::broad_phase::dram_binning_unit::{DramBinningUnit, WAITING_CAPACITY};
use tritri_rtl::broad_phase::list_entry::{pack, unpack, ENTRY_BYTES};
use tritri_rtl::broad_phase::list_pass_machine::ListPassConfig;
use tritri_rtl::emit::dram_binning_unit_unit::{
    dram_binning_unit_name, emit_dram_binning, with_dram_binning, DramBinningVisitor,
};
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

use crate::scene_query::Accelerator;

/// The testbench of the emitted controller against the memory model.
pub const DRAM_BINNING_TESTBENCH: &str = include_str!("../../../testbenches/tb_dram_binning.sv");

/// A run and what it was held to.
pub struct DramBinning {
    pub run: DramBinningRun,
    /// The planner's tree for the same rule.
    pub schedule: OctreeSchedule,
    /// Bytes of the two root lists (what the host writes).
    pub root_bytes: u64,
}

/// A binning to run: the memory as the host leaves it (A's root list at
/// 0, B's after it on a write burst, then the arena), the controller's
/// configuration, the root and its lists.
#[derive(Clone, Debug)]
pub struct DramCase {
    pub config: DramBinningConfig,
    pub params: MemoryParams,
    pub bytes: Vec<u8>,
    pub root: Cell,
    pub root_lists: [ListPlace; 2],
    /// Push back on the controller with [`pushed_back`]'s pattern
    /// (otherwise every leaf is taken at once and no pass is held).
    pub pushback: bool,
}

impl DramCase {
    /// The controller's inputs for this case, by their port names, as the
    /// testbenches take them (`+name=value`): the root's corner as
    /// unsigned grid-bit numbers, its level, the root lists, the arena.
    pub fn inputs(&self) -> Vec<(String, u64)> {
        let g = self.config.pass.grid_bits;
        let corner = |v: i64| (v as u64) & ((1u64 << g) - 1);
        let mut inputs = vec![
            ("corner_x".to_string(), corner(self.root.lo[0])),
            ("corner_y".to_string(), corner(self.root.lo[1])),
            ("corner_z".to_string(), corner(self.root.lo[2])),
            ("level".to_string(), u64::from(self.root.level)),
            ("arena_start".to_string(), self.config.arena.0),
            ("arena_end".to_string(), self.config.arena.1),
        ];
        for k in 0..2 {
            inputs.push((format!("list_base_{k}"), self.root_lists[k].0));
            inputs.push((format!("list_count_{k}"), self.root_lists[k].1));
        }
        inputs
    }
}

/// The words of a testbench's line that are numbers (a negative one is
/// not), in order.
pub(crate) fn numbers(line: &str) -> anyhow::Result<Vec<u64>> {
    line.split_whitespace()
        .filter(|w| w.chars().all(|c| c.is_ascii_digit()))
        .map(|w| w.parse().with_context(|| format!("{w:?} in {line:?}")))
        .collect()
}

/// The pattern of `pushback` in clock `t` (the start's clock is 0):
/// `(leaf_ready, pass_hold)`. A leaf is refused one clock in three and a
/// pass held three clocks in seven, so that a leaf and a pass each meet
/// both values (testbenches/tb_dram_binning.sv drives the same).
pub fn pushed_back(t: u64) -> (bool, bool) {
    (t % 3 != 1, t % 7 < 3)
}

/// What the testbench's pattern is to the model.
struct Pushback {
    t: u64,
}

impl Beside for Pushback {
    fn hold(&self) -> bool {
        pushed_back(self.t).1
    }
    fn ready(&self) -> bool {
        pushed_back(self.t).0
    }
    fn drive(&self, _m: &mut ManagerSignals) {}
    fn clock(&mut self, _mem: &MemoryOutputs, _leaf: Option<(Cell, [ListPlace; 2])>) {
        self.t += 1;
    }
}

/// The controller for `accelerator` (its split rule: the system's depth and
/// pipelines, the levels local frames split) over passes of `pass`; the
/// arena is the run's (empty here).
pub fn binning_config(accelerator: &Accelerator, pass: ListPassConfig) -> DramBinningConfig {
    DramBinningConfig {
        pass,
        rule: BinningParams {
            log_depth: accelerator.depth.ilog2(),
            log_pipelines: accelerator.pipelines.ilog2(),
            max_leaf_level: accelerator.local_frames().map(|l| l.max_leaf_level()),
        },
        arena: (0, 0),
        waiting_capacity: WAITING_CAPACITY,
    }
}

/// The case of `scene` (prepared for `accelerator`) with its lists in a
/// memory of `params`, the arena `arena_bytes` long, and the planner's
/// tree for the same rule.
pub fn dram_case(
    accelerator: &Accelerator,
    scene: &PreparedScene,
    pass: ListPassConfig,
    params: MemoryParams,
    arena_bytes: u64,
) -> anyhow::Result<(DramCase, OctreeSchedule)> {
    let root_box = scene
        .integer_box
        .context("the objects' boxes do not meet: nothing to bin")?;
    let depth = accelerator.depth as usize;
    if !depth.is_power_of_two() || !accelerator.pipelines.is_power_of_two() {
        bail!(
            "the split rule in hardware needs a power-of-two depth and pipeline count, not {} and {}",
            depth,
            accelerator.pipelines
        );
    }
    let local_frames = accelerator.local_frames();
    let rule = DramSplitRule {
        system: accelerator.system_config(),
        pass,
    };
    let schedule = schedule(
        &scene.kept_a,
        &scene.kept_b,
        &root_box,
        depth,
        &rule,
        local_frames,
    );
    let root = schedule.root.context("the schedule has no root")?;
    // The triangles the planner bins (the others go to the host).
    let binned = |list: &[TaggedTriangle]| -> Vec<[u8; ENTRY_BYTES]> {
        list.iter()
            .filter(|t| local_frames.is_none_or(|l| l.fits_any_leaf(t)))
            .map(|t| pack(t.id, &t.triangle, pass.grid_bits))
            .collect()
    };
    let lists = [binned(&scene.kept_a), binned(&scene.kept_b)];
    let burst = pass.burst_bytes();
    let round_up = |n: u64| n.div_ceil(burst) * burst;
    let b_at = round_up((lists[0].len() * ENTRY_BYTES) as u64);
    let arena_start = round_up(b_at + (lists[1].len() * ENTRY_BYTES) as u64);
    let arena_end = arena_start + round_up(arena_bytes);
    let mut bytes = vec![0u8; arena_end as usize];
    for (at, list) in [0, b_at].into_iter().zip(&lists) {
        for (i, entry) in list.iter().enumerate() {
            let from = at as usize + i * ENTRY_BYTES;
            bytes[from..from + ENTRY_BYTES].copy_from_slice(entry);
        }
    }
    let config = DramBinningConfig {
        arena: (arena_start, arena_end),
        ..binning_config(accelerator, pass)
    };
    let case = DramCase {
        config,
        params,
        bytes,
        root,
        root_lists: [(0, lists[0].len() as u64), (b_at, lists[1].len() as u64)],
        pushback: false,
    };
    Ok((case, schedule))
}

/// The controller's clock-exact model on `case`, and the memory after it.
pub fn run_model(case: &DramCase) -> anyhow::Result<(DramBinningRun, Vec<u8>)> {
    let mut memory = AxiMemory::new(case.params, case.bytes.clone());
    let mut pushback = Pushback { t: 0 };
    let mut takes_every_leaf = TakesEveryLeaf;
    let beside: &mut dyn Beside = if case.pushback {
        &mut pushback
    } else {
        &mut takes_every_leaf
    };
    let run = run_dram_binning_beside(case.config, &mut memory, case.root, case.root_lists, beside)
        .map_err(anyhow::Error::msg)?;
    Ok((run, memory.bytes))
}

/// Bins `scene` (prepared for `accelerator`) with its lists in a memory of
/// `params`, the arena `arena_bytes` long, in the controller's model. When
/// no cell found the arena full, an error unless the leaves are the
/// planner's.
pub fn bin_in_dram(
    accelerator: &Accelerator,
    scene: &PreparedScene,
    pass: ListPassConfig,
    params: MemoryParams,
    arena_bytes: u64,
) -> anyhow::Result<DramBinning> {
    let (case, schedule) = dram_case(accelerator, scene, pass, params, arena_bytes)?;
    let (run, _) = run_model(&case)?;
    if run.arena_full == 0 {
        leaves_are_the_planners(&run, &schedule, pass.grid_bits)?;
    }
    Ok(DramBinning {
        run,
        schedule,
        root_bytes: case.config.arena.0,
    })
}

/// What the emitted or rust-hdl controller gave: the same fields as the
/// model's run where they can be seen at the unit's ports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnitRun {
    pub leaves: Vec<DramLeaf>,
    /// Clocks from `start` to `done`.
    pub cycles: u64,
    pub stalled: u64,
    pub passes: u64,
    pub arena_full: u64,
    pub waiting_commits: u64,
    pub error: bool,
    pub faults: usize,
    pub bytes: Vec<u8>,
}

impl UnitRun {
    /// Nothing, when `self` equals the model's run and the memory after it
    /// (`bytes`) in everything the unit's ports show; else an error naming
    /// the first difference. A leaf's entries are compared where they were
    /// read (rust-hdl reads them from the memory in the leaf's clock; the
    /// simulators leave them empty, and their memory is compared at the
    /// end).
    pub fn check_against(&self, model: &DramBinningRun, bytes: &[u8]) -> anyhow::Result<()> {
        for (i, (got, want)) in self.leaves.iter().zip(&model.leaves).enumerate() {
            if (got.cell, got.lists, got.clock) != (want.cell, want.lists, want.clock) {
                bail!(
                    "leaf {i}: {:?} {:?} at clock {}, the model's {:?} {:?} at clock {}",
                    got.cell,
                    got.lists,
                    got.clock,
                    want.cell,
                    want.lists,
                    want.clock
                );
            }
            if !got.entries[0].is_empty() && got.entries != want.entries {
                bail!(
                    "leaf {i} ({:?}): its lists' entries differ from the model's",
                    got.cell
                );
            }
        }
        let seen = (
            self.leaves.len(),
            self.cycles,
            self.stalled,
            self.passes,
            self.arena_full,
            self.waiting_commits,
        );
        let expected = (
            model.leaves.len(),
            model.cycles,
            model.stalled,
            model.passes,
            model.arena_full,
            model.waiting_commits,
        );
        if seen != expected {
            bail!(
                "(leaves, clocks, stalled, passes, arena full, waiting commits) = {seen:?}, the model's {expected:?}"
            );
        }
        if self.error || self.faults != 0 {
            bail!("error {} and {} protocol faults", self.error, self.faults);
        }
        if let Some(at) = self.bytes.iter().zip(bytes).position(|(a, b)| a != b) {
            bail!("the memory differs from the model's at byte {at:#x}");
        }
        Ok(())
    }
}

/// The rust-hdl controller on `case`, against the Rust memory model; each
/// leaf's entries read from the memory in the clock it goes out.
pub fn run_rusthdl(case: &DramCase, limit: u64) -> anyhow::Result<UnitRun> {
    with_dram_binning(&case.config, RustHdlBinning { case, limit }).map_err(anyhow::Error::msg)?
}

struct RustHdlBinning<'c> {
    case: &'c DramCase,
    limit: u64,
}

impl DramBinningVisitor for RustHdlBinning<'_> {
    type Output = anyhow::Result<UnitRun>;
    fn visit<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
    >(
        self,
        mut uut: DramBinningUnit<G, V, N, T, DW, S>,
    ) -> Self::Output {
        let case = self.case;
        uut.connect_all();
        let mut memory = AxiMemory::new(case.params, case.bytes.clone());
        reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
        uut.corner_x.next = grid_value::<G>(case.root.lo[0]);
        uut.corner_y.next = grid_value::<G>(case.root.lo[1]);
        uut.corner_z.next = grid_value::<G>(case.root.lo[2]);
        uut.level.next = u64::from(case.root.level).into();
        for k in 0..2 {
            uut.list_base[k].next = case.root_lists[k].0.into();
            uut.list_count[k].next = case.root_lists[k].1.into();
        }
        uut.arena_start.next = case.config.arena.0.into();
        uut.arena_end.next = case.config.arena.1.into();
        let mut leaves = Vec::new();
        let mut cycles = 0u64;
        loop {
            let out = memory.outputs();
            uut.start.next = cycles == 0;
            let (ready, hold) = if case.pushback {
                pushed_back(cycles)
            } else {
                (true, false)
            };
            uut.leaf_ready.next = ready;
            uut.pass_hold.next = hold;
            drive_from_memory!(uut, &out, DW);
            settle(&mut uut);
            if uut.leaf_valid.val() & ready {
                let cell = Cell {
                    lo: [uut.leaf_x.val(), uut.leaf_y.val(), uut.leaf_z.val()]
                        .map(|v| signed_grid_value(v.to_u64(), G)),
                    level: uut.leaf_level.val().to_u64() as u32,
                };
                let lists: [ListPlace; 2] = std::array::from_fn(|k| {
                    (
                        uut.leaf_base[k].val().to_u64(),
                        uut.leaf_count[k].val().to_u64(),
                    )
                });
                leaves.push(DramLeaf {
                    cell,
                    lists,
                    clock: cycles + 1,
                    after_passes: uut.passes.val().to_u64(),
                    entries: lists.map(|place| read_list(&memory, place)),
                });
            }
            let manager = manager_signals!(uut, DW);
            memory.edge(&manager);
            clock_cycle(&mut uut, |u| &mut u.clock);
            cycles += 1;
            if uut.done.val() {
                break;
            }
            if cycles >= self.limit {
                bail!(
                    "the rust-hdl binning did not end within {} clocks",
                    self.limit
                );
            }
        }
        Ok(UnitRun {
            leaves,
            cycles,
            stalled: memory.stalled,
            passes: uut.passes.val().to_u64(),
            arena_full: uut.arena_full.val().to_u64(),
            waiting_commits: uut.waiting_commits.val().to_u64(),
            error: uut.error.val(),
            faults: memory.faults().len(),
            bytes: memory.bytes,
        })
    }
}

/// The emitted controller in `simulator`, against `axi_memory.sv`: the
/// leaves it printed (without their entries: the final memory is compared
/// instead), the clocks and the memory after the walk.
pub fn run_simulator(simulator: Simulator, case: &DramCase, limit: u64) -> anyhow::Result<UnitRun> {
    let design = emit_dram_binning(&case.config)?;
    let mut files = vec![
        (
            "tb_dram_binning.sv".to_string(),
            DRAM_BINNING_TESTBENCH.to_string(),
        ),
        ("axi_memory.sv".to_string(), AXI_MEMORY.to_string()),
    ];
    for f in design.verilog_files() {
        files.push((f.path.clone(), f.contents.clone()));
    }
    let pass = case.config.pass;
    let mut parameters = vec![
        ("GRID_BITS".to_string(), pass.grid_bits.to_string()),
        ("DATA_BITS".to_string(), pass.data_bits.to_string()),
    ];
    // A power of two, so that cases of about one size share one Verilator
    // build; the bytes past the case's memory are not compared.
    let bytes = (case.bytes.len() as u64).next_power_of_two().max(1 << 16);
    parameters.extend(memory_parameters(&case.params, bytes));
    parameters.push(("LIMIT".to_string(), limit.to_string()));
    parameters.push(("PUSHBACK".to_string(), u8::from(case.pushback).to_string()));
    let testbench = Testbench {
        top: "tb_dram_binning".to_string(),
        files,
        defines: vec![format!(
            "TRITRI_DUT={}",
            dram_binning_unit_name(&case.config)
        )],
        parameters,
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &testbench)?;
    let work = WorkDir::new("dram-binning")?;
    let memory_in = work.join("memory.hex");
    let memory_out = work.join("memory_out.hex");
    write_memory_hex(&memory_in, &case.bytes)?;
    let g = pass.grid_bits;
    let mut plusargs = vec![
        format!("+memory={}", memory_in.display()),
        format!("+out={}", memory_out.display()),
    ];
    plusargs.extend(case.inputs().iter().map(|(name, v)| format!("+{name}={v}")));
    let output = compiled.run(&plusargs)?;
    let text = String::from_utf8_lossy(&output.stdout);
    let status = parse_status(&text)?;
    if !status.done {
        bail!("the emitted binning did not end within {limit} clocks");
    }
    let mut leaves = Vec::new();
    for line in text.lines().filter_map(|l| l.strip_prefix("# leaf ")) {
        let v = numbers(line)?;
        let [clock, x, y, z, level, b0, n0, b1, n1] = v[..] else {
            bail!("a leaf line of {} numbers: {line:?}", v.len());
        };
        leaves.push(DramLeaf {
            cell: Cell {
                lo: [x, y, z].map(|v| signed_grid_value(v, g)),
                level: level as u32,
            },
            lists: [(b0, n0), (b1, n1)],
            clock,
            after_passes: 0,
            entries: [Vec::new(), Vec::new()],
        });
    }
    let counts = text
        .lines()
        .find_map(|l| l.strip_prefix("# passes "))
        .with_context(|| format!("the testbench printed no passes:\n{text}"))?;
    let counts = numbers(counts)?;
    let [passes, arena_full, waiting_commits] = counts[..] else {
        bail!("the testbench's passes line holds {} numbers", counts.len());
    };
    let bytes = read_memory_dump(&memory_out, case.bytes.len())?;
    Ok(UnitRun {
        leaves,
        cycles: status.cycles,
        stalled: status.stalled,
        passes,
        arena_full,
        waiting_commits,
        error: status.error,
        faults: status.faults,
        bytes,
    })
}

/// An error naming the first leaf that is not the planner's.
fn leaves_are_the_planners(
    run: &DramBinningRun,
    schedule: &OctreeSchedule,
    grid_bits: usize,
) -> anyhow::Result<()> {
    if run.leaves.len() != schedule.leaves.len() {
        bail!(
            "{} leaves, the planner has {}",
            run.leaves.len(),
            schedule.leaves.len()
        );
    }
    for (i, (leaf, planned)) in run.leaves.iter().zip(&schedule.leaves).enumerate() {
        if leaf.cell != planned.cell {
            bail!(
                "leaf {i} is cell {:?}, the planner's {:?}",
                leaf.cell,
                planned.cell
            );
        }
        let (a, b) = schedule.leaf_arrays(planned);
        for (k, expected) in [a, b].into_iter().enumerate() {
            let got: Vec<u32> = leaf.entries[k]
                .iter()
                .map(|e| unpack(e, grid_bits).0)
                .collect();
            let want: Vec<u32> = expected.iter().map(|t| t.id).collect();
            if got != want {
                bail!(
                    "leaf {i} ({:?}): object {k}'s list is {} triangles, not the planner's {}",
                    leaf.cell,
                    got.len(),
                    want.len()
                );
            }
        }
    }
    Ok(())
}
