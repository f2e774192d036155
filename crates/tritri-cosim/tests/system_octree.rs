//! The system behind the octree broad phase, in rust-hdl and in the emitted
//! Verilog under Verilator, on a scene of over 5,000 triangles per object
//! (a finely tessellated torus and sphere in contact). Properties: the
//! leaves' batches give, in both simulators, exactly the pairs of the flat
//! system (the bit-exact model over every pair in the common box), the
//! rust-hdl and Verilator runs are identical word for word, and the cycle
//! count is the system's cycle model over the leaf batches.

use tritri_cosim::simulator::Simulator;
use tritri_cosim::system_harness::PipelineKind;
use tritri_cosim::system_harness::{run_system, ReaderBehaviour};
use tritri_cosim::system_rtl::run_system_rtl;
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::reference::{fixed_point_pairs, PairSet};
use tritri_geom::scene::{prepare, prepare_octree, SceneOptions};
use tritri_rtl::system::cycle_model::scene_cycles;
use tritri_rtl::system::SystemConfig;

#[test]
fn octree_leaves_through_rust_hdl_and_verilator_give_the_flat_pairs() {
    let a = SceneObject::from_triangles("torus", torus([0.0, 0.0, 0.0], 1.0, 0.35, 96, 32));
    let b = SceneObject::from_triangles("sphere", sphere([1.0, 0.0, 0.55], 0.4, 64, 48));
    assert!(
        a.triangles.len() >= 5000 && b.triangles.len() >= 5000,
        "{} {}",
        a.triangles.len(),
        b.triangles.len()
    );
    let config = SystemConfig::new(24, 2).with_depth(64);
    let options = SceneOptions {
        grid_bits: 24,
        depth: 64,
        split: true,
    };
    let flat = prepare(&a, &b, &options).unwrap();
    let scene = prepare_octree(&a, &b, &options, &config, None).unwrap();
    let expected = fixed_point_pairs(&flat.batches(), &|_| {});
    assert_eq!(fixed_point_pairs(&scene.batches(), &|_| {}), expected);
    assert!(expected.len() > 100, "{} pairs", expected.len());
    assert!(
        scene.pairs_tested() * 100 < flat.pairs_tested(),
        "{} vs {}",
        scene.pairs_tested(),
        flat.pairs_tested()
    );

    let batches = scene.batches();
    let model_cycles = scene_cycles(config, &batches);

    let hdl = run_system(config, &batches, ReaderBehaviour::AlwaysReady).unwrap();
    let rtl = run_system_rtl(
        Simulator::Verilator,
        config,
        PipelineKind::Parallel,
        &batches,
        true,
        ReaderBehaviour::AlwaysReady,
    )
    .unwrap();
    eprintln!(
        "octree: {} leaves' batches, {} pairs tested (flat {}), {} pairs, cycles {} (model {model_cycles})",
        batches.len(),
        scene.pairs_tested(),
        flat.pairs_tested(),
        expected.len(),
        hdl.cycles
    );
    assert_eq!(rtl, hdl, "Verilator and rust-hdl differ");
    assert_eq!(hdl.pairs.iter().copied().collect::<PairSet>(), expected);
    assert_eq!(hdl.cycles, model_cycles);
    assert_eq!(hdl.pairs_tested, scene.pairs_tested());
    assert!(!hdl.overflow);
}
