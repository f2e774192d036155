//! Drives the broad-phase top ([`tritri_rtl::broad_phase::broad_phase_system`]):
//! a scene's arrays in, on the grid the binning unit was built for, each
//! leaf's pairs out, with the clocks from the first triangle in to `done`.

use crate::binning_unit::{
    grid_value, input_ports, input_testbench, input_vectors, triangle_stream, vertices_word,
    INPUT_REGISTERS,
};
use crate::simulator::{compile, run_on_vectors, vector_testbench, Simulator, Testbench};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::certificate::certified_intersects;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::cell::Cell;
use tritri_geom::widths::{cross_bits, difference_bits, orient3d_bits};
use tritri_rtl::broad_phase::binning_machine::BinningRun;
use tritri_rtl::broad_phase::binning_unit::on_unit_stack;
use tritri_rtl::broad_phase::broad_phase_system::BroadPhaseSystem;
use tritri_rtl::broad_phase::owner_chain_filter::{decide, hit_clocks, streamed, Streamed};
use tritri_rtl::emit::broad_phase_system_unit::{emit_broad_phase_system, BroadPhaseConfig};
use tritri_rtl::octree::cell_classifier::AXES;
use tritri_rtl::octree::value_bits;
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

/// What a run of the top gives.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct BroadPhaseOutput {
    /// The intersecting pairs (`out_hit`), each once, in the order the top
    /// streams them: indices into A's and B's arrays.
    pub pairs: Vec<(u32, u32)>,
    /// The pairs without a certificate (`out_certain = 0`), each once.
    pub uncertain: Vec<(u32, u32)>,
    /// Clocks from the first triangle taken (clock 0) to `binned`.
    pub binned_at: u64,
    /// Clocks from the first triangle taken to `done`.
    pub cycles: u64,
    pub pairs_tested: u64,
    /// The system's hits, each once per leaf holding both triangles.
    pub hits: u64,
    pub overflow: bool,
}

/// What the top's models say of a run: the pairs the owner filter owns
/// (sorted; each intersecting pair once, each uncertain pair once), the
/// system's hits, and the filter's clocks for the reported pairs back to
/// back (2 per pair, 1 per step back through an earlier leaf, 1 per pair
/// out).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TopModel {
    pub pairs: Vec<(u32, u32)>,
    pub uncertain: Vec<(u32, u32)>,
    pub hits: usize,
    pub filter_clocks: u64,
}

/// [`TopModel`] of the binning model's `run` on the arrays `a` and `b`
/// for a system of memory depth `depth`: the entries as the top streams
/// them (tiles of at most `depth`), the reported pairs (hits and pairs
/// without a certificate) as slots, the owner filter's decisions
/// ([`decide`]).
pub fn top_model(
    run: &BinningRun,
    depth: usize,
    a: &[FixedTriangle],
    b: &[FixedTriangle],
) -> TopModel {
    let verdict = |i: u32, j: u32| certified_intersects(&a[i as usize], &b[j as usize]);
    // The system's hit counter counts every tested pair that hits, in
    // every leaf: counted in the same pass that finds the reported pairs.
    let hits = std::cell::Cell::new(0usize);
    let Streamed {
        entries,
        hits: reported,
        ..
    } = streamed(&run.leaf_lists, depth, |i, j| {
        let v = verdict(i, j);
        hits.set(hits.get() + v.hit as usize);
        v.hit || !v.certain
    });
    let hits = hits.get();
    let decisions = decide(&entries, &reported);
    let filter_clocks = decisions
        .iter()
        .map(|(owned, steps)| hit_clocks(owned.is_some(), *steps))
        .sum();
    let owned: Vec<(u32, u32)> = decisions
        .into_iter()
        .filter_map(|(owned, _)| owned)
        .collect();
    let mut pairs: Vec<(u32, u32)> = owned
        .iter()
        .copied()
        .filter(|&(i, j)| verdict(i, j).hit)
        .collect();
    let mut uncertain: Vec<(u32, u32)> = owned
        .iter()
        .copied()
        .filter(|&(i, j)| !verdict(i, j).certain)
        .collect();
    pairs.sort_unstable();
    uncertain.sort_unstable();
    TopModel {
        pairs,
        uncertain,
        hits,
        filter_clocks,
    }
}

