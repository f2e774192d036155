//! The octree engine's core circuit in hardware: planes against 16^3 to
//! 64^3 grids through the rust-hdl model and the emitted Verilog in Icarus
//! and Verilator give the cycle model's records at its edges and its cycle
//! count, and those records describe exactly the software model's
//! half-space and crossed voxels. Planes through voxel corners, along
//! edges and faces (small integer normals, zeros among them), planes that
//! miss the grid, and a reader that stalls.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_cosim::plane_traversal::{run_emitted, run_rusthdl};
use tritri_cosim::simulator::Simulator;
use tritri_geom::octree::plane::{classify_plane, traversal_schedule};
use tritri_rtl::emit::plane_traversal_unit::PlaneInputs;
use tritri_rtl::octree::plane_traversal::STACK_ADDRESS_BITS;

fn planes(count: usize, seed: u64) -> Vec<(u32, [i64; 3], i64)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = vec![
        (4, [0, 0, 1], 8),
        (4, [1, 1, 1], 24),
        (5, [3, -5, 7], 40),
        (4, [1, 0, 0], -3),
        (4, [2, 2, 2], 1000),
        (6, [-7, 3, 11], 100),
    ];
    while out.len() < count {
        let level = rng.gen_range(3..=5);
        let n = 1i64 << level;
        let normal = [0; 3].map(|_: i64| rng.gen_range(-4..=4));
        let normal = if normal == [0; 3] { [0, 1, 0] } else { normal };
        out.push((level, normal, rng.gen_range(-2 * n..=6 * n)));
    }
    out
}

#[test]
fn rusthdl_equals_the_cycle_model_and_the_software_model() {
    for (level, normal, d) in planes(40, 1995) {
        let model = traversal_schedule(level, normal, d);
        assert!(
            model.stack_depth < 1 << STACK_ADDRESS_BITS,
            "the stack's RAM holds the traversal"
        );
        let plane = PlaneInputs::new(level, normal, d).unwrap();
        let hardware = run_rusthdl(&plane, |_| true);
        assert_eq!(hardware.records, model.records, "{level} {normal:?} {d}");
        assert_eq!(hardware.edges, model.edges, "{level} {normal:?} {d}");
        assert_eq!(hardware.cycles, model.cycles, "{level} {normal:?} {d}");
        let software = classify_plane(level, normal, d);
        assert_eq!(
            model.half_space(level),
            software.half_space.to_voxels(),
            "{level} {normal:?} {d}"
        );
        assert_eq!(model.crossed_voxels(), software.crossed_voxels);
        // A reader ready one edge in three: the same records, later.
        let mut stalled = run_rusthdl(&plane, |e| e % 3 == 2);
        let mut records = model.records.clone();
        stalled.records.sort();
        records.sort();
        assert_eq!(stalled.records, records, "{level} {normal:?} {d} (stalled)");
        assert!(stalled.cycles >= model.cycles);
    }
}

#[test]
fn emitted_verilog_equals_the_cycle_model() {
    let planes = planes(12, 512);
    let inputs: Vec<PlaneInputs> = planes
        .iter()
        .map(|&(l, n, d)| PlaneInputs::new(l, n, d).unwrap())
        .collect();
    for simulator in [Simulator::Icarus, Simulator::Verilator] {
        let runs = run_emitted(&inputs, simulator).unwrap();
        for ((level, normal, d), run) in planes.iter().zip(runs) {
            let model = traversal_schedule(*level, *normal, *d);
            assert_eq!(
                run.records, model.records,
                "{simulator:?} {level} {normal:?} {d}"
            );
            assert_eq!(
                run.edges, model.edges,
                "{simulator:?} {level} {normal:?} {d}"
            );
            assert_eq!(
                run.cycles, model.cycles,
                "{simulator:?} {level} {normal:?} {d}"
            );
        }
    }
}

/// The traversal's records through the voxel fill, in rust-hdl and the
/// emitted Verilog: the memory holds exactly the software model's
/// half-space, written a word per clock (the model's word count, one
/// clock more per record without a child to fill).
#[test]
fn the_voxel_fill_writes_the_half_space_a_word_per_clock() {
    use tritri_cosim::voxel_fill::{fill_emitted, fill_rusthdl};
    let cases = [
        (4, [1, 2, 3], 40),
        (6, [3, -5, 7], 100),
        (7, [0, 0, 1], 64),
        (7, [1, 1, 1], 150),
        (3, [2, 2, 2], 1000),
    ];
    for (level, normal, d) in cases {
        let model = traversal_schedule(level, normal, d);
        let expected = classify_plane(level, normal, d).half_space.to_voxels();
        // Records without a child to fill, before the last that has one.
        let last_full = model.records.iter().rposition(|r| r.full != 0).unwrap_or(0);
        let empty_records = model.records[..last_full]
            .iter()
            .filter(|r| r.full == 0)
            .count() as u64;
        let run = fill_rusthdl(level, &model.records).unwrap();
        assert_eq!(run.words, expected.words(), "{level} {normal:?} {d}");
        assert_eq!(run.writes, model.fill_words(64), "{level} {normal:?} {d}");
        assert_eq!(
            run.last_edge,
            run.writes + empty_records,
            "{level} {normal:?} {d}: one write per clock"
        );
        for simulator in [Simulator::Icarus, Simulator::Verilator] {
            let emitted = fill_emitted(level, &model.records, simulator).unwrap();
            assert_eq!(
                (emitted.words.as_slice(), emitted.writes),
                (expected.words(), run.writes),
                "{simulator:?} {level} {normal:?} {d}"
            );
        }
    }
}

/// A traversal built with a stack of 4 entries: its overflow flag rises
/// exactly for the planes whose traversal the cycle model says needs more,
/// and the others give the model's records.
#[test]
fn the_overflow_flag_rises_exactly_when_the_stack_is_too_small() {
    use tritri_cosim::plane_traversal::run_rusthdl_with_stack;
    let (mut over, mut within) = (0, 0);
    for (level, normal, d) in planes(60, 2026) {
        let model = traversal_schedule(level, normal, d);
        let plane = PlaneInputs::new(level, normal, d).unwrap();
        let (run, overflow) = run_rusthdl_with_stack::<2>(&plane, |_| true);
        assert_eq!(
            overflow,
            model.stack_depth > 4,
            "{level} {normal:?} {d}: stack depth {}",
            model.stack_depth
        );
        if overflow {
            over += 1;
        } else {
            within += 1;
            assert_eq!(
                (run.records, run.edges, run.cycles),
                (model.records, model.edges, model.cycles),
                "{level} {normal:?} {d}"
            );
        }
    }
    eprintln!("{over} planes overflow a 4-entry stack, {within} fit");
    assert!(over > 0 && within > 0);
}
