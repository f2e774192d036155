//! The broad-phase accelerator with its scene in DRAM
//! ([`tritri_rtl::broad_phase::dram_broad_phase`]) on a prepared scene: the
//! host's root lists in the memory model, the top run in rust-hdl until
//! `done`, each pair it streams recorded; and the exact answer on the grid
//! it is held to: every intersecting pair of A's and B's kept triangles,
//! and every pair its leaves hold whose verdict has no certificate.

use crate::dram_binning::{dram_case, numbers, run_model, DramCase};
use crate::scene_query::Accelerator;
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use std::collections::BTreeSet;
use tritri_geom::certificate::certified_intersects;
use tritri_geom::fixed_point::intersects;
use tritri_geom::scene::octree::OctreeSchedule;
use tritri_geom::scene::{PreparedScene, TaggedTriangle};
use tritri_rtl::axi::memory_model::{AxiMemory, MemoryParams};
use tritri_rtl::broad_phase::broad_phase_system::slots_of_leaves;
use tritri_rtl::broad_phase::dram_broad_phase::{DramBroadPhase, SharedDramBroadPhase};
use tritri_rtl::broad_phase::dram_broad_phase_machine::run_dram_broad_phase;
use tritri_rtl::broad_phase::list_entry::{pack, unpack, ENTRY_BYTES};
use tritri_rtl::broad_phase::list_pass_machine::ListPassConfig;
use tritri_rtl::emit::dram_broad_phase_unit::{
    emit_dram_broad_phase, with_dram_broad_phase, DramBroadPhaseConfig, DramBroadPhaseVisitor,
};
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

use crate::axi_copy::AXI_MEMORY;
use crate::axi_drive::{
    drive_from_memory, manager_signals, memory_parameters, parse_status, write_memory_hex,
};
use crate::binning_unit::grid_value;
use crate::simulator::{compile, Simulator, Testbench, WorkDir};
use tritri_rtl::emit::dsp_mapping::MultiplierMapping;

/// A run of the top to make: the controller's case (the memory as the
/// host leaves it) and the top around it.
#[derive(Clone, Debug)]
pub struct TopCase {
    pub binning: DramCase,
    pub config: DramBroadPhaseConfig,
    /// Each object's triangle indices are below this.
    pub index_count: [u64; 2],
    /// The host numbers each root list's entries 0, 1, ... (so that the
    /// owner filter's head table holds the triangles in the common box, not
    /// the whole mesh): entry `i` of object `k` is triangle `ids[k][i]`.
    pub ids: [Vec<u32>; 2],
}

impl TopCase {
    /// The top's inputs for this case, by their port names: the
    /// controller's ([`DramCase::inputs`]) and each object's index bound.
    pub fn inputs(&self) -> Vec<(String, u64)> {
        let mut inputs = self.binning.inputs();
        for k in 0..2 {
            inputs.push((format!("index_count_{k}"), self.index_count[k]));
        }
        inputs
    }

    /// The pairs of `run` as the meshes number their triangles; an error
    /// names an index the host never wrote.
    fn to_originals(&self, run: &mut TopRun) -> anyhow::Result<()> {
        let original = |&(a, b): &(u32, u32)| -> anyhow::Result<(u32, u32)> {
            match (self.ids[0].get(a as usize), self.ids[1].get(b as usize)) {
                (Some(&a), Some(&b)) => Ok((a, b)),
                _ => bail!(
                    "the top streamed the pair ({a}, {b}); the lists hold {} and {} entries",
                    self.ids[0].len(),
                    self.ids[1].len()
                ),
            }
        };
        run.pairs = run.pairs.iter().map(original).collect::<Result<_, _>>()?;
        run.uncertain = run
            .uncertain
            .iter()
            .map(original)
            .collect::<Result<_, _>>()?;
        Ok(())
    }
}

