//! The triangle voxelizer in hardware equals its cycle model record for
//! record and edge for edge, in rust-hdl, Icarus and Verilator, and the
//! records mark exactly the software voxelizer's voxels: on the cases
//! voxelizers get wrong (faces on cell faces, edges and corners, degenerate
//! triangles), on random triangles, and on a mesh.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_cosim::simulator::Simulator;
use tritri_cosim::triangle_voxelizer::{check_stream, run_emitted, run_rusthdl};
use tritri_geom::builtin_scene::torus;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::voxelize::{surface, VoxelFrame, SUB_BITS};

/// Faces lying on voxel faces, edges and corners, points and segments,
/// triangles spanning the grid, at level 3.
fn hard_cases() -> Vec<FixedTriangle> {
    let s = 1i64 << SUB_BITS;
    let v = |x: i64, y: i64, z: i64| [x * s, y * s, z * s];
    vec![
        [v(0, 0, 0), v(8, 0, 0), v(0, 8, 0)],
        [v(2, 2, 2), v(6, 2, 2), v(2, 6, 2)],
        [v(4, 0, 0), v(4, 8, 0), v(4, 0, 8)],
        [v(3, 3, 3), v(3, 3, 3), v(3, 3, 3)],
        [v(1, 1, 1), v(7, 7, 7), v(4, 4, 4)],
        [v(2, 5, 0), v(2, 5, 8), v(2, 5, 4)],
        [v(8, 8, 8), v(8, 8, 8), v(0, 8, 8)],
        [
            [s / 3, 5 * s + 7, 8 * s],
            [8 * s, s, s / 2],
            [4 * s, 8 * s, 0],
        ],
        [v(0, 0, 0), v(8, 8, 8), v(8, 0, 8)],
    ]
}

fn random_triangles(level: u32, count: usize, seed: u64) -> Vec<FixedTriangle> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let top = 1i64 << (level + SUB_BITS);
    (0..count)
        .map(|_| {
            // Small triangles near a random point, and a few long ones.
            let size = if rng.gen_bool(0.8) { top / 16 } else { top };
            let centre = [0; 3].map(|_: i64| rng.gen_range(0..=top));
            [0; 3]
                .map(|_: i64| 0)
                .map(|_| [0, 1, 2].map(|k| (centre[k] + rng.gen_range(-size..=size)).clamp(0, top)))
        })
        .collect()
}

fn check(name: &str, triangles: &[FixedTriangle], level: u32, simulators: &[Simulator]) {
    let model = check_stream(triangles, level).unwrap();
    let want = surface(triangles, level, &mut |_| ());
    assert_eq!(
        model.grid(level),
        want,
        "{name}: the cycle model's records against the software voxelizer"
    );
    eprintln!(
        "{name}: {} triangles at 2^{level}: {} voxels, {} records, {} cells, {} cycles, stack depth {}",
        triangles.len(),
        want.count(),
        model.records.len(),
        model.cells,
        model.cycles,
        model.stack_depth
    );
    let mut rusthdl = run_rusthdl(triangles, level);
    rusthdl.cells = model.cells;
    rusthdl.stack_depth = model.stack_depth;
    assert_eq!(rusthdl, model, "{name}: rust-hdl");
    for &simulator in simulators {
        let mut emitted = run_emitted(triangles, level, simulator).unwrap();
        emitted.cells = model.cells;
        emitted.stack_depth = model.stack_depth;
        assert_eq!(emitted, model, "{name}: {simulator:?}");
    }
}

#[test]
fn hard_cases_agree_in_rust_hdl_icarus_and_verilator() {
    check(
        "hard cases",
        &hard_cases(),
        3,
        &[Simulator::Icarus, Simulator::Verilator],
    );
}

#[test]
fn random_triangles_agree_at_several_levels() {
    for (level, count) in [(1, 20), (4, 60), (7, 40), (10, 12)] {
        check(
            &format!("random, level {level}"),
            &random_triangles(level, count, level as u64),
            level,
            &[Simulator::Verilator],
        );
    }
}

#[test]
fn a_torus_mesh_agrees_in_verilator() {
    let triangles = torus([0.0, 0.0, 0.0], 1.0, 0.35, 24, 12);
    let level = 5;
    let frame = VoxelFrame::fit(&triangles, level).unwrap();
    let fixed: Vec<FixedTriangle> = triangles.iter().map(|t| frame.quantize(t)).collect();
    check("torus", &fixed, level, &[Simulator::Verilator]);
}

/// A unit built with a stack of 4 entries: its overflow flag rises exactly
/// for the triangles whose traversal the cycle model says needs more, and
/// the others are voxelized as the model says.
#[test]
fn the_overflow_flag_rises_exactly_when_the_stack_is_too_small() {
    use tritri_cosim::triangle_voxelizer::run_rusthdl_with_stack;
    let (mut over, mut within) = (0, 0);
    for (i, t) in random_triangles(6, 40, 66).iter().enumerate() {
        let stream = [*t];
        let model = check_stream(&stream, 6).unwrap();
        let (run, overflow) = run_rusthdl_with_stack::<2>(&stream, 6);
        assert_eq!(
            overflow,
            model.stack_depth > 4,
            "triangle {i}: stack depth {}",
            model.stack_depth
        );
        if overflow {
            over += 1;
        } else {
            within += 1;
            assert_eq!(
                (run.records, run.edges, run.cycles),
                (model.records, model.edges, model.cycles),
                "triangle {i}"
            );
        }
    }
    eprintln!("{over} triangles overflow a 4-entry stack, {within} fit");
    assert!(over > 0 && within > 0);
}