/// The scene through the rust-hdl model of the top built for `config`,
/// the reader always ready.
pub fn run_rusthdl(
    config: &BroadPhaseConfig,
    a: &[FixedTriangle],
    b: &[FixedTriangle],
    root: Cell,
    max_leaf_level: Option<u32>,
) -> anyhow::Result<BroadPhaseOutput> {
    fn run<
        const G: usize,
        const V: usize,
        const N: usize,
        const T: usize,
        const W: usize,
        const D: usize,
        const C: usize,
        const O: usize,
    >(
        config: &BroadPhaseConfig,
        a: &[FixedTriangle],
        b: &[FixedTriangle],
        root: Cell,
        max_leaf_level: Option<u32>,
    ) -> anyhow::Result<BroadPhaseOutput> {
        let unit = &config.unit;
        let mut uut = BroadPhaseSystem::<G, V, N, T, W, D, C, O>::new(
            unit.triangles,
            unit.list_words,
            unit.leaves,
            config.slots,
            config.system,
            config.local_frames,
        );
        uut.connect_all();
        reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
        let g = grid_value::<G>;
        uut.root_x.next = g(root.lo[0]);
        uut.root_y.next = g(root.lo[1]);
        uut.root_z.next = g(root.lo[2]);
        uut.root_level.next = (root.level as u64).into();
        uut.max_leaf_enable.next = max_leaf_level.is_some();
        uut.max_leaf_level.next = (max_leaf_level.unwrap_or(0) as u64).into();
        uut.out_ready.next = true;
        uut.start.next = true;
        clock_cycle(&mut uut, |u| &mut u.clock);
        uut.start.next = false;
        let stream = triangle_stream(a, b);
        let mut out = BroadPhaseOutput::default();
        let mut binned_at = None;
        let mut next = 0;
        let mut clock = 0u64;
        let limit = 50_000_000u64;
        loop {
            uut.in_valid.next = next < stream.len();
            if let Some(&(object, t)) = stream.get(next) {
                uut.in_object.next = object;
                uut.in_last.next = next + 1 == stream.len();
                uut.in_vertices.next = vertices_word::<G, T>(t);
            }
            settle(&mut uut);
            if uut.binned.val() && binned_at.is_none() {
                binned_at = Some(clock);
            }
            if uut.out_valid.val() {
                let pair = (
                    uut.out_index_a.val().index() as u32,
                    uut.out_index_b.val().index() as u32,
                );
                out.record(pair, uut.out_hit.val(), uut.out_certain.val());
            }
            if uut.done.val() && next == stream.len() && binned_at.is_some() {
                break;
            }
            let taken = uut.in_valid.val() && uut.in_ready.val();
            clock_cycle(&mut uut, |u| &mut u.clock);
            if taken {
                next += 1;
            }
            clock += 1;
            if clock > limit {
                bail!("the broad-phase top did not finish in {limit} clocks");
            }
        }
        out.cycles = clock;
        out.binned_at = binned_at.unwrap_or(clock);
        out.overflow = uut.overflow.val();
        out.pairs_tested = uut.pairs_tested.val().index() as u64;
        out.hits = uut.hits.val().index() as u64;
        // `done` waits for the last pair to be taken: nothing may follow.
        for _ in 0..8 {
            clock_cycle(&mut uut, |u| &mut u.clock);
            settle(&mut uut);
            if uut.out_valid.val() {
                bail!("a pair after done, at clock {clock}");
            }
        }
        Ok(out)
    }
    if let Err(why) = config.check() {
        bail!("{why}");
    }
    const V24: usize = value_bits(24);
    on_unit_stack(|| match config.system.coordinate_bits {
        24 => run::<
            24,
            V24,
            { AXES * V24 },
            { 9 * 24 },
            24,
            { difference_bits(24) },
            { cross_bits(24) },
            { orient3d_bits(24) },
        >(config, a, b, root, max_leaf_level),
        _ => run::<
            24,
            V24,
            { AXES * V24 },
            { 9 * 24 },
            16,
            { difference_bits(16) },
            { cross_bits(16) },
            { orient3d_bits(16) },
        >(config, a, b, root, max_leaf_level),
    })
}

