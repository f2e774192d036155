//! The broad-phase top, triangles in to pairs out in one design: the
//! binning unit's leaves go straight into the collision system, whose hits
//! the owner filter lets through once. In rust-hdl and Verilator its pairs
//! are the leaves' fixed-point pairs, each once (the filter's model's
//! owned pairs), their set is the flat system's, the system's hits and
//! pairs tested are the leaves', `binned` comes at the binning unit's
//! modelled clock, and `done` after the system's modelled clock
//! (`broad_phase_cycles`: the binning unit's model, then the system's bank
//! recurrence fed at the leaf stream's pace) by at most the filter's
//! clocks for the hits back to back.

use tritri_cosim::broad_phase_system::{
    run_emitted, run_rusthdl, top_model, BroadPhaseOutput, TopModel,
};
use tritri_cosim::simulator::Simulator;
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::fixed_point::{intersects, FixedTriangle};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::octree::LocalFrames;
use tritri_geom::scene::reference::fixed_point_pairs;
use tritri_geom::scene::{prepare, prepare_octree, PreparedScene, SceneOptions, TaggedTriangle};
use tritri_rtl::broad_phase::binning_machine::{run_binning, BinningParams, BinningRun};
use tritri_rtl::broad_phase::binning_unit::BinningUnitConfig;
use tritri_rtl::broad_phase::broad_phase_system::{broad_phase_cycles, leaf_batches, stream_slots};
use tritri_rtl::emit::broad_phase_system_unit::BroadPhaseConfig;
use tritri_rtl::system::cycle_model::BatchSizes;
use tritri_rtl::system::SystemConfig;

fn objects(torus_segments: usize, sphere_segments: usize) -> (SceneObject, SceneObject) {
    (
        SceneObject::from_triangles(
            "torus",
            torus(
                [0.0, 0.0, 0.0],
                1.0,
                0.35,
                torus_segments,
                torus_segments / 2,
            ),
        ),
        SceneObject::from_triangles(
            "sphere",
            sphere([1.0, 0.0, 0.55], 0.4, sphere_segments, sphere_segments / 2),
        ),
    )
}

fn arrays(scene: &PreparedScene) -> (Vec<FixedTriangle>, Vec<FixedTriangle>) {
    (
        scene.kept_a.iter().map(|t| t.triangle).collect(),
        scene.kept_b.iter().map(|t| t.triangle).collect(),
    )
}

/// The top's output against its model: each pair once, the model's owned
/// pairs, the system's hits; the clocks from the system's model on, with
/// the filter's clocks at most added after it. Prints the run's figures
/// under `label`.
fn assert_top_as_model(
    label: &str,
    out: &BroadPhaseOutput,
    run: &BinningRun,
    system: SystemConfig,
    a: &[FixedTriangle],
    b: &[FixedTriangle],
) -> (Vec<(u32, u32)>, usize) {
    let TopModel {
        pairs: owned,
        uncertain,
        hits,
        filter_clocks,
    } = top_model(run, system.triangles_per_bank, a, b);
    let mut pairs = out.pairs.clone();
    pairs.sort_unstable();
    assert_eq!(pairs, owned);
    let mut out_uncertain = out.uncertain.clone();
    out_uncertain.sort_unstable();
    assert_eq!(out_uncertain, uncertain, "the pairs without a certificate");
    let mut distinct = leaf_pairs(run, a, b);
    distinct.dedup();
    assert_eq!(pairs, distinct, "each pair once");
    assert_eq!(out.hits as usize, hits);
    let model = broad_phase_cycles(system, run);
    assert!(
        out.cycles >= model && out.cycles <= model + filter_clocks,
        "{} clocks, the system's model {model}, the filter's {filter_clocks}",
        out.cycles
    );
    eprintln!(
        "{label}: {} + {} triangles, {} leaves, {} pairs tested, {hits} hits, {} pairs, {} uncertain; binned at {}, done at {} (the system's model {model})",
        a.len(),
        b.len(),
        run.leaves.len(),
        out.pairs_tested,
        pairs.len(),
        uncertain.len(),
        out.binned_at,
        out.cycles
    );
    (pairs, hits)
}

