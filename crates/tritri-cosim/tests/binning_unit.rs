//! The binning unit bins in hardware what the broad phase's planner bins in
//! software: a scene's arrays streamed in once, the leaves streamed out,
//! equal to the cycle-exact model (whose leaves are the planner's) in
//! cells, triangles and order, and in clocks: in rust-hdl (with and
//! without back-pressure on the leaf stream), and as emitted Verilog in
//! Icarus and in Verilator.

use tritri_cosim::binning_unit::{
    expected_leaves, run_emitted, run_rusthdl, BinningOutput, StreamedLeaf,
};
use tritri_cosim::simulator::Simulator;
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::{prepare_octree, PreparedScene, SceneOptions};
use tritri_rtl::broad_phase::binning_machine::{run_binning, BinningParams, BinningRun};
use tritri_rtl::broad_phase::binning_unit::BinningUnitConfig;
use tritri_rtl::system::SystemConfig;

/// A torus and a sphere in contact, at memory depth `depth` (small: many
/// leaves, deep frames, dropped subtrees).
fn scene(depth: usize, torus_segments: usize, sphere_segments: usize) -> PreparedScene {
    let a = SceneObject::from_triangles(
        "torus",
        torus(
            [0.0, 0.0, 0.0],
            1.0,
            0.35,
            torus_segments,
            torus_segments / 2,
        ),
    );
    let b = SceneObject::from_triangles(
        "sphere",
        sphere([1.0, 0.0, 0.55], 0.4, sphere_segments, sphere_segments / 2),
    );
    let config = SystemConfig::new(24, 2).with_depth(depth);
    prepare_octree(
        &a,
        &b,
        &SceneOptions {
            grid_bits: 24,
            depth,
            split: true,
        },
        &config,
        None,
    )
    .unwrap()
}

fn arrays(scene: &PreparedScene) -> (Vec<FixedTriangle>, Vec<FixedTriangle>) {
    (
        scene.kept_a.iter().map(|t| t.triangle).collect(),
        scene.kept_b.iter().map(|t| t.triangle).collect(),
    )
}

/// The model's run on the scene, checked against the scene's schedule.
fn model(scene: &PreparedScene, params: BinningParams) -> BinningRun {
    let (a, b) = arrays(scene);
    let run = run_binning(&a, &b, scene.octree.as_ref().unwrap().root.unwrap(), params);
    // The model is the planner (tested in the hardware crate); here the
    // leaves must also be the scene's schedule.
    assert_eq!(
        run.leaves.len(),
        scene.octree.as_ref().unwrap().leaves.len()
    );
    run
}

/// The unit's output equals the model's run: leaves (reported by the first
/// that differs, not printed whole) and cycles.
fn assert_bins_as(out: &BinningOutput, run: &BinningRun, depth: usize) {
    let expected = expected_leaves(run, depth);
    let show = |l: Option<&StreamedLeaf>| {
        l.map_or("none".to_string(), |l| {
            format!("{:?} with {} + {} triangles", l.cell, l.a.len(), l.b.len())
        })
    };
    if let Some(k) =
        (0..out.leaves.len().max(expected.len())).find(|&k| out.leaves.get(k) != expected.get(k))
    {
        panic!(
            "{} leaves, expected {}; leaf {k} is {}, expected {}",
            out.leaves.len(),
            expected.len(),
            show(out.leaves.get(k)),
            show(expected.get(k))
        );
    }
    assert_eq!(out.cycles, run.cycles);
    assert!(
        !out.overflow,
        "overflow raised with memories sized for the run"
    );
}

const PARAMS: BinningParams = BinningParams {
    log_depth: 4,
    log_pipelines: 1,
    max_leaf_level: None,
};

#[test]
fn rust_hdl_bins_as_the_model_leaf_for_leaf_and_clock_for_clock() {
    let scene = scene(16, 48, 32);
    let run = model(&scene, PARAMS);
    assert!(
        run.leaves.len() > 20 && run.peak_frames > 3,
        "{} leaves, {} frames",
        run.leaves.len(),
        run.peak_frames
    );
    let (a, b) = arrays(&scene);
    let config = BinningUnitConfig::sized_for(24, PARAMS, a.len().max(b.len()), &run);
    let root = scene.octree.as_ref().unwrap().root.unwrap();
    let out = run_rusthdl(&config, &a, &b, root, None, &|_| true).unwrap();
    assert_bins_as(&out, &run, 16);
    // A reader that stalls: the same leaves (binning is over before the
    // first leaf leaves, so the same cycles too).
    let stalled =
        run_rusthdl(&config, &a, &b, root, None, &|clock| (clock * 7919) % 5 < 2).unwrap();
    assert_eq!(stalled, out);
    // One word, one leaf or one triangle too few: the unit says so.
    for small in [
        BinningUnitConfig {
            list_words: config.list_words - 1,
            ..config
        },
        BinningUnitConfig {
            leaves: config.leaves - 1,
            ..config
        },
        BinningUnitConfig {
            triangles: config.triangles - 1,
            ..config
        },
    ] {
        let overflowed = run_rusthdl(&small, &a, &b, root, None, &|_| true).unwrap();
        assert!(
            overflowed.overflow && overflowed.leaves.is_empty(),
            "{small:?}"
        );
    }
    eprintln!(
        "{} leaves, {} frames at most, {} cells passed, {} clocks; {} + {} triangles",
        run.leaves.len(),
        run.peak_frames,
        run.cells,
        run.cycles,
        a.len(),
        b.len()
    );
}

