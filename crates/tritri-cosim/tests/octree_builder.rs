//! The octree builder (voxel → octree in hardware) equals its cycle model
//! node for node and edge for edge, in rust-hdl, Icarus and Verilator, and
//! its nodes reversed are the canonical octree of the software model: on
//! empty, full, random and voxelized models; and the round trip octree →
//! voxels → octree, the voxel fill then the builder, is lossless in
//! hardware.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_cosim::engine::Engine;
use tritri_cosim::octree_builder::run;
use tritri_geom::builtin_scene::torus;
use tritri_geom::octree::tree::Octree;
use tritri_geom::octree::voxelize::{surface, VoxelFrame};
use tritri_geom::octree::voxels::VoxelGrid;

/// Blocks of side `2^block` filled with probability `p`.
fn blocky(level: u32, block: u32, p: f64, seed: u64) -> VoxelGrid {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut grid = VoxelGrid::empty(level);
    let n = 1usize << level;
    for z in (0..n).step_by(1 << block) {
        for y in (0..n).step_by(1 << block) {
            for x in (0..n).step_by(1 << block) {
                if rng.gen_bool(p) {
                    grid.fill_cube([x, y, z], block);
                }
            }
        }
    }
    grid
}

fn check(name: &str, grid: &VoxelGrid, engines: &[Engine]) {
    let tree = Octree::from_voxels(grid);
    let model = run(Engine::Model, grid).unwrap();
    assert_eq!(
        model.preorder(),
        tree.nodes(),
        "{name}: the cycle model against the software tree"
    );
    assert_eq!(
        Octree::from_preorder(grid.level(), &model.preorder())
            .unwrap()
            .to_voxels(),
        *grid,
        "{name}: round trip"
    );
    eprintln!(
        "{name}: 2^{} grid, {} voxels: {} nodes in {} cycles",
        grid.level(),
        grid.count(),
        model.nodes.len(),
        model.cycles
    );
    for &engine in engines {
        assert_eq!(
            run(engine, grid).unwrap(),
            model,
            "{name}: {}",
            engine.name()
        );
    }
}

#[test]
fn edge_cases_agree_in_rust_hdl_icarus_and_verilator() {
    let all = [Engine::Rusthdl, Engine::Icarus, Engine::Verilator];
    for level in [2, 3, 4] {
        check(&format!("empty {level}"), &VoxelGrid::empty(level), &all);
        let mut full = VoxelGrid::empty(level);
        full.fill_cube([0; 3], level);
        check(&format!("full {level}"), &full, &all);
        let mut one = VoxelGrid::empty(level);
        one.set([1, 0, (1 << level) - 1]);
        check(&format!("one voxel {level}"), &one, &all);
        let mut all_but_one = full.clone();
        all_but_one =
            all_but_one.combine(tritri_geom::octree::tree::SetOperation::Difference, &one);
        check(&format!("all but one voxel {level}"), &all_but_one, &all);
    }
    check("random 3", &blocky(3, 0, 0.5, 3), &all);
}

#[test]
fn random_models_agree_at_several_levels() {
    for (level, block, p) in [
        (4, 0, 0.1),
        (4, 1, 0.5),
        (5, 2, 0.7),
        (6, 1, 0.05),
        (6, 3, 0.5),
    ] {
        let grid = blocky(level, block, p, level as u64 * 10 + block as u64);
        check(
            &format!("blocks of 2^{block}, p = {p}"),
            &grid,
            &[Engine::Rusthdl, Engine::Verilator],
        );
    }
}

#[test]
fn a_voxelized_torus_agrees_in_verilator() {
    let triangles = torus([0.0, 0.0, 0.0], 1.0, 0.35, 24, 12);
    let level = 6;
    let frame = VoxelFrame::fit(&triangles, level).unwrap();
    let fixed: Vec<_> = triangles.iter().map(|t| frame.quantize(t)).collect();
    check(
        "torus surface",
        &surface(&fixed, level, &mut |_| ()),
        &[Engine::Verilator],
    );
}

/// The round trip in hardware: a random octree's full leaves written into
/// the voxel memory by the voxel fill, that memory read back by the octree
/// builder, both in rust-hdl: the same tree.
#[test]
fn octree_to_voxels_to_octree_in_hardware_is_lossless() {
    for (i, (level, block, p)) in [(2, 0, 0.4), (4, 1, 0.5), (5, 2, 0.3), (5, 0, 0.02)]
        .into_iter()
        .enumerate()
    {
        let tree = Octree::from_voxels(&blocky(level, block, p, 100 + i as u64));
        let filled = tritri_cosim::voxel_fill::fill_rusthdl(level, &tree.fill_records()).unwrap();
        let memory = VoxelGrid::from_words(level, filled.words).unwrap();
        let built = run(Engine::Rusthdl, &memory).unwrap();
        assert_eq!(
            built.preorder(),
            tree.nodes(),
            "level {level}: {} nodes",
            tree.nodes().len()
        );
    }
}