/// Numbers the entries of each root list in `case`'s memory by their place
/// in the list; gives the triangles' own numbers, list by list.
fn number_root_entries(case: &mut DramCase) -> [Vec<u32>; 2] {
    let g = case.config.pass.grid_bits;
    std::array::from_fn(|k| {
        let (at, count) = case.root_lists[k];
        (0..count as usize)
            .map(|i| {
                let from = at as usize + i * ENTRY_BYTES;
                let entry = &mut case.bytes[from..from + ENTRY_BYTES];
                let (id, triangle) = unpack(entry, g);
                entry.copy_from_slice(&pack(i as u32, &triangle, g));
                id
            })
            .collect()
    })
}

/// The case of `scene` (prepared for `accelerator`): the controller's
/// ([`dram_case`]), the owner filter's tables sized for the leaves the
/// controller's model makes (every tile's entries), and the planner's
/// tree.
pub fn top_case(
    accelerator: &Accelerator,
    scene: &PreparedScene,
    pass: ListPassConfig,
    params: MemoryParams,
    arena_bytes: u64,
) -> anyhow::Result<(TopCase, OctreeSchedule)> {
    let (mut binning, schedule) = dram_case(accelerator, scene, pass, params, arena_bytes)?;
    let ids = number_root_entries(&mut binning);
    let system = accelerator.system_config();
    let (model, _) = run_model(&binning)?;
    let slots = slots_of_leaves(
        system.triangles_per_bank,
        model
            .leaves
            .iter()
            .map(|l| l.lists.map(|(_, n)| n as usize)),
    );
    let index_count = binning.root_lists.map(|(_, count)| count);
    let config = DramBroadPhaseConfig {
        binning: binning.config,
        system,
        triangles: index_count.into_iter().max().unwrap_or(1).max(1) as usize,
        slots: slots.into_iter().max().unwrap_or(1).max(1),
        local_frames: accelerator.local_frames().is_some(),
        rare_cases: accelerator.rare_cases,
    };
    Ok((
        TopCase {
            binning,
            config,
            index_count,
            ids,
        },
        schedule,
    ))
}

/// The exact answer on the grid: every (A, B) pair of kept triangles that
/// intersects, sorted. (Two triangles that meet share a leaf, so the top
/// must stream each of these.)
pub fn exact_on_grid(scene: &PreparedScene) -> Vec<(u32, u32)> {
    let boxes = |list: &[TaggedTriangle]| -> Vec<([i64; 3], [i64; 3])> {
        list.iter()
            .map(|t| {
                let v = t.triangle;
                let lo = std::array::from_fn(|k| v.iter().map(|p| p[k]).min().unwrap());
                let hi = std::array::from_fn(|k| v.iter().map(|p| p[k]).max().unwrap());
                (lo, hi)
            })
            .collect()
    };
    let (box_a, box_b) = (boxes(&scene.kept_a), boxes(&scene.kept_b));
    let mut pairs = BTreeSet::new();
    for (ta, ba) in scene.kept_a.iter().zip(&box_a) {
        for (tb, bb) in scene.kept_b.iter().zip(&box_b) {
            // Boxes apart on the grid: no intersection on the grid.
            if (0..3).any(|k| ba.1[k] < bb.0[k] || bb.1[k] < ba.0[k]) {
                continue;
            }
            if intersects(&ta.triangle, &tb.triangle) {
                pairs.insert((ta.id, tb.id));
            }
        }
    }
    pairs.into_iter().collect()
}

/// An error unless `got` holds each pair once and is `want` as a set,
/// naming `what` and the pairs missing and extra.
pub fn once_and_exact(got: &[(u32, u32)], want: &[(u32, u32)], what: &str) -> anyhow::Result<()> {
    let set: BTreeSet<_> = got.iter().copied().collect();
    anyhow::ensure!(set.len() == got.len(), "{what}: a pair came out twice");
    let want: BTreeSet<_> = want.iter().copied().collect();
    anyhow::ensure!(
        set == want,
        "{what}: {} pairs, the exact answer on the grid has {} ({} missing, {} extra)",
        set.len(),
        want.len(),
        want.difference(&set).count(),
        set.difference(&want).count()
    );
    Ok(())
}

