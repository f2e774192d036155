//! The route on the design that fits the ECP5-85
//! (`tritri_cosim::dram_query`): a scene within the owner filter's tables
//! runs as one case; a scene past them is cut into regions that fit, and
//! the answer is still exact f64's, each pair once.

use tritri_cosim::dram_broad_phase::TopCase;
use tritri_cosim::dram_query::{
    find_pairs_in_dram, fitting_cases, host_root_lists, DramAccelerator, DramQueryOptions,
    TABLE_WORDS,
};
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::{prepare, PreparedScene};
use tritri_rtl::broad_phase::list_entry::ENTRY_BYTES;

/// A torus of `nu * nv * 2` triangles and a sphere through its tube.
fn scene(nu: usize, nv: usize) -> (SceneObject, SceneObject) {
    (
        SceneObject::from_triangles("torus", torus([0.0, 0.0, 0.0], 1.0, 0.35, nu, nv)),
        SceneObject::from_triangles("sphere", sphere([1.0, 0.0, 0.55], 0.4, 120, 60)),
    )
}

#[test]
fn a_scene_past_the_tables_is_cut_into_regions_and_stays_exact() {
    let dram = DramAccelerator::versa();
    let (a, b) = scene(1000, 200);
    let prepared = prepare(&a, &b, &dram.accelerator().scene_options()).unwrap();
    assert!(
        prepared.kept_a.len() > TABLE_WORDS,
        "{} torus triangles near the sphere: the test needs more than the tables",
        prepared.kept_a.len()
    );
    let cases = fitting_cases(&dram, &prepared, dram.memory()).unwrap();
    assert!(cases.len() > 1, "{} regions", cases.len());
    for case in &cases {
        let [a, b] = case.ids.each_ref().map(Vec::len);
        assert!(a <= TABLE_WORDS && b <= TABLE_WORDS, "{a} + {b}");
    }
    assert_host_lists_are_the_memory(&prepared, &cases);
    let answer = find_pairs_in_dram(&a, &b, &dram, &DramQueryOptions::default()).unwrap();
    assert!(answer.faults.is_empty(), "{:?}", answer.faults);
    let check = answer.check.as_ref().unwrap();
    assert!(
        check.engine_vs_grid.is_empty(),
        "{:?}",
        check.engine_vs_grid
    );
    assert_eq!(answer.pairs, check.truth.pairs);
    assert!(!answer.pairs.is_empty());
    let run = answer.run.as_ref().unwrap();
    assert_eq!(run.cases.len(), cases.len());
    // The regions run one after another: their clocks add.
    assert!(run.clocks() >= run.memory_bound());
}

/// What the host packs (and the route times) is what the simulated memory
/// holds: each root list, byte for byte.
fn assert_host_lists_are_the_memory(scene: &PreparedScene, cases: &[TopCase]) {
    let regions = host_root_lists(scene, cases).unwrap();
    assert_eq!(regions.len(), cases.len());
    for (lists, case) in regions.iter().zip(cases) {
        for (k, list) in lists.iter().enumerate() {
            let (at, count) = case.binning.root_lists[k];
            let (at, bytes) = (at as usize, count as usize * ENTRY_BYTES);
            assert_eq!(list.len(), bytes, "object {k}");
            assert!(
                list[..] == case.binning.bytes[at..at + bytes],
                "object {k}'s root list"
            );
        }
    }
}

/// The built-in scene fits: one case, the model's clocks at the routed
/// clock, the end-to-end parts summing to the whole.
#[test]
fn the_built_in_scene_is_one_case() {
    let dram = DramAccelerator::versa();
    assert!(dram.clock.source.is_post_route(), "{:?}", dram.clock);
    let (a, b) = scene(48, 24);
    let answer = find_pairs_in_dram(&a, &b, &dram, &DramQueryOptions::default()).unwrap();
    let run = answer.run.as_ref().unwrap();
    assert_eq!(run.cases.len(), 1);
    assert_host_lists_are_the_memory(&answer.scene, &run.cases);
    assert_eq!(answer.pairs, answer.check.as_ref().unwrap().truth.pairs);
    let whole = answer.end_to_end().unwrap();
    assert_eq!(
        whole.total(),
        whole.host + whole.link_in + whole.accelerator + whole.link_back + whole.redecide
    );
    assert_eq!(whole.accelerator, dram.clock.time_of(run.clocks()));
}
