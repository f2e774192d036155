//! The system whose pipelines test their rare pairs on the shared unit
//! (`PipelineKind::Shared`, `tritri gen --system --rare-cases shared`), on
//! batches full of coplanar and degenerate pairs. Properties, in rust-hdl
//! and in the emitted Verilog in Verilator:
//!
//! * the pairs are those of `fixed_point::intersects`, the pairs without a
//!   certificate those of `certificate::certain`;
//! * on one batch, the clocks it stalls are exactly those
//!   `system::rare_case_model` counts for it, and the run takes the cycle
//!   model's cycles plus those; over several batches, with the host
//!   writing on, too;
//! * Verilator and rust-hdl agree cycle for cycle.

mod system_common;

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use tritri_cosim::simulator::Simulator;
use tritri_cosim::system_harness::*;
use tritri_cosim::system_rtl::run_system_rtl;
use tritri_geom::certificate::certain;
use tritri_geom::fixed_point::{intersects, FixedTriangle};
use tritri_geom::scene::reference::{pairs_where, PairDiff};
use tritri_geom::scene::{Batch, TaggedTriangle};
use tritri_rtl::system::rare_case_model::rare_case_cost;

/// Small integer triangles: most on the plane z = x (coplanar pairs with
/// each other), some collinear (degenerate, many pairs of segments), the
/// rest anywhere near.
fn rare_triangles(rng: &mut ChaCha8Rng, n: usize, first_id: u32) -> Vec<TaggedTriangle> {
    (0..n)
        .map(|i| {
            let mut c = || rng.gen_range(-4i64..=4);
            let triangle: FixedTriangle = match i % 5 {
                0..=2 => [0; 3].map(|_| {
                    let (x, y) = (c(), c());
                    [x, y, x]
                }),
                3 => {
                    let (p, d) = ([c(), c(), c()], [c(), c(), c()]);
                    [0, 1, 2].map(|k: i64| [p[0] + k * d[0], p[1] + k * d[1], p[2] + k * d[2]])
                }
                _ => [0; 3].map(|_| [c(), c(), c()]),
            };
            TaggedTriangle {
                id: first_id + i as u32,
                triangle,
            }
        })
        .collect()
}

fn arrays(seed: u64, shapes: &[(usize, usize)]) -> Vec<system_common::Arrays> {
    let mut rng = system_common::rng(seed);
    shapes
        .iter()
        .enumerate()
        .map(|(k, &(a, b))| {
            let first = 1000 * k as u32;
            (
                rare_triangles(&mut rng, a, first),
                rare_triangles(&mut rng, b, first + 500),
            )
        })
        .collect()
}

/// Result FIFO words above the reserve, more than these batches' pairs:
/// its back-pressure never holds the read side, so every stall is a rare
/// pair's.
const FIFO_ROOM: usize = 256;

/// The pairs and uncertain pairs are the models'; returns the run.
fn run_and_check(
    config: SystemConfig,
    batches: &[Batch],
    overlap: bool,
    reader: ReaderBehaviour,
) -> SystemResult {
    let expected = pairs_where(batches, |x, y| intersects(&x.triangle, &y.triangle));
    let uncertain = pairs_where(batches, |x, y| !certain(&x.triangle, &y.triangle));
    let r = run_system_with(config, PipelineKind::Shared, batches, overlap, reader).unwrap();
    assert!(PairDiff::between(&expected, &r.pairs).is_empty());
    assert!(PairDiff::between(&uncertain, &r.uncertain).is_empty());
    r
}

/// One batch at a time: stalls are the rare-case model's count, cycles the
/// cycle model's plus the stalls.
#[test]
fn one_batch_stalls_exactly_as_the_rare_case_model_counts() {
    for (p, shape) in [(1, (7, 40)), (2, (9, 40)), (4, (6, 33))] {
        let arrays = arrays(p as u64, &[shape]);
        let batches = system_common::batches(&arrays);
        let config = SystemConfig::new(16, p)
            .with_depth(64)
            .with_result_fifo_room(FIFO_ROOM);
        let r = run_and_check(config, &batches, false, ReaderBehaviour::AlwaysReady);
        let cost = rare_case_cost(p, &batches);
        let sizes: Vec<_> = batches.iter().map(BatchSizes::of).collect();
        let model = system_cycles(config, &sizes, false, ReaderBehaviour::AlwaysReady);
        eprintln!(
            "P={p}, {shape:?}: {} pairs, {} rare ({} coplanar), stalls {} (model {}), cycles {} (model {model} + stalls)",
            r.pairs_tested, cost.coplanar + cost.segments, cost.coplanar, r.stall_cycles, cost.stall_cycles, r.cycles
        );
        assert!(cost.stall_cycles > 50, "the batch keeps the unit busy");
        assert_eq!(r.stall_cycles, cost.stall_cycles);
        assert_eq!(r.cycles, model + cost.stall_cycles);
    }
}

