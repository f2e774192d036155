//! The binning unit bins in hardware what the broad phase's planner bins in
//! software: a scene's arrays streamed in once, the leaves streamed out,
//! equal to the cycle-exact model (whose leaves are the planner's) in
//! cells, triangles and order, and in clocks.

use tritri_cosim::binning_unit::{run_rusthdl, StreamedLeaf, UnitSizes};
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::{prepare_octree, PreparedScene, SceneOptions};
use tritri_rtl::octree::binning_machine::{run_binning, BinningParams, BinningRun};
use tritri_rtl::pipeline::triangle_pipeline::latency;
use tritri_rtl::system::SystemConfig;

/// A torus and a sphere in contact, at memory depth `depth` (small: many
/// leaves, deep frames, dropped subtrees).
fn scene(depth: usize, torus_segments: usize) -> PreparedScene {
    let a = SceneObject::from_triangles("torus", torus([0.0, 0.0, 0.0], 1.0, 0.35, torus_segments, torus_segments / 2));
    let b = SceneObject::from_triangles("sphere", sphere([1.0, 0.0, 0.55], 0.4, 32, 16));
    let config = SystemConfig::new(24, 2, latency()).with_depth(depth);
    prepare_octree(&a, &b, &SceneOptions { width: 24, depth, split: true }, &config, None).unwrap()
}

fn model(scene: &PreparedScene, params: BinningParams) -> BinningRun {
    let a: Vec<_> = scene.kept_a.iter().map(|t| t.triangle).collect();
    let b: Vec<_> = scene.kept_b.iter().map(|t| t.triangle).collect();
    run_binning(&a, &b, scene.octree.as_ref().unwrap().root.unwrap(), params)
}

fn sizes(scene: &PreparedScene, run: &BinningRun) -> UnitSizes {
    let words = run.list_words.iter().flatten().max().copied().unwrap_or(1).max(1) as usize;
    UnitSizes { triangles: scene.kept_a.len().max(scene.kept_b.len()), list_words: words, leaves: run.peak_leaves.max(1) }
}

fn expected_leaves(run: &BinningRun) -> Vec<StreamedLeaf> {
    run.leaves.iter().zip(&run.leaf_lists).map(|(leaf, (a, b))| StreamedLeaf { cell: leaf.cell, a: a.clone(), b: b.clone() }).collect()
}

#[test]
fn rust_hdl_bins_as_the_model_leaf_for_leaf_and_clock_for_clock() {
    let scene = scene(16, 48);
    let params = BinningParams { log_depth: 4, log_pipelines: 1, max_leaf_level: None };
    let run = model(&scene, params);
    // The model is the planner (tested in the hardware crate); here the
    // leaves must also be the scene's schedule.
    let schedule = scene.octree.as_ref().unwrap();
    assert_eq!(run.leaves.len(), schedule.leaves.len());
    assert!(run.leaves.len() > 20 && run.peak_frames > 3, "{} leaves, {} frames", run.leaves.len(), run.peak_frames);
    let out = run_rusthdl(24, &scene.kept_a.iter().map(|t| t.triangle).collect::<Vec<_>>(), &scene.kept_b.iter().map(|t| t.triangle).collect::<Vec<_>>(), schedule.root.unwrap(), params, sizes(&scene, &run), &|_| true).unwrap();
    assert_eq!(out.leaves, expected_leaves(&run));
    assert_eq!(out.cycles, run.cycles);
    eprintln!("{} leaves, {} frames at most, {} cells passed, {} clocks; {} + {} triangles", run.leaves.len(), run.peak_frames, run.cells, run.cycles, scene.kept_a.len(), scene.kept_b.len());
}