#[test]
fn the_emitted_unit_bins_as_the_model_in_icarus() {
    let scene = scene(16, 48, 32);
    let run = model(&scene, PARAMS);
    let (a, b) = arrays(&scene);
    let config = BinningUnitConfig::sized_for(24, PARAMS, a.len().max(b.len()), &run);
    let bound = run.cycles + 4 * (run.leaves.len() as u64 + run.entries) + 100;
    let out = run_emitted(
        &config,
        &a,
        &b,
        scene.octree.as_ref().unwrap().root.unwrap(),
        None,
        bound,
        Simulator::Icarus,
    )
    .unwrap();
    assert_bins_as(&out, &run, 16);
}

#[test]
fn the_emitted_unit_bins_a_large_scene_as_the_model_in_verilator() {
    // Two dense spheres overlapping deeply: over 5,000 triangles per object
    // in the common box, the system's default memory depth, and local
    // frames (cells above level 18 always split).
    let a = SceneObject::from_triangles("sphere a", sphere([0.0, 0.0, 0.0], 1.0, 112, 56));
    let b = SceneObject::from_triangles("sphere b", sphere([0.6, 0.2, 0.1], 0.9, 112, 56));
    let system = SystemConfig::new(24, 2).with_depth(256);
    let scene = prepare_octree(
        &a,
        &b,
        &SceneOptions {
            grid_bits: 24,
            depth: 256,
            split: true,
        },
        &system,
        None,
    )
    .unwrap();
    let params = BinningParams {
        log_depth: 8,
        log_pipelines: 1,
        max_leaf_level: Some(18),
    };
    let (a, b) = arrays(&scene);
    assert!(
        a.len() > 5000 && b.len() > 5000,
        "{} + {} triangles",
        a.len(),
        b.len()
    );
    let root = scene.octree.as_ref().unwrap().root.unwrap();
    let run = run_binning(&a, &b, root, params);
    let config = BinningUnitConfig::sized_for(24, params, a.len().max(b.len()), &run);
    let bound = run.cycles + 4 * (run.leaves.len() as u64 + run.entries) + 100;
    let out = run_emitted(
        &config,
        &a,
        &b,
        root,
        params.max_leaf_level,
        bound,
        Simulator::Verilator,
    )
    .unwrap();
    assert_bins_as(&out, &run, 256);
    eprintln!(
        "{} + {} triangles: {} leaves, {} cells passed, {} clocks",
        a.len(),
        b.len(),
        run.leaves.len(),
        run.cells,
        run.cycles
    );
}

#[test]
fn leaves_over_the_depth_stream_as_tiles_in_rust_hdl() {
    // At depth 4, triangles around a shared vertex stay together in every
    // cell, so some leaves hold more than 4 of an object: each goes out as
    // tiles (every A tile with every B tile), a reader stalling or not.
    let params = BinningParams {
        log_depth: 2,
        log_pipelines: 1,
        max_leaf_level: None,
    };
    let scene = scene(4, 48, 32);
    let run = model(&scene, params);
    let over = run
        .leaves
        .iter()
        .filter(|l| l.a.count > 4 || l.b.count > 4)
        .count();
    assert!(over > 5, "{over} leaves over the depth");
    let (a, b) = arrays(&scene);
    let config = BinningUnitConfig::sized_for(24, params, a.len().max(b.len()), &run);
    let root = scene.octree.as_ref().unwrap().root.unwrap();
    let out = run_rusthdl(&config, &a, &b, root, None, &|_| true).unwrap();
    assert_bins_as(&out, &run, 4);
    let stalled = run_rusthdl(&config, &a, &b, root, None, &|clock| {
        (clock * 7919) % 3 == 0
    })
    .unwrap();
    assert_eq!(stalled, out);
    eprintln!(
        "{} leaves, {over} over the depth, {} tiles streamed",
        run.leaves.len(),
        out.leaves.len()
    );
}
