//! A cell's pass over lists in external memory: the clock-exact model, the
//! rust-hdl unit and the emitted Verilog in Icarus and Verilator read a
//! real scene's lists and write the same child lists in the same clocks,
//! against an ideal memory and a memory with random stalls; the child
//! lists are the software classifier's, in read order; no burst breaks the
//! protocol's rules; and a child's list, written by one pass, is the next
//! level's input.

mod list_scene;

use list_scene::scene as scene_on;
use tritri_cosim::list_pass::{run_model, run_rusthdl, run_simulator, PassCase, PassOutcome};
use tritri_cosim::simulator::Simulator;
use tritri_geom::octree::cell::Cell;
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::broad_phase::classify_lane::LANE_LATENCY;
use tritri_rtl::broad_phase::list_entry::ENTRY_BYTES;
use tritri_rtl::broad_phase::list_pass_machine::{child_lists, ListPassConfig};

const GRID_BITS: usize = 24;

/// The torus and sphere's lists on the grid of these tests.
fn scene(torus_segments: usize, sphere_segments: usize) -> ([Vec<[u8; ENTRY_BYTES]>; 2], Cell) {
    scene_on(GRID_BITS, torus_segments, sphere_segments)
}

fn case(
    data_bits: usize,
    params: MemoryParams,
    lists: [Vec<[u8; ENTRY_BYTES]>; 2],
    cell: Cell,
) -> PassCase {
    PassCase {
        config: ListPassConfig {
            grid_bits: GRID_BITS,
            data_bits,
            max_read_burst: 16,
            outstanding: 4,
        },
        params,
        cell,
        lists,
        limit: 2_000_000,
    }
}

/// The pass's checks against the software answer: no faults, no error,
/// each child's list the classifier's, nothing else in memory touched.
fn assert_classified(case: &PassCase, out: &PassOutcome, engine: &str) {
    assert_eq!(out.faults, 0, "{engine}: protocol faults");
    assert!(!out.error, "{engine}: error response");
    let lists = case
        .lists
        .each_ref()
        .map(|l| l.iter().map(|e| e.to_vec()).collect::<Vec<_>>());
    let expected = child_lists(GRID_BITS, &case.cell, [&lists[0], &lists[1]]);
    let got = case
        .child_lists(out)
        .unwrap_or_else(|e| panic!("{engine}: {e:#}"));
    for (i, (g, e)) in got.iter().zip(&expected).enumerate() {
        assert_eq!(g.len(), e.len(), "{engine}: child {i}'s entries");
        if let Some(at) = (0..e.len()).find(|&at| g[at] != e[at]) {
            panic!("{engine}: child {i}'s entry {at} differs from the classifier's");
        }
    }
    // Every A entry meets at least one child of its cell.
    let written_a: u64 = out.child_counts[..8].iter().sum();
    let read_a = case.lists[0].len() as u64;
    assert!(
        written_a >= read_a,
        "{engine}: {written_a} A entries written, {read_a} read"
    );
}

/// `out` equals the model's outcome; the first differing byte is named.
fn assert_same(out: &PassOutcome, model: &PassOutcome, engine: &str) {
    let counts = |o: &PassOutcome| (o.cycles, o.stalled, o.error, o.faults, o.child_counts);
    assert_eq!(
        counts(out),
        counts(model),
        "{engine} against the model: (cycles, stalled, error, faults, child counts)"
    );
    if let Some(i) = (0..model.bytes.len()).find(|&i| out.bytes.get(i) != model.bytes.get(i)) {
        panic!("{engine}: byte {i:#x} differs from the model's");
    }
    assert_eq!(out.bytes.len(), model.bytes.len(), "{engine}: memory size");
}

/// The model, checked, and each engine in `engines` against it.
fn all_engines(case: &PassCase, rusthdl: bool, simulators: &[Simulator]) -> PassOutcome {
    let model = run_model(case).unwrap();
    assert_classified(case, &model, "model");
    if rusthdl {
        assert_same(&run_rusthdl(case).unwrap(), &model, "rust-hdl");
    }
    for &sim in simulators {
        assert_same(
            &run_simulator(sim, case).unwrap(),
            &model,
            &format!("{sim:?}"),
        );
    }
    let entries = case.lists[0].len() + case.lists[1].len();
    let written: u64 = model.child_counts.iter().sum();
    eprintln!(
        "{entries} entries of {} bits a beat in, {written} out: {} clocks ({} stalled); \
         model{}{}",
        case.config.data_bits,
        model.cycles,
        model.stalled,
        if rusthdl { " = rust-hdl" } else { "" },
        simulators
            .iter()
            .map(|s| format!(" = {s:?}"))
            .collect::<String>()
    );
    model
}

/// Beats the pass moves: each entry read once, each written once per child.
fn beats(case: &PassCase, out: &PassOutcome) -> u64 {
    let per_entry = case.config.beats_per_entry();
    let read = (case.lists[0].len() + case.lists[1].len()) as u64;
    (read + out.child_counts.iter().sum::<u64>()) * per_entry
}