/// Every leaf's intersecting pairs on the grid, as indices, sorted.
fn leaf_pairs(run: &BinningRun, a: &[FixedTriangle], b: &[FixedTriangle]) -> Vec<(u32, u32)> {
    let mut pairs: Vec<(u32, u32)> = run
        .leaf_lists
        .iter()
        .flat_map(|(la, lb)| {
            la.iter()
                .flat_map(move |&i| lb.iter().map(move |&j| (i, j)))
        })
        .filter(|&(i, j)| intersects(&a[i as usize], &b[j as usize]))
        .collect();
    pairs.sort_unstable();
    pairs
}

/// The top sized for the model's run of a scene.
fn top_for(
    run: &BinningRun,
    params: BinningParams,
    system: SystemConfig,
    triangles: usize,
    local_frames: bool,
) -> BroadPhaseConfig {
    let unit = BinningUnitConfig::sized_for(24, params, triangles, run);
    let slots = stream_slots(system.triangles_per_bank, run)
        .into_iter()
        .max()
        .unwrap_or(1)
        .max(1);
    BroadPhaseConfig {
        unit,
        system,
        slots,
        local_frames,
    }
}

#[test]
fn the_top_gives_each_pair_once_in_rust_hdl() {
    let (torus, sphere) = objects(48, 32);
    let depth = 16;
    let system = SystemConfig::new(24, 2).with_depth(depth);
    let options = SceneOptions {
        grid_bits: 24,
        depth,
        split: true,
    };
    let scene = prepare_octree(&torus, &sphere, &options, &system, None).unwrap();
    let (a, b) = arrays(&scene);
    let root = scene.octree.as_ref().unwrap().root.unwrap();
    let params = BinningParams {
        log_depth: 4,
        log_pipelines: 1,
        max_leaf_level: None,
    };
    let run = run_binning(&a, &b, root, params);
    let config = top_for(&run, params, system, a.len().max(b.len()), false);

    let out = run_rusthdl(&config, &a, &b, root, None).unwrap();
    assert!(!out.overflow);
    let (pairs, hits) = assert_top_as_model("torus x sphere", &out, &run, system, &a, &b);
    assert!(
        hits > pairs.len() && pairs.len() > 100,
        "{hits} hits, {} pairs",
        pairs.len()
    );
    // One record too few for the filter: the top says so.
    assert!(
        run_rusthdl(
            &BroadPhaseConfig {
                slots: config.slots - 1,
                ..config
            },
            &a,
            &b,
            root,
            None
        )
        .unwrap()
        .overflow
    );
    // Their set is the flat system's pairs.
    let flat = prepare(&torus, &sphere, &options).unwrap();
    let ids: std::collections::BTreeSet<(u32, u32)> = pairs
        .iter()
        .map(|&(i, j)| (scene.kept_a[i as usize].id, scene.kept_b[j as usize].id))
        .collect();
    assert_eq!(
        ids,
        fixed_point_pairs(&flat.batches(), &|_| {})
            .into_iter()
            .collect()
    );
    let tested: u64 = run
        .leaf_lists
        .iter()
        .map(|(la, lb)| (la.len() * lb.len()) as u64)
        .sum();
    assert_eq!(out.pairs_tested, tested);
    assert_eq!(out.binned_at, run.cycles);
}

#[test]
fn with_local_frames_the_top_keeps_the_fine_grids_pairs_in_rust_hdl() {
    // An 18-bit grid on 16-bit pipelines: every leaf in a frame of its own
    // (a finer torus, so that most of its triangles fit a leaf's window).
    let (torus, sphere) = objects(128, 48);
    let depth = 16;
    let system = SystemConfig::new(16, 2).with_depth(depth);
    let options = SceneOptions {
        grid_bits: 18,
        depth,
        split: true,
    };
    let frames = LocalFrames { width: 16 };
    let scene = prepare_octree(&torus, &sphere, &options, &system, Some(frames)).unwrap();
    // Triangles too long for a leaf's window would go to the host, not the top.
    let binned = |kept: &[TaggedTriangle]| -> Vec<FixedTriangle> {
        kept.iter()
            .filter(|t| frames.fits_any_leaf(t))
            .map(|t| t.triangle)
            .collect()
    };
    let (a, b) = (binned(&scene.kept_a), binned(&scene.kept_b));
    let root = scene.octree.as_ref().unwrap().root.unwrap();
    let params = BinningParams {
        log_depth: 4,
        log_pipelines: 1,
        max_leaf_level: Some(frames.max_leaf_level()),
    };
    let run = run_binning(&a, &b, root, params);
    let config = top_for(&run, params, system, a.len().max(b.len()), true);
    let out = run_rusthdl(&config, &a, &b, root, params.max_leaf_level).unwrap();
    assert!(!out.overflow);
    let (pairs, _) = assert_top_as_model("local frames", &out, &run, system, &a, &b);
    assert!(pairs.len() > 100, "{} pairs", pairs.len());
    assert_eq!(out.binned_at, run.cycles);
}

