//! The classifier's setup in hardware computes what the software model
//! computes, triangle for triangle and bit for bit: the rust-hdl model and
//! the emitted Verilog in Icarus and Verilator, on the broad phase's own
//! quantized triangles and root, on degenerate triangles, and on extreme
//! triangles that use the whole value width. And its functions, fed to the
//! classifier step at the root, give the children the triangle's own test
//! finds: setup and classifier together decide as the software does.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_cosim::cell_classifier::{run_rusthdl as classify, ClassifierEntry};
use tritri_cosim::simulator::Simulator;
use tritri_cosim::triangle_setup::{expected, run_emitted, run_rusthdl};
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::cell::Cell;
use tritri_geom::octree::triangle_cell::{TriangleCellTest, BROAD_PHASE_MARGIN};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::{prepare_octree, SceneOptions};
use tritri_rtl::system::SystemConfig;

/// The built-in scene's kept triangles and the octree's root, plus points
/// and segments (zero normals and zero edge functions).
fn scene_triangles() -> (Vec<FixedTriangle>, Cell) {
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
    let mut triangles: Vec<FixedTriangle> = scene
        .kept_a
        .iter()
        .chain(&scene.kept_b)
        .map(|t| t.triangle)
        .take(600)
        .collect();
    let p = triangles[0][0];
    let q = triangles[1][2];
    triangles.extend([
        [p, p, p],
        [p, q, p],
        [p, q, q],
        [q, p, [2 * q[0] - p[0], 2 * q[1] - p[1], 2 * q[2] - p[2]]],
    ]);
    (triangles, root)
}

#[test]
fn scene_triangles_agree_in_rust_hdl_icarus_and_verilator() {
    let (triangles, root) = scene_triangles();
    let want = expected(&triangles, root.lo, true);
    eprintln!("{} triangles, root {:?}", triangles.len(), root);
    assert_eq!(
        run_rusthdl(24, 1, &triangles, root.lo, true).unwrap(),
        want,
        "rust-hdl"
    );
    assert_eq!(
        run_emitted(24, 1, &triangles, root.lo, true, Simulator::Icarus).unwrap(),
        want,
        "Icarus"
    );
    assert_eq!(
        run_emitted(24, 1, &triangles, root.lo, true, Simulator::Verilator).unwrap(),
        want,
        "Verilator"
    );
}

/// A setup sharing its products over 2, 3 or 4 clocks (a lane behind a
/// 128- or 64-bit port) answers as the software, one triangle every
/// `phases` clocks with other vertices on its inputs in between: rust-hdl,
/// Icarus and Verilator, on the scene's triangles at G = 24 and the
/// extreme ones at G = 16.
#[test]
fn phased_setups_agree_in_rust_hdl_icarus_and_verilator() {
    let (scene, root) = scene_triangles();
    let scene = &scene[..200];
    let want = expected(scene, root.lo, true);
    let extreme = extreme_triangles(16);
    let root16 = [-(1i64 << 15); 3];
    let want16 = expected(&extreme, root16, true);
    for phases in [2, 3, 4] {
        assert_eq!(
            run_rusthdl(24, phases, scene, root.lo, true).unwrap(),
            want,
            "rust-hdl, {phases} phases"
        );
        assert_eq!(
            run_rusthdl(16, phases, &extreme, root16, true).unwrap(),
            want16,
            "rust-hdl, G = 16, {phases} phases"
        );
        for simulator in [Simulator::Icarus, Simulator::Verilator] {
            assert_eq!(
                run_emitted(24, phases, scene, root.lo, true, simulator).unwrap(),
                want,
                "{simulator:?}, {phases} phases"
            );
        }
        assert_eq!(
            run_emitted(16, phases, &extreme, root16, true, Simulator::Verilator).unwrap(),
            want16,
            "Verilator, G = 16, {phases} phases"
        );
    }
}

/// Triangles with vertices at the corners of the `g`-bit grid, and some
/// anywhere in it.
fn extreme_triangles(g: usize) -> Vec<FixedTriangle> {
    let mut rng = ChaCha8Rng::seed_from_u64(g as u64 + 100);
    let half = 1i64 << (g - 1);
    let corner =
        |rng: &mut ChaCha8Rng| [0; 3].map(|_| if rng.gen_bool(0.5) { -half } else { half - 1 });
    let any = |rng: &mut ChaCha8Rng| [0; 3].map(|_| rng.gen_range(-half..half));
    (0..80)
        .map(|i| {
            if i % 2 == 0 {
                [corner(&mut rng), corner(&mut rng), corner(&mut rng)]
            } else {
                [any(&mut rng), corner(&mut rng), any(&mut rng)]
            }
        })
        .collect()
}

/// Vertices at the ends of the grid and the root at its low end: normals
/// near 2^(2G), plane values beyond 2^(3G-1), within the 3G + 6 bits.
#[test]
fn extreme_triangles_at_every_grid_width() {
    for g in [16usize, 24, 32] {
        let half = 1i64 << (g - 1);
        let triangles = extreme_triangles(g);
        let root = [-half; 3];
        // Grown by a step (the broad phase) at G = 16 and 32, exact at 24.
        let grow = g != 24;
        let want = expected(&triangles, root, grow);
        let biggest = want
            .iter()
            .flat_map(|(_, axes)| {
                axes.iter()
                    .flat_map(|(g, l, h)| g.iter().chain([l, h]).map(|x| x.unsigned_abs()))
            })
            .max()
            .unwrap();
        eprintln!(
            "G = {g}: largest value 2^{:.1} of the {}-bit range",
            (biggest as f64).log2(),
            tritri_rtl::octree::value_bits(g)
        );
        assert!(
            biggest >= 1u128 << (3 * g - 1),
            "G = {g}: the values do not reach 2^(3G-1)"
        );
        assert_eq!(
            run_rusthdl(g, 1, &triangles, root, grow).unwrap(),
            want,
            "rust-hdl, G = {g}"
        );
        assert_eq!(
            run_emitted(g, 1, &triangles, root, grow, Simulator::Icarus).unwrap(),
            want,
            "Icarus, G = {g}"
        );
    }
}

/// The setup's functions as the classifier's first entries (at the root,
/// no values): the children masks equal the triangle's own test.
#[test]
fn setup_then_classifier_decide_as_the_software() {
    let (triangles, root) = scene_triangles();
    let answers = run_rusthdl(24, 1, &triangles, root.lo, true).unwrap();
    let entries: Vec<ClassifierEntry> = answers
        .iter()
        .map(|&(tag, axes)| ClassifierEntry {
            tag,
            level: root.level,
            descend: None,
            at_lo: [0; 13],
            axes,
        })
        .collect();
    let masks: Vec<u8> = classify(24, &entries)
        .unwrap()
        .iter()
        .map(|a| a.mask)
        .collect();
    let want: Vec<u8> = triangles
        .iter()
        .map(|t| TriangleCellTest::widened(t, BROAD_PHASE_MARGIN).children_of_cell(&root))
        .collect();
    let met: u32 = want.iter().map(|m| m.count_ones()).sum();
    eprintln!(
        "{} triangles at the root (level {}): {met} children met of {}",
        triangles.len(),
        root.level,
        8 * triangles.len()
    );
    assert!(met > 0 && (met as usize) < 8 * triangles.len());
    assert_eq!(masks, want);
}