/// Several batches, the host writing on (overlap): with a reader always
/// ready and a result FIFO that never fills, the stalls are the model's
/// count; with a result FIFO of two words above its reserve and a slow
/// reader, its back-pressure and the rare pairs' holds mix. Either way
/// Verilator running the emitted system equals rust-hdl.
///
/// The stall counter counts every clock the read side holds with work to
/// do, the FIFO's back-pressure included: these batches' small triangles
/// hit often, two pairs in a word drain in two clocks, and the default
/// FIFO (64 words, `L` of them in reserve) filled at `L = 40`, 7 clocks
/// above the model on the first batch. Hence the room here.
#[test]
fn batches_in_verilator_equal_rust_hdl() {
    let arrays = arrays(7, &[(5, 30), (0, 4), (8, 25), (3, 3)]);
    let batches = system_common::batches(&arrays);
    let config = SystemConfig::new(16, 2).with_depth(32);
    for (config, reader) in [
        (
            config.with_result_fifo_room(FIFO_ROOM),
            ReaderBehaviour::AlwaysReady,
        ),
        (config.with_result_fifo_room(2), ReaderBehaviour::OneIn(5)),
    ] {
        let hdl = run_and_check(config, &batches, true, reader);
        let bound = rare_case_cost(2, &batches).stall_cycles;
        let rtl = run_system_rtl(
            Simulator::Verilator,
            config,
            PipelineKind::Shared,
            &batches,
            true,
            reader,
        )
        .unwrap();
        eprintln!(
            "P=2, 4 batches, {reader:?}: {} (the model: {bound})",
            system_common::rtl_against_hdl(&rtl, &hdl)
        );
        if reader == ReaderBehaviour::AlwaysReady {
            assert!(hdl.stall_cycles > 50);
            assert_eq!(hdl.stall_cycles, bound);
        } else {
            assert!(hdl.stall_cycles > bound);
        }
        assert_eq!(rtl, hdl);
    }
}

/// The same system with the ECP5 primitives (`tritri gen --dsp ecp5`, the
/// default with `--synth ecp5`): the multipliers on MULT18X18D and every
/// triangle memory and result FIFO column on DP16KD with its read and
/// output registers, each primitive run on its simulation model. With a
/// small result FIFO and a slow reader the read side holds often (both
/// memory stages hold on `read_enable`), the FIFO fills and drains, and
/// with the rare pairs the pipelines hold too: Verilator equals rust-hdl
/// cycle for cycle.
#[test]
fn batches_on_ecp5_primitives_in_verilator_equal_rust_hdl() {
    use tritri_cosim::simulator::compile;
    use tritri_cosim::system_rtl::{run_compiled_system, system_testbench, SystemRunOptions};
    use tritri_rtl::emit::block_ram_mapping::ECP5_DP16KD_MODEL_FILE;
    use tritri_rtl::emit::dsp_mapping::{MultiplierMapping, ECP5_MODEL_FILE};
    use tritri_rtl::system::dual_port_ram::OUTPUT_REGISTER_SHAPE;
    use tritri_rtl::system::system_unit::emit_system_with;

    let arrays = arrays(7, &[(5, 30), (0, 4), (8, 25), (3, 3)]);
    let batches = system_common::batches(&arrays);
    let config = SystemConfig::new(16, 2)
        .with_depth(32)
        .with_result_fifo_room(2);
    let reader = ReaderBehaviour::OneIn(5);
    let hdl = run_and_check(config, &batches, true, reader);
    let design = emit_system_with(config, PipelineKind::Shared, MultiplierMapping::Ecp5).unwrap();
    assert!(design.file(ECP5_MODEL_FILE).is_some());
    assert!(design.file(ECP5_DP16KD_MODEL_FILE).is_some());
    // The column modules of the triangle memories (16-bit coordinates,
    // 32-bit ids) and of the result FIFO (16-bit masks, 32-bit ids) are on
    // DP16KD, the ids on two blocks; no memory with an output register is
    // left to inference.
    let columns: Vec<(&str, usize)> = design
        .verilog_files()
        .filter(|f| f.contents.contains(OUTPUT_REGISTER_SHAPE))
        .map(|f| (f.path.as_str(), f.contents.matches("DP16KD #(").count()))
        .collect();
    assert_eq!(columns.len(), 4, "{columns:?}");
    for (path, blocks) in &columns {
        let expected = if path.contains("_w32_") { 2 } else { 1 };
        assert_eq!(*blocks, expected, "{columns:?}");
    }
    let compiled = compile(Simulator::Verilator, &system_testbench(&design, 16, false)).unwrap();
    let rtl = run_compiled_system(
        &compiled,
        16,
        &batches,
        true,
        reader,
        SystemRunOptions::default(),
    )
    .unwrap();
    eprintln!(
        "ECP5 primitives, P=2, 4 batches, {reader:?}: {}",
        system_common::rtl_against_hdl(&rtl, &hdl)
    );
    assert!(hdl.stall_cycles > 0);
    assert_eq!(rtl, hdl);
}
