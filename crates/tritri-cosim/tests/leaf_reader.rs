//! A leaf's lists read back from external memory: the clock-exact model,
//! the rust-hdl unit and the emitted Verilog in Verilator and Icarus give
//! the same stream (the header, A's entries, B's, each with its index and
//! vertices) in the same clocks, against an ideal memory and one with
//! random stalls, with the stream's reader ready always or seven clocks in
//! ten; the stream is the lists', entry for entry.

mod list_scene;

use list_scene::scene;
use tritri_cosim::leaf_reader::{
    run_model, run_rusthdl, run_simulator, LeafCase, LeafOutcome, StreamWord,
};
use tritri_cosim::simulator::Simulator;
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::broad_phase::list_pass_machine::ListPassConfig;

fn case(grid_bits: usize, data_bits: usize, params: MemoryParams, ready_tenths: u64) -> LeafCase {
    let (lists, root) = scene(grid_bits, 24, 16);
    LeafCase {
        config: ListPassConfig {
            grid_bits,
            data_bits,
            max_read_burst: 16,
            outstanding: 4,
        },
        params,
        cell: root,
        lists,
        ready_tenths,
        limit: 1_000_000,
    }
}

/// The model, checked against the lists, and each engine against it.
fn all_engines(case: &LeafCase, rusthdl: bool, simulators: &[Simulator]) -> LeafOutcome {
    let model = run_model(case).unwrap();
    assert_eq!(model.faults, 0, "model: protocol faults");
    assert!(!model.error, "model: error response");
    let words: Vec<StreamWord> = model.words.iter().map(|(_, w)| w.clone()).collect();
    assert_eq!(
        words,
        case.expected_words(),
        "model: the stream is not the lists'"
    );
    let clocks: Vec<u64> = model.words.iter().map(|(t, _)| *t).collect();
    assert!(
        clocks.windows(2).all(|w| w[0] < w[1]),
        "two words in a clock"
    );
    assert!(model.read_cycles <= model.cycles);
    if rusthdl {
        assert_eq!(
            run_rusthdl(case).unwrap(),
            model,
            "rust-hdl against the model"
        );
    }
    for &sim in simulators {
        assert_eq!(
            run_simulator(sim, case).unwrap(),
            model,
            "{sim:?} against the model"
        );
    }
    let entries = case.lists[0].len() + case.lists[1].len();
    eprintln!(
        "{entries} entries, {}-bit port, ready {}/10: read in {} clocks, streamed in {} ({} stalled); \
         model{}{}",
        case.config.data_bits,
        case.ready_tenths,
        model.read_cycles,
        model.cycles,
        model.stalled,
        if rusthdl { " = rust-hdl" } else { "" },
        simulators.iter().map(|s| format!(" = {s:?}")).collect::<String>()
    );
    model
}

#[test]
fn a_leaf_streams_as_its_lists_in_every_engine() {
    let c = case(24, 64, MemoryParams::ideal(8, 24), 10);
    let out = all_engines(&c, true, &[Simulator::Verilator, Simulator::Icarus]);
    // An ideal 64-bit port delivers a beat a clock: the leaf takes its
    // beats, the two lists' latencies and a few clocks more.
    let beats = (c.lists[0].len() + c.lists[1].len()) as u64 * c.config.beats_per_entry();
    assert!(
        out.cycles >= beats,
        "{} clocks, under {beats} beats",
        out.cycles
    );
    assert!(
        out.cycles <= beats + 120,
        "{} clocks, over {beats} + 120",
        out.cycles
    );
}

#[test]
fn stalls_and_a_slow_reader_change_the_clocks_not_the_stream() {
    let ideal = case(16, 128, MemoryParams::ideal(16, 24), 10);
    let base = run_model(&ideal).unwrap();
    let slow = LeafCase {
        params: ideal.params.with_stalls(20, 5),
        ready_tenths: 7,
        ..ideal.clone()
    };
    let out = all_engines(&slow, true, &[Simulator::Verilator]);
    assert!(out.stalled > 0, "no clock stalled");
    assert!(
        out.cycles > base.cycles,
        "stalls and back-pressure cost no clocks"
    );
    // The reader takes 7 clocks in 10: the stream cannot go faster.
    let words = out.words.len() as u64;
    assert!(
        out.cycles * 7 / 10 + 1 >= words,
        "{words} words in {} clocks",
        out.cycles
    );
}

#[test]
fn a_leaf_with_an_empty_list_sends_its_header_and_the_other_list() {
    let mut c = case(24, 256, MemoryParams::ideal(32, 24), 10);
    c.lists[1].clear();
    let out = all_engines(&c, true, &[]);
    assert_eq!(out.words.len(), 1 + c.lists[0].len());
}