/// What the top must stream, from the leaves of the controller's walk (the
/// model's, on the case's memory), as the meshes number their triangles,
/// sorted: every (A, B) pair sharing a leaf that intersects on the grid
/// (`hits`), and every one whose verdict the certified predicate cannot
/// certify (`uncertain`). This is the model engine's narrow phase: the
/// owner filter passes each pair once, so the top's stream is these sets.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LeafPairs {
    pub hits: Vec<(u32, u32)>,
    pub uncertain: Vec<(u32, u32)>,
    /// Pairs tested over all leaves (a pair in several leaves each time).
    pub tested: u64,
}

/// [`LeafPairs`] of `case`'s walk.
pub fn leaf_pairs(case: &TopCase) -> anyhow::Result<LeafPairs> {
    let (walk, _) = run_model(&case.binning)?;
    let g = case.binning.config.pass.grid_bits;
    let (mut hits, mut uncertain) = (BTreeSet::new(), BTreeSet::new());
    let mut tested = 0;
    for leaf in &walk.leaves {
        let [a, b] = leaf
            .entries
            .each_ref()
            .map(|list| list.iter().map(|e| unpack(e, g)).collect::<Vec<_>>());
        tested += (a.len() * b.len()) as u64;
        for (ia, ta) in &a {
            for (ib, tb) in &b {
                let verdict = certified_intersects(ta, tb);
                let pair = (case.ids[0][*ia as usize], case.ids[1][*ib as usize]);
                if verdict.hit {
                    hits.insert(pair);
                }
                if !verdict.certain {
                    uncertain.insert(pair);
                }
            }
        }
    }
    Ok(LeafPairs {
        hits: hits.into_iter().collect(),
        uncertain: uncertain.into_iter().collect(),
        tested,
    })
}

/// The pairs without a certificate that the top must stream
/// ([`LeafPairs::uncertain`]). This depends on the leaves: two triangles a
/// step apart on the grid may be uncertain (their originals may touch) and
/// be tested only where they share a leaf.
pub fn uncertain_in_leaves(case: &TopCase) -> anyhow::Result<Vec<(u32, u32)>> {
    Ok(leaf_pairs(case)?.uncertain)
}

/// What a run of the top gave.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TopRun {
    /// The pairs streamed with `out_hit`, and those without a certificate,
    /// in stream order.
    pub pairs: Vec<(u32, u32)>,
    pub uncertain: Vec<(u32, u32)>,
    /// Clocks from `start` (clock 0) to the first clock with `binned`,
    /// `tested` and `done` high.
    pub binned_at: u64,
    pub tested_at: u64,
    pub cycles: u64,
    pub leaves: u64,
    pub passes: u64,
    pub pairs_tested: u64,
    pub hits: u64,
    pub stalled: u64,
    /// Beats the memory read and wrote over the run (the port's width
    /// each): the DRAM traffic.
    pub beats_read: u64,
    pub beats_written: u64,
    pub error: bool,
    pub overflow: bool,
    pub faults: usize,
}

impl TopRun {
    /// The run ended cleanly (no error response, no overflow, no fault)
    /// and streamed the exact pairs and the uncertain ones, each once.
    pub fn is_exact(&self, pairs: &[(u32, u32)], uncertain: &[(u32, u32)]) -> anyhow::Result<()> {
        anyhow::ensure!(
            !self.error && !self.overflow && self.faults == 0,
            "error {}, overflow {}, {} faults",
            self.error,
            self.overflow,
            self.faults
        );
        once_and_exact(&self.pairs, pairs, "intersecting")?;
        once_and_exact(&self.uncertain, uncertain, "without a certificate")
    }
}

/// The rust-hdl top on `case` against the Rust memory model, the pairs'
/// reader always ready; an error past `limit` clocks.
pub fn run_top_rusthdl(case: &TopCase, limit: u64) -> anyhow::Result<TopRun> {
    with_dram_broad_phase(&case.config, RustHdlTop { case, limit }).map_err(anyhow::Error::msg)?
}

