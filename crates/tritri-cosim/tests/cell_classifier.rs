//! The octree classifier step in hardware answers what the software
//! classifier answers, entry for entry: the rust-hdl model and the emitted
//! Verilog in Icarus and Verilator, on the entries a binning pass meets in
//! a real scene (the broad phase's own quantized triangles and root cell)
//! and on extreme triangles that reach the ends of the value width.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_cosim::cell_classifier::{
    harvest, run_emitted, run_rusthdl, ClassifierAnswer, ClassifierEntry, Simulator,
};
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::octree::cell::Cell;
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::{prepare_octree, SceneOptions};
use tritri_rtl::system::SystemConfig;

fn split(
    vectors: Vec<(ClassifierEntry, ClassifierAnswer)>,
) -> (Vec<ClassifierEntry>, Vec<ClassifierAnswer>) {
    vectors.into_iter().unzip()
}

fn hits_and_misses(answers: &[ClassifierAnswer]) -> (usize, usize) {
    let hits: usize = answers.iter().map(|a| a.mask.count_ones() as usize).sum();
    (hits, answers.len() * 8 - hits)
}

#[test]
fn scene_entries_agree_in_rust_hdl_icarus_and_verilator() {
    let a = SceneObject::from_triangles("torus", torus([0.0, 0.0, 0.0], 1.0, 0.35, 48, 16));
    let b = SceneObject::from_triangles("sphere", sphere([1.0, 0.0, 0.55], 0.4, 32, 24));
    let options = SceneOptions {
        grid_bits: 24,
        depth: 64,
        split: true,
    };
    let config = SystemConfig::new(24, 2).with_depth(64);
    let scene = prepare_octree(&a, &b, &options, &config, None).unwrap();
    let root = scene
        .octree
        .as_ref()
        .and_then(|o| o.root)
        .expect("an octree root");
    let triangles: Vec<_> = scene
        .kept_a
        .iter()
        .chain(&scene.kept_b)
        .map(|t| t.triangle)
        .collect();
    let (mut entries, mut expected) = split(harvest(&triangles, root, 6, 3000));
    let (boundary_entries, boundary_expected) =
        split(harvest(&on_cell_corners(root, 24), root, 4, 1000));
    entries.extend(boundary_entries);
    expected.extend(boundary_expected);
    let (hits, misses) = hits_and_misses(&expected);
    eprintln!(
        "{} entries, root level {}, {hits} children met, {misses} missed",
        entries.len(),
        root.level
    );
    assert_eq!(entries.len(), 4000);
    assert!(
        hits > 2000 && misses > 2000,
        "{hits} hits, {misses} misses: too one-sided to test"
    );
    assert!(
        entries.iter().any(|e| e.descend.is_none()) && entries.iter().any(|e| e.descend.is_some())
    );

    assert_eq!(run_rusthdl(24, &entries).unwrap(), expected, "rust-hdl");
    assert_eq!(
        run_emitted(24, &entries, Simulator::Icarus).unwrap(),
        expected,
        "Icarus"
    );
    assert_eq!(
        run_emitted(24, &entries, Simulator::Verilator).unwrap(),
        expected,
        "Verilator"
    );
}

/// Triangles whose vertices are corners of cells three levels below
/// `root`: they touch cells at faces, edges and corners exactly, where a
/// closed-cell test differs from an open one.
fn on_cell_corners(root: Cell, seed: u64) -> Vec<[[i64; 3]; 3]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let step = root.size() >> 3;
    let corner = |rng: &mut ChaCha8Rng| [0, 1, 2].map(|k| root.lo[k] + step * rng.gen_range(0..=8));
    (0..200)
        .map(|_| [corner(&mut rng), corner(&mut rng), corner(&mut rng)])
        .collect()
}

/// Triangles with vertices at the ends of the grid (long edges, normals
/// near 2^(2G+1)) in the largest root the grid allows, for every emitted
/// grid width: the values use the full `3G + 6` bits.
#[test]
fn extreme_triangles_at_every_grid_width() {
    for g in [16usize, 24, 32] {
        let mut rng = ChaCha8Rng::seed_from_u64(g as u64);
        let half = 1i64 << (g - 1);
        let corner = |rng: &mut ChaCha8Rng| {
            [0; 3].map(|_| {
                if rng.gen_bool(0.5) {
                    -half
                } else {
                    half - 1 - rng.gen_range(0..4)
                }
            })
        };
        let any = |rng: &mut ChaCha8Rng| [0; 3].map(|_| rng.gen_range(-half..half));
        let triangles: Vec<[[i64; 3]; 3]> = (0..60)
            .map(|i| {
                if i % 2 == 0 {
                    [corner(&mut rng), corner(&mut rng), any(&mut rng)]
                } else {
                    [any(&mut rng), any(&mut rng), any(&mut rng)]
                }
            })
            .collect();
        let root = Cell {
            lo: [-half; 3],
            level: g as u32,
        };
        let (entries, expected) = split(harvest(&triangles, root, 3, 800));
        let (hits, misses) = hits_and_misses(&expected);
        assert!(
            hits > 100 && misses > 100,
            "G = {g}: {hits} hits, {misses} misses"
        );
        assert_eq!(
            run_rusthdl(g, &entries).unwrap(),
            expected,
            "rust-hdl, G = {g}"
        );
        assert_eq!(
            run_emitted(g, &entries, Simulator::Icarus).unwrap(),
            expected,
            "Icarus, G = {g}"
        );
    }
}
