//! The owner filter decides in hardware which leaf reports a pair: on an
//! octree schedule whose triangles sit in many leaves, the hits of every
//! leaf (duplicates included) go in as slots, and each intersecting pair
//! comes out once, as triangle ids. rust-hdl, Icarus and Verilator give the
//! model's pairs in the model's order at the cycle model's edges.

use tritri_cosim::engine::narrow_phase;
use tritri_cosim::owner_filter::{expected, run_emitted, run_rusthdl};
use tritri_cosim::simulator::Simulator;
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::owner_slots::OwnerSlots;
use tritri_geom::scene::reference::{fixed_point_pairs, PairSet};
use tritri_geom::scene::{prepare_octree, PreparedScene, SceneOptions};
use tritri_rtl::system::SystemConfig;

/// A torus and a sphere in contact, cut into small leaves (memory depth
/// 16), so that many triangles are in several leaves and many hits are
/// found more than once.
fn scene() -> PreparedScene {
    let a = SceneObject::from_triangles("torus", torus([0.0, 0.0, 0.0], 1.0, 0.35, 48, 24));
    let b = SceneObject::from_triangles("sphere", sphere([1.0, 0.0, 0.55], 0.4, 32, 16));
    let config = SystemConfig::new(24, 2).with_depth(16);
    prepare_octree(
        &a,
        &b,
        &SceneOptions {
            grid_bits: 24,
            depth: 16,
            split: true,
        },
        &config,
        None,
    )
    .unwrap()
}

/// The scene's slot tables and its hits in leaf order, as slots.
fn slots_and_hits(scene: &PreparedScene) -> (OwnerSlots, Vec<(u32, u32)>) {
    let schedule = scene.octree.as_ref().expect("an octree schedule");
    let slots = OwnerSlots::of(schedule);
    let (a, b) = slots.slotted(schedule);
    let (hits, _) = narrow_phase(&scene.leaf_batches(&a, &b), &|_| {});
    (slots, hits)
}

#[test]
fn each_pair_leaves_once_in_rust_hdl_icarus_and_verilator() {
    let scene = scene();
    let schedule = scene.octree.as_ref().expect("an octree schedule");
    let (slots, hits) = slots_and_hits(&scene);
    let model = expected(&slots, &hits);

    // The model: every pair of the scene, once.
    let pairs: PairSet = model.pairs.iter().copied().collect();
    assert_eq!(pairs.len(), model.pairs.len(), "a pair left twice");
    assert_eq!(pairs, fixed_point_pairs(&scene.batches(), &|_| {}));
    let decisions: Vec<_> = hits.iter().map(|&(sa, sb)| slots.decide(sa, sb)).collect();
    let merged = decisions.iter().filter(|d| d.comparisons > 0).count();
    let dropped = decisions.iter().filter(|d| !d.owner).count();
    eprintln!(
        "owner filter: {} leaves, {} + {} slots, {} hits, {} merged, {} duplicates dropped, {} pairs, last at edge {:?}",
        schedule.leaves.len(),
        slots.a.len(),
        slots.b.len(),
        hits.len(),
        merged,
        dropped,
        model.pairs.len(),
        model.edges.last()
    );
    assert!(
        dropped > 50 && merged > dropped,
        "the scene must exercise the merge: {merged} merged, {dropped} dropped"
    );

    assert_eq!(run_rusthdl(&slots, &hits, |_| true), model, "rust-hdl");
    assert_eq!(
        run_emitted(&slots, &hits, Simulator::Icarus).unwrap(),
        model,
        "Icarus"
    );
    assert_eq!(
        run_emitted(&slots, &hits, Simulator::Verilator).unwrap(),
        model,
        "Verilator"
    );
}

/// A reader that is ready one cycle in three changes when pairs leave, not
/// which or in what order.
#[test]
fn a_slow_reader_changes_no_pair() {
    let (slots, hits) = slots_and_hits(&scene());
    let model = expected(&slots, &hits);
    let slow = run_rusthdl(&slots, &hits, |edge| edge % 3 == 2);
    assert_eq!(slow.pairs, model.pairs);
    assert!(slow.edges.last() > model.edges.last());
}
