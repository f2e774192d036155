//! The broad-phase accelerator with its scene in DRAM, in rust-hdl against
//! the memory model: the controller's passes and the leaf reader share one
//! AXI4 port, and the pairs it streams are the exact answer on the grid,
//! each once.

use tritri_cosim::dram_broad_phase::{
    exact_on_grid, run_top_model, run_top_rusthdl, run_top_simulator, top_case, uncertain_in_leaves,
};
use tritri_cosim::scene_query::Accelerator;
use tritri_cosim::simulator::Simulator;
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::PreparedScene;
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::broad_phase::list_pass_machine::ListPassConfig;

fn pass() -> ListPassConfig {
    ListPassConfig {
        grid_bits: 24,
        data_bits: 64,
        max_read_burst: 16,
        outstanding: 4,
    }
}

/// The torus and sphere of the controller's tests.
fn torus_and_sphere_objects() -> (SceneObject, SceneObject) {
    let a = SceneObject::from_triangles("torus", torus([0.0, 0.0, 0.0], 1.0, 0.35, 48, 24));
    let b = SceneObject::from_triangles("sphere", sphere([1.0, 0.0, 0.55], 0.4, 32, 16));
    (a, b)
}

/// Them on a 24-bit grid, one pipeline, the system's depth cut to 16 so
/// that leaves come as several tiles.
fn torus_and_sphere() -> (Accelerator, PreparedScene) {
    let (a, b) = torus_and_sphere_objects();
    let mut accelerator = Accelerator::new(24);
    accelerator.depth = 16;
    accelerator.pipelines = 1;
    let prepared = accelerator.prepare(&a, &b).unwrap();
    (accelerator, prepared)
}

/// The scene above with an ideal memory and one that stalls.
#[test]
fn the_rust_hdl_top_streams_the_exact_pairs_once() {
    let (accelerator, prepared) = torus_and_sphere();
    let pairs = exact_on_grid(&prepared);
    assert!(pairs.len() > 20, "{} pairs", pairs.len());
    let ideal = MemoryParams::ideal(8, 24);
    for params in [ideal, ideal.with_stalls(20, 7)] {
        let (case, _) = top_case(&accelerator, &prepared, pass(), params, 1 << 24).unwrap();
        let uncertain = uncertain_in_leaves(&case).unwrap();
        let run = run_top_rusthdl(&case, 5_000_000).unwrap();
        run.is_exact(&pairs, &uncertain)
            .unwrap_or_else(|e| panic!("{e}: {run:?}"));
        assert!(run.binned_at <= run.tested_at && run.tested_at <= run.cycles);
        // The clock-exact model to the last verdict.
        let model = run_top_model(&case, 5_000_000).unwrap();
        assert_eq!(
            (
                model.binned_at,
                model.tested_at,
                model.leaves,
                model.passes,
                model.stalled,
                model.beats_read,
                model.beats_written
            ),
            (
                run.binned_at,
                run.tested_at,
                run.leaves,
                run.passes,
                run.stalled,
                run.beats_read,
                run.beats_written
            ),
            "the model against rust-hdl (binned, tested, leaves, passes, stalled, beats read and written)"
        );
        eprintln!(
            "stalls {}%: {} pairs ({} uncertain), {} leaves, {} passes, binned at {}, tested at {}, done at {} ({} stalled)",
            params.stall_percent,
            run.pairs.len(),
            run.uncertain.len(),
            run.leaves,
            run.passes,
            run.binned_at,
            run.tested_at,
            run.cycles,
            run.stalled
        );
    }
}

