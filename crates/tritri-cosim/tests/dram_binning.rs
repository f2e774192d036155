//! The broad phase's binning with every list in external memory, in the
//! controller's clock-exact model over the list pass unit's: the leaves are
//! the streaming planner's, they go out while the walk goes on, a memory
//! that stalls changes the clocks and nothing else, and an arena too small
//! for the tree loses no pair.

use std::collections::HashSet;
use tritri_cosim::dram_binning::{bin_in_dram, dram_case, run_model, run_rusthdl, run_simulator};
use tritri_cosim::scene_query::Accelerator;
use tritri_cosim::simulator::Simulator;
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::PreparedScene;
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::broad_phase::list_entry::unpack;
use tritri_rtl::broad_phase::list_pass_machine::ListPassConfig;

fn scene() -> (Accelerator, PreparedScene) {
    let a = SceneObject::from_triangles("torus", torus([0.0, 0.0, 0.0], 1.0, 0.35, 48, 24));
    let b = SceneObject::from_triangles("sphere", sphere([1.0, 0.0, 0.55], 0.4, 32, 16));
    let mut accelerator = Accelerator::new(24);
    accelerator.depth = 32;
    let prepared = accelerator.prepare(&a, &b).unwrap();
    (accelerator, prepared)
}

fn pass(data_bits: usize) -> ListPassConfig {
    ListPassConfig {
        grid_bits: 24,
        data_bits,
        max_read_burst: 16,
        outstanding: 4,
    }
}

/// Every (A, B) pair of triangle indices that some leaf holds.
fn pairs(leaves: impl Iterator<Item = [Vec<u32>; 2]>) -> HashSet<(u32, u32)> {
    let mut out = HashSet::new();
    for [a, b] in leaves {
        for &i in &a {
            out.extend(b.iter().map(|&j| (i, j)));
        }
    }
    out
}

#[test]
fn the_leaves_are_the_streaming_planners_and_go_out_as_decided() {
    let (accelerator, prepared) = scene();
    for data_bits in [64, 256] {
        let params = MemoryParams::ideal(data_bits as u64 / 8, 24);
        let got = bin_in_dram(&accelerator, &prepared, pass(data_bits), params, 1 << 24).unwrap();
        let run = &got.run;
        assert_eq!(run.arena_full, 0);
        assert!(
            got.schedule.tree_depth >= 2,
            "depth {}",
            got.schedule.tree_depth
        );
        assert!(run.leaves.len() > 8, "{} leaves", run.leaves.len());
        assert!(run.passes >= got.schedule.tree_depth as u64);
        // A streaming binner classifies only the cells it splits or tries.
        assert_eq!(run.passes, got.schedule.cells_visited);
        // Leaves go out one after another while the walk goes on.
        assert!(run.leaves.windows(2).all(|w| w[0].clock < w[1].clock));
        let first = &run.leaves[0];
        assert!(
            first.after_passes < run.passes / 2,
            "the first leaf after {} of {} passes",
            first.after_passes,
            run.passes
        );
        let beat = data_bits as u64 / 8;
        let (read, written) = (run.bytes_read / beat, run.bytes_written / beat);
        // Reads and writes go on their own channels: at least the larger,
        // at most both and a pass's latencies.
        assert!(run.pass_cycles >= read.max(written), "{run:?}");
        assert!(run.cycles <= read + written + 300 * run.passes, "{run:?}");
        assert!(run.peak_arena > 0 && run.peak_arena <= 1 << 24);
        eprintln!(
            "{data_bits}-bit port: {} passes, {} leaves (first out at clock {}), {} clocks ({} in passes); \
             {} KiB read, {} KiB written, arena peak {} KiB, {} frames",
            run.passes,
            run.leaves.len(),
            run.leaves[0].clock,
            run.cycles,
            run.pass_cycles,
            run.bytes_read / 1024,
            run.bytes_written / 1024,
            run.peak_arena / 1024,
            run.peak_frames
        );
    }
}

#[test]
fn a_memory_that_stalls_changes_the_clocks_only() {
    let (accelerator, prepared) = scene();
    let ideal = MemoryParams::ideal(8, 24);
    let calm = bin_in_dram(&accelerator, &prepared, pass(64), ideal, 1 << 24).unwrap();
    let stalls = bin_in_dram(
        &accelerator,
        &prepared,
        pass(64),
        ideal.with_stalls(20, 7),
        1 << 24,
    )
    .unwrap();
    let places = |run: &tritri_rtl::broad_phase::dram_binning_machine::DramBinningRun| {
        run.leaves
            .iter()
            .map(|l| (l.cell, l.lists, l.entries.clone()))
            .collect::<Vec<_>>()
    };
    assert_eq!(places(&calm.run), places(&stalls.run));
    assert!(stalls.run.stalled > 0 && calm.run.stalled == 0);
    assert!(stalls.run.cycles > calm.run.cycles);
    // A stalled clock delays the port by at most that clock.
    assert!(stalls.run.cycles <= calm.run.cycles + stalls.run.stalled);
}