struct RustHdlTop<'c> {
    case: &'c TopCase,
    limit: u64,
}

// Both tops have the same ports: one body, in a macro since the two are
// distinct types with no trait over their signals.
macro_rules! run_top {
    ($visitor:ident, $uut:ident) => {{
        let (mut uut, this) = ($uut, $visitor);
        let case = &this.case.binning;
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
            uut.index_count[k].next = this.case.index_count[k].into();
        }
        uut.arena_start.next = case.config.arena.0.into();
        uut.arena_end.next = case.config.arena.1.into();
        uut.out_ready.next = true;
        let mut run = TopRun::default();
        let (mut binned, mut tested) = (None, None);
        let mut cycles = 0u64;
        loop {
            let out = memory.outputs();
            uut.start.next = cycles == 0;
            drive_from_memory!(uut, &out, DW);
            settle(&mut uut);
            if uut.out_valid.val() {
                let pair = (
                    uut.out_index_a.val().to_u64() as u32,
                    uut.out_index_b.val().to_u64() as u32,
                );
                if uut.out_hit.val() {
                    run.pairs.push(pair);
                }
                if !uut.out_certain.val() {
                    run.uncertain.push(pair);
                }
            }
            if cycles > 0 {
                if uut.binned.val() && binned.is_none() {
                    binned = Some(cycles);
                }
                if uut.tested.val() && tested.is_none() {
                    tested = Some(cycles);
                }
                if uut.done.val() {
                    break;
                }
            }
            let manager = manager_signals!(uut, DW);
            memory.edge(&manager);
            clock_cycle(&mut uut, |u| &mut u.clock);
            cycles += 1;
            if cycles >= this.limit {
                bail!("the rust-hdl top did not end within {} clocks", this.limit);
            }
        }
        run.binned_at = binned.context("done before binned")?;
        run.tested_at = tested.context("done before tested")?;
        run.cycles = cycles;
        run.leaves = uut.leaves.val().to_u64();
        run.passes = uut.passes.val().to_u64();
        run.pairs_tested = uut.pairs_tested.val().to_u64();
        run.hits = uut.hits.val().to_u64();
        run.stalled = memory.stalled;
        run.beats_read = memory.beats_read;
        run.beats_written = memory.beats_written;
        run.error = uut.error.val();
        run.overflow = uut.overflow.val();
        run.faults = memory.faults().len();
        this.case.to_originals(&mut run)?;
        Ok(run)
    }};
}

impl DramBroadPhaseVisitor for RustHdlTop<'_> {
    type Output = anyhow::Result<TopRun>;
    fn visit<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    >(
        self,
        uut: DramBroadPhase<G, V, N, T, DW, S, W, D, C, O>,
    ) -> Self::Output {
        run_top!(self, uut)
    }
    fn visit_shared<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const DW: usize,
        const S: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    >(
        self,
        uut: SharedDramBroadPhase<G, V, N, T, DW, S, W, D, C, O>,
    ) -> Self::Output {
        run_top!(self, uut)
    }
}

/// testbenches/tb_dram_broad_phase.sv: the top against `axi_memory.sv`.
pub const DRAM_BROAD_PHASE_TESTBENCH: &str =
    include_str!("../../../testbenches/tb_dram_broad_phase.sv");