/// The emitted top in Verilator against `axi_memory.sv`, on the same
/// scene: the rust-hdl run's pairs in the same order, and its clocks.
#[test]
fn the_verilated_top_is_the_rust_hdl_top_clock_for_clock() {
    let (accelerator, prepared) = torus_and_sphere();
    let ideal = MemoryParams::ideal(8, 24);
    for params in [ideal, ideal.with_stalls(20, 7)] {
        let (case, _) = top_case(&accelerator, &prepared, pass(), params, 1 << 24).unwrap();
        let rusthdl = run_top_rusthdl(&case, 5_000_000).unwrap();
        let verilated = run_top_simulator(Simulator::Verilator, &case, 5_000_000).unwrap();
        assert_eq!(verilated, rusthdl, "stalls {}%", params.stall_percent);
        eprintln!(
            "stalls {}%: Verilator = rust-hdl: {} pairs, binned at {}, tested at {}, done at {}",
            params.stall_percent,
            rusthdl.pairs.len(),
            rusthdl.binned_at,
            rusthdl.tested_at,
            rusthdl.cycles
        );
    }
}

/// The tops for the ECP5-85 (16-bit grid, one pipeline, the rare cases
/// shared) on their 256- and 128-bit ports (the 128-bit lane shares its
/// setup's products over an entry's two beats), emitted and run in
/// Verilator: the exact pairs once, the model's walk and clocks, and the
/// passes' speed-up over the 64-bit port that the wider port is for.
#[test]
fn the_256_and_128_bit_tops_stream_the_exact_pairs_at_the_models_clocks() {
    let (a, b) = torus_and_sphere_objects();
    let mut accelerator = Accelerator::new(16);
    accelerator.pipelines = 1;
    accelerator.rare_cases = tritri_rtl::pipeline::RareCasePath::Shared;
    let prepared = accelerator.prepare(&a, &b).unwrap();
    let pairs = exact_on_grid(&prepared);
    let port = |data_bits| ListPassConfig {
        grid_bits: 16,
        data_bits,
        ..pass()
    };
    // The 64-bit port's passes on a memory with a beat each way a clock.
    let (narrow, _) = top_case(
        &accelerator,
        &prepared,
        port(64),
        MemoryParams::ideal(8, 24),
        1 << 24,
    )
    .unwrap();
    let narrow = run_top_model(&narrow, 5_000_000).unwrap();
    // (port bits, the most of the 64-bit port's binning clocks it may take)
    for (data_bits, at_most) in [(256, 0.6), (128, 0.75)] {
        let ideal = MemoryParams::ideal(data_bits as u64 / 8, 24);
        for params in [ideal, ideal.with_stalls(20, 7)] {
            let (case, _) =
                top_case(&accelerator, &prepared, port(data_bits), params, 1 << 24).unwrap();
            let uncertain = uncertain_in_leaves(&case).unwrap();
            let run = run_top_simulator(Simulator::Verilator, &case, 5_000_000).unwrap();
            run.is_exact(&pairs, &uncertain)
                .unwrap_or_else(|e| panic!("{e}: {run:?}"));
            // The model has no shared rare-case unit: its walk is the top's,
            // its last verdict no later.
            let model = run_top_model(&case, 5_000_000).unwrap();
            assert_eq!(
            (
                model.binned_at,
                model.leaves,
                model.passes,
                model.stalled,
                model.beats_read,
                model.beats_written
            ),
            (
                run.binned_at,
                run.leaves,
                run.passes,
                run.stalled,
                run.beats_read,
                run.beats_written
            ),
            "the model against Verilator (binned, leaves, passes, stalled, beats read and written)"
        );
            assert!(model.tested_at <= run.tested_at);
            eprintln!(
            "{data_bits}-bit port, stalls {}%: {} pairs ({} uncertain), {} leaves, {} passes, binned at {} (64-bit port: {}), tested at {} (model {}), done at {}",
            params.stall_percent,
            run.pairs.len(),
            run.uncertain.len(),
            run.leaves,
            run.passes,
            run.binned_at,
            narrow.binned_at,
            run.tested_at,
            model.tested_at,
            run.cycles
        );
            if params.stall_percent == 0 {
                assert!(
                    (run.binned_at as f64) < at_most * narrow.binned_at as f64,
                    "binned at {} on the {data_bits}-bit port, {} on the 64-bit one",
                    run.binned_at,
                    narrow.binned_at
                );
            }
        }
    }
}