/// The scene through the emitted top built for `config` in `simulator`
/// (the reader always ready). `clock_bound` bounds the clocks the run may
/// take after its last triangle.
pub fn run_emitted(
    config: &BroadPhaseConfig,
    a: &[FixedTriangle],
    b: &[FixedTriangle],
    root: Cell,
    max_leaf_level: Option<u32>,
    clock_bound: u64,
    simulator: Simulator,
) -> anyhow::Result<BroadPhaseOutput> {
    let design = emit_broad_phase_system(config)?;
    let g = config.unit.grid_bits;
    let mut files = vec![(
        "tb_broad_phase.sv".to_string(),
        testbench(&design.top, g, clock_bound as usize),
    )];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_broad_phase".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 1,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let vectors = input_vectors(g, a, b, root, max_leaf_level);
    let (text, _) = run_on_vectors(&compiled, "broad-phase-run", &vectors, &[])?;
    parse_outputs(&text)
}

impl BroadPhaseOutput {
    /// One pair of the top's output stream.
    fn record(&mut self, pair: (u32, u32), hit: bool, certain: bool) {
        if hit {
            self.pairs.push(pair);
        }
        if !certain {
            self.uncertain.push(pair);
        }
    }
}

/// The testbench's lines: `P edge a b hit certain` a pair, `D edge` the first edge
/// with `binned`, `F edge overflow pairs_tested hits` the first with
/// `done`. The first triangle is
/// offered at edge 1, the top's clock 0.
fn parse_outputs(text: &str) -> anyhow::Result<BroadPhaseOutput> {
    let mut out = BroadPhaseOutput::default();
    let mut finished = false;
    for line in text.lines() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        let number = |k: usize, radix| -> anyhow::Result<u64> {
            let s = fields
                .get(k)
                .with_context(|| format!("broad-phase output line `{line}` has no field {k}"))?;
            u64::from_str_radix(s, radix).with_context(|| format!("`{s}` in `{line}`"))
        };
        match fields.first().copied() {
            Some("P") => out.record(
                (number(2, 16)? as u32, number(3, 16)? as u32),
                number(4, 2)? == 1,
                number(5, 2)? == 1,
            ),
            Some("D") => out.binned_at = number(1, 10)?.saturating_sub(1),
            Some("F") => {
                out.cycles = number(1, 10)?.saturating_sub(1);
                out.overflow = number(2, 16)? == 1;
                out.pairs_tested = number(3, 16)?;
                out.hits = number(4, 16)?;
                finished = true;
            }
            _ => bail!("broad-phase output line `{line}` is not P, D or F"),
        }
    }
    if !finished {
        bail!("the broad-phase top did not say done (the run hit its clock bound)");
    }
    Ok(out)
}

