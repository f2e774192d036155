//! The broad-phase tops' owner filter alone: on leaves whose triangles sit
//! in many leaves (long chains, many duplicates), rust-hdl, Icarus and
//! Verilator give the model's pairs at the model's edges, so the cycles a
//! walk costs ([`hit_clocks`]) are the hardware's, not only a bound.

use tritri_cosim::owner_chain_filter::{model, run_emitted, run_rusthdl};
use tritri_cosim::simulator::Simulator;
use tritri_rtl::broad_phase::owner_chain_filter::{decide, hit_clocks, streamed, Streamed};

/// Sixty leaves over twenty triangles a side, each triangle in a leaf with
/// probability 1/3, tiled at depth 3: chains ten to twenty long.
fn stream() -> Streamed {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = |n: u64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state % n
    };
    let leaves: Vec<(Vec<u32>, Vec<u32>)> = (0..60)
        .map(|_| {
            let a: Vec<u32> = (0..20).filter(|_| next(3) == 0).collect();
            let b: Vec<u32> = (0..20).filter(|_| next(3) == 0).collect();
            (a, b)
        })
        .filter(|(a, b)| !a.is_empty() && !b.is_empty())
        .collect();
    streamed(&leaves, 3, |i, j| (i * 5 + j * 3) % 7 < 2)
}

#[test]
fn each_pair_leaves_at_the_models_edge_in_rust_hdl_icarus_and_verilator() {
    let stream = stream();
    let decisions = decide(&stream.entries, &stream.hits);
    let walks = decisions.iter().filter(|d| d.1 > 0).count();
    let dropped = decisions.iter().filter(|d| d.0.is_none()).count();
    let longest = decisions.iter().map(|d| d.1).max().unwrap_or(0);
    let expected = model(&stream);
    let clocks: u64 = decisions
        .iter()
        .map(|&(owned, steps)| hit_clocks(owned.is_some(), steps))
        .sum();
    eprintln!(
        "owner chain filter: {} entries, {} hits, {walks} walks (longest {longest} steps), {dropped} dropped, {} pairs, {clocks} clocks",
        stream.entries.len(),
        stream.hits.len(),
        expected.pairs.len()
    );
    assert!(
        dropped > 100 && walks > dropped && longest >= 8,
        "the stream must exercise the walk: {walks} walks, {dropped} dropped, longest {longest}"
    );
    assert_eq!(run_rusthdl(&stream), expected, "rust-hdl");
    assert_eq!(
        run_emitted(&stream, Simulator::Icarus).unwrap(),
        expected,
        "Icarus"
    );
    assert_eq!(
        run_emitted(&stream, Simulator::Verilator).unwrap(),
        expected,
        "Verilator"
    );
}