/// The emitted top in `simulator`, against `axi_memory.sv`, the pairs'
/// reader always ready: what it printed, as [`run_top_rusthdl`] records it.
pub fn run_top_simulator(
    simulator: Simulator,
    case: &TopCase,
    limit: u64,
) -> anyhow::Result<TopRun> {
    let design = emit_dram_broad_phase(&case.config, MultiplierMapping::Inferred)?;
    let binning = &case.binning;
    let mut files = vec![
        (
            "tb_dram_broad_phase.sv".to_string(),
            DRAM_BROAD_PHASE_TESTBENCH.to_string(),
        ),
        ("axi_memory.sv".to_string(), AXI_MEMORY.to_string()),
    ];
    for f in design.verilog_files() {
        files.push((f.path.clone(), f.contents.clone()));
    }
    let pass = binning.config.pass;
    let mut parameters = vec![
        ("GRID_BITS".to_string(), pass.grid_bits.to_string()),
        ("DATA_BITS".to_string(), pass.data_bits.to_string()),
    ];
    // The arena's end bounds every address the top reads or writes.
    let bytes = binning
        .config
        .arena
        .1
        .max(binning.bytes.len() as u64)
        .next_power_of_two()
        .max(1 << 16);
    parameters.extend(memory_parameters(&binning.params, bytes));
    parameters.push(("LIMIT".to_string(), limit.to_string()));
    let testbench = Testbench {
        top: "tb_dram_broad_phase".to_string(),
        files,
        defines: vec![format!("TRITRI_DUT={}", case.config.unit_name())],
        parameters,
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &testbench)?;
    let work = WorkDir::new("dram-broad-phase")?;
    let memory_in = work.join("memory.hex");
    write_memory_hex(&memory_in, &binning.bytes)?;
    let mut plusargs = vec![format!("+memory={}", memory_in.display())];
    plusargs.extend(case.inputs().iter().map(|(name, v)| format!("+{name}={v}")));
    let output = compiled.run(&plusargs)?;
    let text = String::from_utf8_lossy(&output.stdout);
    let status = parse_status(&text)?;
    if !status.done {
        bail!("the emitted top did not end within {limit} clocks");
    }
    // (-1, a flag never seen, is not a number: the line gives none.)
    let mut run = TopRun::default();
    for line in text.lines().filter_map(|l| l.strip_prefix("# pair ")) {
        let v = numbers(line)?;
        let [_clock, a, b, hit, certain] = v[..] else {
            bail!("a pair line of {} numbers: {line:?}", v.len());
        };
        let pair = (a as u32, b as u32);
        if hit != 0 {
            run.pairs.push(pair);
        }
        if certain == 0 {
            run.uncertain.push(pair);
        }
    }
    let line = |prefix: &str| -> anyhow::Result<Vec<u64>> {
        let l = text
            .lines()
            .find_map(|l| l.strip_prefix(prefix))
            .with_context(|| format!("the testbench printed no {prefix:?}:\n{text}"))?;
        numbers(l)
    };
    run.binned_at = *line("# binned ")?.first().context("done before binned")?;
    run.tested_at = *line("# tested ")?.first().context("done before tested")?;
    let [leaves, passes, pairs_tested, hits, overflow] = line("# counts ")?[..] else {
        bail!("the testbench's counts line is not 5 numbers");
    };
    run.cycles = status.cycles;
    run.leaves = leaves;
    run.passes = passes;
    run.pairs_tested = pairs_tested;
    run.hits = hits;
    run.stalled = status.stalled;
    let [beats_read, beats_written] = line("# memory ")?[..] else {
        bail!("the testbench's memory line is not 2 numbers");
    };
    run.beats_read = beats_read;
    run.beats_written = beats_written;
    run.error = status.error;
    run.overflow = overflow != 0;
    run.faults = status.faults;
    case.to_originals(&mut run)?;
    Ok(run)
}

/// The top's clock-exact model ([`run_dram_broad_phase`]) on `case`: the
/// clocks of `binned` and `tested`, the leaves and the memory's beats, as
/// the runs above record them.
pub fn run_top_model(case: &TopCase, limit: u64) -> anyhow::Result<TopRun> {
    let binning = &case.binning;
    let mut memory = AxiMemory::new(binning.params, binning.bytes.clone());
    let times = run_dram_broad_phase(
        binning.config,
        case.config.system,
        &mut memory,
        binning.root,
        binning.root_lists,
        case.index_count,
        limit,
    )
    .map_err(anyhow::Error::msg)?;
    Ok(TopRun {
        binned_at: times.binned_at,
        tested_at: times.tested_at,
        leaves: times.leaves,
        passes: times.walk.passes,
        stalled: memory.stalled,
        beats_read: memory.beats_read,
        beats_written: memory.beats_written,
        ..TopRun::default()
    })
}