/// The testbench: the start line for one clock, each triangle held until
/// taken, the reader always ready; every pair written with its edge; at
/// `done` the result FIFO is drained and the run ends (or `drain` clocks
/// after the last triangle).
fn testbench(top: &str, g: usize, drain: usize) -> String {
    let body = format!(
        "\
{registers}
    reg [63:0] edge_count = 64'd0;
    reg binned_seen = 1'b0;
    reg done_seen = 1'b0;
    wire in_ready, out_valid, out_hit, out_certain, binned, done, overflow;
    wire [31:0] out_index_a, out_index_b, pairs_tested, hits;
    {top} dut (
        .clock(clock), .reset(reset),
{ports}
        .out_valid(out_valid), .out_ready(1'b1), .out_index_a(out_index_a), .out_index_b(out_index_b),
        .out_hit(out_hit), .out_certain(out_certain),
        .binned(binned), .done(done), .overflow(overflow), .pairs_tested(pairs_tested), .hits(hits)
    );

    always @(posedge clock) if (!reset) edge_count <= edge_count + 64'd1;

    // Outputs are registered, stable at the falling edge; a word shown
    // there leaves at the next rising edge, number edge_count.
    always @(negedge clock) begin
        if (!reset && binned && !binned_seen) begin
            $fwrite(outputs, \"D %0d\\n\", edge_count);
            binned_seen = 1'b1;
        end
        if (!reset && out_valid) $fwrite(outputs, \"P %0d %h %h %0d %0d\\n\", edge_count, out_index_a, out_index_b, out_hit, out_certain);
        if (!reset && done && binned_seen && !done_seen) begin
            $fwrite(outputs, \"F %0d %h %h %h\\n\", edge_count, overflow, pairs_tested, hits);
            done_seen = 1'b1;
        end
        if (done_seen && !out_valid) begin
            $fclose(outputs);
            $finish;
        end
    end
",
        registers = INPUT_REGISTERS,
        ports = input_ports(g),
    );
    vector_testbench(&input_testbench("tb_broad_phase", body, drain))
}

/// A prepared octree scene through the broad-phase top: what it reported,
/// in the objects' triangle ids, beside what its models say.
#[derive(Clone, Debug)]
pub struct TopSceneRun {
    /// The top's intersecting pairs and pairs without a certificate.
    pub pairs: tritri_geom::scene::reference::PairSet,
    pub uncertain: tritri_geom::scene::reference::PairSet,
    /// What the top's counters and flags said.
    pub output: BroadPhaseOutput,
    /// The owner filter's pairs by the model (sorted, array indices).
    pub model: TopModel,
    /// The binning unit and system's cycle model: `done` comes at least
    /// this many clocks after the first triangle, and at most
    /// `model.filter_clocks` more.
    pub model_cycles: u64,
    /// The top's build parameters.
    pub config: BroadPhaseConfig,
}

impl TopSceneRun {
    /// What says the top is wrong: its pairs against its model's, `done`
    /// outside the models' window, the overflow flag (each a bug).
    pub fn faults(&self) -> Vec<crate::fault::Fault> {
        use crate::fault::Fault;
        let mut faults = Vec::new();
        let mut got = self.output.pairs.clone();
        got.sort_unstable();
        if got != self.model.pairs {
            faults.push(Fault::TopPairs {
                top: got.len(),
                model: self.model.pairs.len(),
            });
        }
        let (low, high) = (
            self.model_cycles,
            self.model_cycles + self.model.filter_clocks,
        );
        if !(low..=high).contains(&self.output.cycles) {
            faults.push(Fault::Cycles {
                simulated: self.output.cycles,
                low,
                high,
            });
        }
        if self.output.overflow {
            faults.push(Fault::Overflow {
                what: "a memory of the broad-phase top was too small (its sizing)",
            });
        }
        faults
    }
}

/// Runs `scene` (prepared with the octree broad phase on a grid the binning
/// unit is built for, and `binning` its run of the binning unit,
/// `crate::binning_unit::bin_scene`) through the broad-phase top sized for
/// it, in rust-hdl (`simulator` `None`) or in the emitted Verilog; `system`
/// is the collision system it feeds, `max_leaf_level` the local frames'
/// bound.
pub fn run_scene_on_top(
    scene: &tritri_geom::scene::PreparedScene,
    binning: &crate::binning_unit::SceneBinning,
    system: tritri_rtl::system::SystemConfig,
    max_leaf_level: Option<u32>,
    simulator: Option<Simulator>,
) -> anyhow::Result<TopSceneRun> {
    let root = scene
        .octree
        .as_ref()
        .and_then(|o| o.root)
        .context("the scene has no octree root")?;
    let a: Vec<FixedTriangle> = scene.kept_a.iter().map(|t| t.triangle).collect();
    let b: Vec<FixedTriangle> = scene.kept_b.iter().map(|t| t.triangle).collect();
    let slots = tritri_rtl::broad_phase::broad_phase_system::stream_slots(
        system.triangles_per_bank,
        &binning.run,
    )
    .into_iter()
    .max()
    .unwrap_or(1)
    .max(1);
    let config = BroadPhaseConfig {
        unit: binning.config,
        system,
        slots,
        local_frames: max_leaf_level.is_some(),
    };
    config.check().map_err(|why| {
        anyhow::anyhow!("the broad-phase top cannot be built for this scene: {why}")
    })?;
    let model_cycles =
        tritri_rtl::broad_phase::broad_phase_system::broad_phase_cycles(system, &binning.run);
    let model = top_model(&binning.run, system.triangles_per_bank, &a, &b);
    let output = match simulator {
        None => run_rusthdl(&config, &a, &b, root, max_leaf_level)?,
        Some(simulator) => run_emitted(
            &config,
            &a,
            &b,
            root,
            max_leaf_level,
            model_cycles + model.filter_clocks + 1_000,
            simulator,
        )?,
    };
    let ids = |&(i, j): &(u32, u32)| (scene.kept_a[i as usize].id, scene.kept_b[j as usize].id);
    Ok(TopSceneRun {
        pairs: output.pairs.iter().map(ids).collect(),
        uncertain: output.uncertain.iter().map(ids).collect(),
        output,
        model,
        model_cycles,
        config,
    })
}