#[test]
fn a_root_pass_over_a_real_scene_is_the_classifier_in_every_engine() {
    let (lists, root) = scene(24, 16);
    let c = case(64, MemoryParams::ideal(8, 24), lists, root);
    let out = all_engines(&c, true, &[Simulator::Verilator, Simulator::Icarus]);
    // Reads and writes share no channel, so the pass takes about the larger
    // of its read and write beats; the bound is their sum and the latencies.
    let bound = beats(&c, &out) + 200;
    assert!(out.cycles <= bound, "{} clocks, over {bound}", out.cycles);
}

#[test]
fn random_stalls_change_the_clocks_but_not_the_lists() {
    let (lists, root) = scene(48, 32);
    let ideal = case(64, MemoryParams::ideal(8, 24), lists, root);
    let base = run_model(&ideal).unwrap();
    let stalls = PassCase {
        params: ideal.params.with_stalls(20, 11),
        ..ideal.clone()
    };
    let out = all_engines(&stalls, false, &[Simulator::Verilator]);
    assert!(out.stalled > 0, "no clock stalled");
    assert!(out.cycles > base.cycles, "stalls cost no clocks");
    assert_eq!(out.child_counts, base.child_counts);
    // The bound of the model: every beat at its port's pace, each stalled
    // clock on top.
    let bound = beats(&ideal, &base) + out.stalled + 200;
    assert!(out.cycles <= bound, "{} clocks, over {bound}", out.cycles);
}

#[test]
fn a_wide_port_reads_an_entry_a_clock() {
    let (lists, root) = scene(48, 32);
    let c = case(256, MemoryParams::ideal(32, 24), lists, root);
    let out = all_engines(&c, true, &[Simulator::Verilator]);
    let per_child_beats: u64 = out.child_counts.iter().sum();
    let floor = per_child_beats.max((c.lists[0].len() + c.lists[1].len()) as u64);
    assert!(out.cycles >= floor, "{} clocks, under {floor}", out.cycles);
    assert!(
        out.cycles <= floor + 300,
        "{} clocks, over {floor} + 300",
        out.cycles
    );
}

#[test]
fn a_child_list_written_by_one_pass_is_the_next_levels_input() {
    let (lists, root) = scene(24, 16);
    let c = case(64, MemoryParams::ideal(8, 24), lists, root);
    let first = run_model(&c).unwrap();
    let children = c.child_lists(&first).unwrap();
    // The child with the most entries of both objects.
    let octant = (0..8)
        .max_by_key(|&o| children[o].len().min(children[8 + o].len()))
        .unwrap();
    let list = |i: usize| -> Vec<[u8; ENTRY_BYTES]> {
        children[i]
            .iter()
            .map(|e| e.as_slice().try_into().unwrap())
            .collect()
    };
    let child = root.child(octant);
    let next = case(64, c.params, [list(octant), list(8 + octant)], child);
    all_engines(&next, true, &[]);
}

/// A pass's clocks beyond its beats: one entry of each object, so nearly
/// all of it is the memory's latencies, the lane's and the flush. The
/// binning over external memory pays it once per split cell
/// (docs/axi-port.md).
#[test]
fn a_pass_of_one_entry_each_costs_its_latencies() {
    let (lists, root) = scene(24, 16);
    let one = [vec![lists[0][0]], vec![lists[1][0]]];
    let latency = 24;
    let c = case(64, MemoryParams::ideal(8, latency), one, root);
    let out = all_engines(&c, true, &[Simulator::Verilator]);
    // At least: A's read (its latency, its beats), then B's (the reader
    // takes B's region once A's beats have left it), the lane, the flush
    // of the sixteen children (a clock each) and the last write's
    // response.
    let per_entry = c.config.beats_per_entry();
    let floor = 2 * (latency + per_entry) + LANE_LATENCY as u64 + 16 + latency;
    eprintln!("one entry each: {} clocks, floor {floor}", out.cycles);
    assert!(out.cycles >= floor, "{} clocks, under {floor}", out.cycles);
    assert!(
        out.cycles <= floor + 40,
        "{} clocks, over {floor} + 40",
        out.cycles
    );
}

/// A B entry goes only to children that hold an A entry: with A's list cut
/// to the entries that meet octant 0 alone, B's entries reach child 0 and
/// no other, in every engine.
#[test]
fn b_entries_go_only_to_the_children_a_reached() {
    use tritri_geom::octree::triangle_cell::{TriangleCellTest, BROAD_PHASE_MARGIN};
    use tritri_rtl::broad_phase::list_entry::unpack;
    let (lists, root) = scene(24, 16);
    let mask = |e: &[u8; ENTRY_BYTES]| {
        let (_, t) = unpack(e, GRID_BITS);
        TriangleCellTest::widened(&t, BROAD_PHASE_MARGIN).children_of_cell(&root)
    };
    let a: Vec<_> = lists[0].iter().copied().filter(|e| mask(e) == 1).collect();
    let b_meeting = |o: usize| lists[1].iter().filter(|e| mask(e) >> o & 1 == 1).count() as u64;
    assert!(
        !a.is_empty() && (1..8).any(|o| b_meeting(o) > 0),
        "a case that cuts nothing"
    );
    let c = case(64, MemoryParams::ideal(8, 24), [a, lists[1].clone()], root);
    let out = all_engines(&c, true, &[Simulator::Verilator]);
    assert_eq!(out.child_counts[8], b_meeting(0));
    assert!(
        out.child_counts[9..].iter().all(|&n| n == 0),
        "{:?}",
        out.child_counts
    );
}