#[test]
fn leaves_over_the_depth_reach_the_system_as_tiles_in_rust_hdl() {
    // Depth 4: many leaves hold more triangles of an object than a bank,
    // and a triangle comes back in several tiles of its leaf.
    let (torus, sphere) = objects(48, 32);
    let depth = 4;
    let system = SystemConfig::new(24, 2).with_depth(depth);
    let options = SceneOptions {
        grid_bits: 24,
        depth,
        split: true,
    };
    let scene = prepare_octree(&torus, &sphere, &options, &system, None).unwrap();
    let (a, b) = arrays(&scene);
    let root = scene.octree.as_ref().unwrap().root.unwrap();
    let params = BinningParams {
        log_depth: 2,
        log_pipelines: 1,
        max_leaf_level: None,
    };
    let run = run_binning(&a, &b, root, params);
    assert!(
        run.leaves
            .iter()
            .filter(|l| l.a.count > 4 || l.b.count > 4)
            .count()
            > 5
    );
    let config = top_for(&run, params, system, a.len().max(b.len()), false);
    let out = run_rusthdl(&config, &a, &b, root, None).unwrap();
    assert!(!out.overflow, "a tile over the system's depth");
    assert_top_as_model("tiles", &out, &run, system, &a, &b);
    // The tiles are the host's batches.
    assert_eq!(
        leaf_batches(depth, &run),
        scene
            .batches()
            .iter()
            .map(BatchSizes::of)
            .collect::<Vec<_>>()
    );
}

#[test]
fn the_emitted_top_gives_each_pair_once_on_a_large_scene_in_verilator() {
    // Two dense spheres overlapping deeply: over 5,000 triangles of each
    // in the common box, the system's default memory depth.
    let a = SceneObject::from_triangles("sphere a", sphere([0.0, 0.0, 0.0], 1.0, 112, 56));
    let b = SceneObject::from_triangles("sphere b", sphere([0.6, 0.2, 0.1], 0.9, 112, 56));
    let depth = 256;
    let system = SystemConfig::new(24, 2).with_depth(depth);
    let options = SceneOptions {
        grid_bits: 24,
        depth,
        split: true,
    };
    let scene = prepare_octree(&a, &b, &options, &system, None).unwrap();
    let (ta, tb) = arrays(&scene);
    assert!(
        ta.len() >= 5000 && tb.len() >= 5000,
        "{} + {}",
        ta.len(),
        tb.len()
    );
    let root = scene.octree.as_ref().unwrap().root.unwrap();
    let params = BinningParams {
        log_depth: 8,
        log_pipelines: 1,
        max_leaf_level: None,
    };
    let run = run_binning(&ta, &tb, root, params);
    let config = top_for(&run, params, system, ta.len().max(tb.len()), false);
    let model = broad_phase_cycles(system, &run);
    let out = run_emitted(
        &config,
        &ta,
        &tb,
        root,
        None,
        model + 100_000,
        Simulator::Verilator,
    )
    .unwrap();
    assert!(!out.overflow);
    let (pairs, _) = assert_top_as_model("two spheres", &out, &run, system, &ta, &tb);
    let flat = prepare(&a, &b, &options).unwrap();
    let ids: std::collections::BTreeSet<(u32, u32)> = pairs
        .iter()
        .map(|&(i, j)| (scene.kept_a[i as usize].id, scene.kept_b[j as usize].id))
        .collect();
    assert_eq!(
        ids,
        fixed_point_pairs(&flat.batches(), &|_| {})
            .into_iter()
            .collect()
    );
    assert!(ids.len() > 500, "{} pairs", ids.len());
    let tested: u64 = run
        .leaf_lists
        .iter()
        .map(|(la, lb)| (la.len() * lb.len()) as u64)
        .sum();
    assert_eq!(out.pairs_tested, tested);
    assert_eq!(out.binned_at, run.cycles);
    eprintln!(
        "two spheres: the flat system tests {} pairs",
        flat.pairs_tested()
    );
}