#[test]
fn an_arena_too_small_for_the_tree_raises_its_flag_and_loses_no_pair() {
    let (accelerator, prepared) = scene();
    let params = MemoryParams::ideal(8, 24);
    let full = bin_in_dram(&accelerator, &prepared, pass(64), params, 1 << 24).unwrap();
    // Three quarters of the arena the tree needs: the root still splits, deeper cells
    // find it full.
    let arena = full.run.peak_arena * 3 / 4;
    let small = bin_in_dram(&accelerator, &prepared, pass(64), params, arena).unwrap();
    assert!(small.run.arena_full > 0, "{:?}", small.run.arena_full);
    assert!(
        small.run.passes > 1 && small.run.peak_arena <= arena,
        "{} passes, arena {} of {arena}, full {}",
        small.run.passes,
        small.run.peak_arena,
        full.run.peak_arena
    );
    let ids = |run: &tritri_rtl::broad_phase::dram_binning_machine::DramBinningRun| {
        pairs(run.leaves.iter().map(|l| {
            l.entries
                .clone()
                .map(|list| list.iter().map(|e| unpack(e, 24).0).collect())
        }))
    };
    let wanted = ids(&full.run);
    let kept = ids(&small.run);
    assert!(
        wanted.is_subset(&kept),
        "{} pairs lost",
        wanted.difference(&kept).count()
    );
}

/// The controller in rust-hdl, over the list pass unit and against the
/// memory model, equals its clock-exact model: every leaf (cell, lists'
/// places, clock, and the entries in the memory when it goes out), the
/// clocks to `done`, the stalled clocks, the passes and every byte of the
/// memory, with an ideal memory and with one that stalls. With one
/// pipeline the split rule tries splits that do not pay and drops some of
/// them: leaves wait on chip and are dropped.
#[test]
fn the_rust_hdl_controller_is_its_model() {
    let (mut accelerator, prepared) = scene();
    let ideal = MemoryParams::ideal(8, 24);
    for (pipelines, params) in [(2, ideal), (2, ideal.with_stalls(20, 7)), (1, ideal)] {
        accelerator.pipelines = pipelines;
        let (case, _) = dram_case(&accelerator, &prepared, pass(64), params, 1 << 24).unwrap();
        let (model, bytes) = run_model(&case).unwrap();
        let unit = run_rusthdl(&case, 2 * model.cycles + 100).unwrap();
        unit.check_against(&model, &bytes).unwrap();
        assert!(model.passes > 4 && model.leaves.len() > 8, "{model:?}");
        // Leaves sent from the waiting memory go out a clock apart.
        let together = model
            .leaves
            .windows(2)
            .filter(|w| w[1].clock == w[0].clock + 1)
            .count();
        if pipelines == 1 {
            assert!(model.leaves_dropped > 0, "no split dropped");
        }
        eprintln!(
            "P = {pipelines}: rust-hdl = model: {} passes, {} leaves, {} clocks, {} stalled; \
             {} leaves dropped, {} waiting at most, {} sent a clock after the last, {} frames",
            model.passes,
            model.leaves.len(),
            model.cycles,
            model.stalled,
            model.leaves_dropped,
            model.peak_waiting,
            together,
            model.peak_frames
        );
    }
}

/// The emitted controller in Verilator (and, with the ideal memory, in
/// Icarus), against `axi_memory.sv`, equals
/// the model in every leaf's cell, places and clock, the clocks to `done`,
/// the stalled clocks, the passes and every byte of the memory at the end,
/// with an ideal memory and with one that stalls.
#[test]
fn the_emitted_controller_in_verilator_and_icarus_is_its_model() {
    let (mut accelerator, prepared) = scene();
    accelerator.pipelines = 1;
    let ideal = MemoryParams::ideal(8, 24);
    for params in [ideal, ideal.with_stalls(20, 7)] {
        let (case, _) = dram_case(&accelerator, &prepared, pass(64), params, 1 << 24).unwrap();
        let (model, bytes) = run_model(&case).unwrap();
        let unit = run_simulator(Simulator::Verilator, &case, 2 * model.cycles + 100).unwrap();
        unit.check_against(&model, &bytes).unwrap();
        assert!(model.leaves_dropped > 0);
        if params.stall_percent == 0 {
            let icarus = run_simulator(Simulator::Icarus, &case, 2 * model.cycles + 100).unwrap();
            icarus.check_against(&model, &bytes).unwrap();
        }
    }
}

