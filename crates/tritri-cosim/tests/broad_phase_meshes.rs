//! The broad-phase top, emitted and run in Verilator on a real scene:
//! CGAL's camel and elephant (19,536 and 5,558 triangles, from Debian's
//! `libcgal-demo`, fetched by `scripts/fetch-meshes.sh`) posed in contact
//! as `scripts/broad-phase-scenes.sh` poses them. The top gives each pair
//! once, the flat system's pairs; its hits are the leaves' pairs on the
//! grid, `binned` comes at the binning unit's modelled clock and `done`
//! after the system's modelled clock by at most the owner filter's clocks.
//!
//! Run by `scripts/test-shared.sh` (`test = false`: `cargo test` runs it only
//! when named; the script fetches the meshes); a missing mesh is a failure, not a skip.

use std::collections::BTreeSet;
use std::path::PathBuf;
use tritri_cosim::broad_phase_system::{run_emitted, top_model};
use tritri_cosim::simulator::Simulator;
use tritri_geom::fixed_point::{intersects, FixedTriangle};
use tritri_geom::scene::load::{load_object, Pose};
use tritri_geom::scene::reference::fixed_point_pairs;
use tritri_geom::scene::{prepare, prepare_octree, SceneOptions};
use tritri_rtl::broad_phase::binning_machine::{run_binning, BinningParams};
use tritri_rtl::broad_phase::binning_unit::BinningUnitConfig;
use tritri_rtl::broad_phase::broad_phase_system::{broad_phase_cycles, stream_slots};
use tritri_rtl::emit::broad_phase_system_unit::BroadPhaseConfig;
use tritri_rtl::pipeline::triangle_pipeline::latency;
use tritri_rtl::system::SystemConfig;

fn mesh(name: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../build/meshes")
        .join(name);
    assert!(
        path.exists(),
        "{} missing: run bash scripts/fetch-meshes.sh",
        path.display()
    );
    path.to_string_lossy().into_owned()
}

#[test]
fn the_emitted_top_on_camel_and_elephant_in_verilator() {
    let a = load_object(&mesh("camel.off"), 0).unwrap();
    let b = load_object(&mesh("elephant.off"), 0)
        .unwrap()
        .posed(&Pose::translation([0.3, 0.0, 0.0]));
    let depth = 256;
    let system = SystemConfig::new(24, 2).with_depth(depth);
    let options = SceneOptions {
        grid_bits: 24,
        depth,
        split: true,
    };
    let scene = prepare_octree(&a, &b, &options, &system, None).unwrap();
    let ta: Vec<FixedTriangle> = scene.kept_a.iter().map(|t| t.triangle).collect();
    let tb: Vec<FixedTriangle> = scene.kept_b.iter().map(|t| t.triangle).collect();
    let root = scene.octree.as_ref().unwrap().root.unwrap();
    let params = BinningParams {
        log_depth: 8,
        log_pipelines: 1,
        max_leaf_level: None,
    };
    let run = run_binning(&ta, &tb, root, params);
    let unit = BinningUnitConfig::sized_for(24, params, ta.len().max(tb.len()), &run);
    let slots = stream_slots(depth, &run).into_iter().max().unwrap().max(1);
    let model = broad_phase_cycles(system, &run);
    let out = run_emitted(
        &BroadPhaseConfig {
            unit,
            system,
            slots,
            local_frames: false,
        },
        &ta,
        &tb,
        root,
        None,
        model + 100_000,
        Simulator::Verilator,
    )
    .unwrap();
    assert!(!out.overflow);

    let mut expected: Vec<(u32, u32)> = run
        .leaf_lists
        .iter()
        .flat_map(|(la, lb)| {
            la.iter()
                .flat_map(move |&i| lb.iter().map(move |&j| (i, j)))
        })
        .filter(|&(i, j)| intersects(&ta[i as usize], &tb[j as usize]))
        .collect();
    expected.sort_unstable();
    assert_eq!(out.hits as usize, expected.len());
    expected.dedup();
    let mut got = out.pairs.clone();
    got.sort_unstable();
    assert_eq!(got, expected, "each pair once");
    let pairs: BTreeSet<(u32, u32)> = got
        .iter()
        .map(|&(i, j)| (scene.kept_a[i as usize].id, scene.kept_b[j as usize].id))
        .collect();
    let flat = prepare(&a, &b, &options).unwrap();
    assert_eq!(
        pairs,
        fixed_point_pairs(&flat.batches(), &|_| {})
            .into_iter()
            .collect()
    );
    eprintln!(
        "camel x elephant: {} + {} triangles in the common box, {} leaves, {} pairs tested, {} hits, {} pairs; binned at {}, done at {} (the system's model {model})",
        ta.len(),
        tb.len(),
        run.leaves.len(),
        out.pairs_tested,
        out.hits,
        pairs.len(),
        out.binned_at,
        out.cycles
    );
    assert_eq!(out.binned_at, run.cycles);
    // The owner filter's pairs and, at most, its clocks after the system's.
    let top = top_model(&run, depth, &ta, &tb);
    assert_eq!(got, top.pairs);
    assert!(
        out.cycles >= model && out.cycles <= model + top.filter_clocks,
        "{} clocks, the filter's {}",
        out.cycles,
        top.filter_clocks
    );
}
