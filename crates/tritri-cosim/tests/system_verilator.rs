//! The emitted system Verilog, run in Verilator with
//! testbenches/tb_collision_system.sv, against the rust-hdl model driven
//! directly. Property: on the same batches and host behaviour both return
//! the same pairs in the same order, the same cycle count and the same
//! counters, and the pairs are those of `fixed_point::intersects`, the
//! pairs without a certificate those of `certificate::certain`.

mod system_common;

use std::time::Instant;
use tritri_cosim::simulator::Simulator;
use tritri_cosim::system_harness::*;
use tritri_cosim::system_rtl::run_system_rtl;
use tritri_geom::certificate::certain;
use tritri_geom::fixed_point::intersects;
use tritri_geom::scene::reference::{pairs_where, PairDiff};
use tritri_rtl::system::stub_pipeline::{stub_certain, stub_hit};

/// Stub pipelines, tiny FIFO, slow reader, both host modes: Verilator ==
/// rust-hdl, cycle for cycle.
#[test]
fn stub_system_verilator_matches_rust_hdl() {
    let mut rng = system_common::rng(11);
    let arrays = system_common::random_arrays(&mut rng, &[(5, 4), (0, 3), (6, 7), (3, 3)], 24, 100);
    let batches = system_common::batches(&arrays);
    let expected = pairs_where(&batches, |a, b| {
        stub_hit(a.id, a.triangle[0][0], b.id, b.triangle[2][2])
    });
    let uncertain = pairs_where(&batches, |a, b| {
        !stub_certain(a.id, a.triangle[0][0], b.id, b.triangle[2][2])
    });
    assert!(!uncertain.is_empty());
    let config = SystemConfig::new(24, 2)
        .with_pipeline_latency(4)
        .with_depth(8)
        .with_result_fifo_room(2);
    for (overlap, reader) in [
        (true, ReaderBehaviour::AlwaysReady),
        (false, ReaderBehaviour::OneIn(7)),
    ] {
        let hdl = run_stub_system(config, &batches, overlap, reader);
        let rtl = run_system_rtl(
            Simulator::Verilator,
            config,
            PipelineKind::Stub,
            &batches,
            overlap,
            reader,
        )
        .unwrap();
        eprintln!(
            "stub P=2 overlap={overlap} {reader:?}: {}",
            system_common::rtl_against_hdl(&rtl, &hdl)
        );
        assert!(PairDiff::between(&expected, &hdl.pairs).is_empty());
        assert!(PairDiff::between(&uncertain, &hdl.uncertain).is_empty());
        assert_eq!(rtl, hdl);
    }
}

/// Real pipelines (W = 24, P = 2) on a small torus/sphere scene.
#[test]
fn system_verilator_matches_rust_hdl_on_a_small_scene() {
    let (a, b) = system_common::small_scene(24, 12, 6);
    let batches = tritri_geom::scene::tile(&a, &b, 16);
    let expected = pairs_where(&batches, |x, y| intersects(&x.triangle, &y.triangle));
    let uncertain = pairs_where(&batches, |x, y| !certain(&x.triangle, &y.triangle));
    let config = SystemConfig::new(24, 2)
        .with_depth(16)
        .with_result_fifo_room(4);
    let started = Instant::now();
    let hdl = run_system_with(
        config,
        PipelineKind::Parallel,
        &batches,
        true,
        ReaderBehaviour::AlwaysReady,
    )
    .unwrap();
    let hdl_seconds = started.elapsed().as_secs_f64();
    let started = Instant::now();
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
        "real P=2: {} batches, pairs {} (expected {}), uncertain {} (expected {}), cycles {} / {}, rust-hdl {hdl_seconds:.1} s, verilator (with build) {:.1} s",
        batches.len(), rtl.pairs.len(), expected.len(), rtl.uncertain.len(), uncertain.len(), rtl.cycles, hdl.cycles, started.elapsed().as_secs_f64()
    );
    assert!(PairDiff::between(&expected, &hdl.pairs).is_empty());
    assert!(PairDiff::between(&uncertain, &hdl.uncertain).is_empty());
    assert_eq!(rtl, hdl);
}