/// A waiting memory too small for a tried split's leaves loses nothing:
/// the leaf that finds it full keeps every tried split on the stack, the
/// waiting leaves go out, then it; the leaves still hold every
/// intersecting pair the roomy memory's leaves hold, and rust-hdl and
/// Verilator do the same as the model, clock for clock.
#[test]
fn a_full_waiting_memory_keeps_the_tried_splits_and_loses_no_pair() {
    let (mut accelerator, prepared) = scene();
    accelerator.pipelines = 1;
    let ideal = MemoryParams::ideal(8, 24);
    let (roomy, _) = dram_case(&accelerator, &prepared, pass(64), ideal, 1 << 24).unwrap();
    let (full, _) = run_model(&roomy).unwrap();
    assert!(
        full.peak_waiting >= 2 && full.waiting_commits == 0,
        "{} waiting at most",
        full.peak_waiting
    );
    let mut small = roomy.clone();
    small.config.waiting_capacity = 1;
    let (model, bytes) = run_model(&small).unwrap();
    assert!(model.waiting_commits > 0 && model.peak_waiting <= 1);
    let held = |run: &tritri_rtl::broad_phase::dram_binning_machine::DramBinningRun| {
        pairs(run.leaves.iter().map(|l| {
            l.entries
                .clone()
                .map(|list| list.iter().map(|e| unpack(e, 24).0).collect())
        }))
    };
    // The kept splits' leaves hold fewer pairs than the dropped splits'
    // cells did, but every pair that intersects.
    let triangles = |list: &[tritri_geom::scene::TaggedTriangle]| {
        list.iter()
            .map(|t| (t.id, t.triangle))
            .collect::<std::collections::HashMap<_, _>>()
    };
    let (ta, tb) = (triangles(&prepared.kept_a), triangles(&prepared.kept_b));
    let meeting: HashSet<(u32, u32)> = held(&full)
        .into_iter()
        .filter(|(a, b)| tritri_geom::fixed_point::intersects(&ta[a], &tb[b]))
        .collect();
    assert!(!meeting.is_empty());
    assert!(meeting.is_subset(&held(&model)));
    let unit = run_rusthdl(&small, 2 * model.cycles + 100).unwrap();
    unit.check_against(&model, &bytes).unwrap();
    let emitted = run_simulator(Simulator::Verilator, &small, 2 * model.cycles + 100).unwrap();
    emitted.check_against(&model, &bytes).unwrap();
}

/// A narrow phase that pushes back (a leaf refused one clock in three, a
/// pass held three clocks in seven) changes when leaves go out and passes
/// start, and nothing else: the same leaves with the same lists, and every
/// byte of the memory the same. rust-hdl and Verilator equal the model
/// clock for clock, leaves sent from the waiting memory and from a commit
/// included.
#[test]
fn a_narrow_phase_that_pushes_back_delays_the_walk_only() {
    let (mut accelerator, prepared) = scene();
    accelerator.pipelines = 1;
    let ideal = MemoryParams::ideal(8, 24);
    let (free, _) = dram_case(&accelerator, &prepared, pass(64), ideal, 1 << 24).unwrap();
    for waiting_capacity in [free.config.waiting_capacity, 1] {
        let mut taken = free.clone();
        taken.config.waiting_capacity = waiting_capacity;
        let mut held = taken.clone();
        held.pushback = true;
        let (at_once, at_once_bytes) = run_model(&taken).unwrap();
        let (model, bytes) = run_model(&held).unwrap();
        assert!(model.leaves_dropped > 0 || model.waiting_commits > 0);
        let places = |run: &tritri_rtl::broad_phase::dram_binning_machine::DramBinningRun| {
            run.leaves
                .iter()
                .map(|l| (l.cell, l.lists))
                .collect::<Vec<_>>()
        };
        assert_eq!(places(&model), places(&at_once));
        assert_eq!(bytes, at_once_bytes);
        assert!(model.cycles > at_once.cycles + model.passes);
        let unit = run_rusthdl(&held, 2 * model.cycles + 100).unwrap();
        unit.check_against(&model, &bytes).unwrap();
        if waiting_capacity == 1 {
            let emitted =
                run_simulator(Simulator::Verilator, &held, 2 * model.cycles + 100).unwrap();
            emitted.check_against(&model, &bytes).unwrap();
        }
        eprintln!(
            "waiting memory of {waiting_capacity}: pushed back, {} clocks where leaves taken at once take {}",
            model.cycles, at_once.cycles
        );
    }
}
