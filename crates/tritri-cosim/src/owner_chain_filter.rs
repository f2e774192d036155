//! Co-simulation of the broad-phase tops' owner filter alone
//! ([`tritri_rtl::broad_phase::owner_chain_filter`]): a stream of leaves'
//! entries, then their hits back to back, through the model ([`decide`] and
//! [`hit_clocks`]), the rust-hdl unit and the emitted Verilog in Icarus and
//! Verilator. Inside the tops the filter is only bounded (its clocks after
//! the system's last verdict); here each pair's edge is the model's.
//!
//! Vectors: one line per clock, five hex fields `kind f1 f2 f3 f4`: kind 0
//! pulses `start`, 1 loads a triangle of object `f1`, 2 streams an entry
//! (`object index slot leaf`), 3 offers a hit (`slot_a slot_b 0 0`) and
//! waits until the filter takes it, 4 is an idle clock. Outputs: one line
//! per owned pair, `edge index_a index_b`, `edge` the rising edge (counted
//! from reset) at which it left.

use crate::owner_filter::{filter_testbench, pairs_at_edges};
use crate::simulator::{compile, run_on_vectors, Simulator, Testbench};
use rust_hdl::prelude::*;
use tritri_rtl::broad_phase::owner_chain_filter::{
    decide, hit_clocks, OwnerChainFilter, Streamed, CHAIN_LEAF_BITS, CHAIN_SLOT_BITS,
};
use tritri_rtl::emit::owner_chain_filter_unit::emit_owner_chain_filter;
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

/// Owned pairs `(index_a, index_b)` in the order they left, and the edge
/// at which each left, counted from the edge at which the first hit was
/// offered.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ChainRun {
    pub pairs: Vec<(u32, u32)>,
    pub edges: Vec<u64>,
}

/// What the model says the filter does with the stream's hits offered back
/// to back, the reader always ready: each hit is taken [`hit_clocks`] after
/// the one before, and an owned pair leaves in its hit's last clock.
pub fn model(stream: &Streamed) -> ChainRun {
    let mut run = ChainRun::default();
    let mut taken = 0u64;
    for (owned, steps) in decide(&stream.entries, &stream.hits) {
        let clocks = hit_clocks(owned.is_some(), steps);
        if let Some(pair) = owned {
            run.pairs.push(pair);
            run.edges.push(taken + clocks - 1);
        }
        taken += clocks;
    }
    run
}

/// Triangles per object the stream's entries name (the head tables' size).
fn triangles(stream: &Streamed) -> [usize; 2] {
    let mut n = [1usize; 2];
    for &(object, index, _) in &stream.entries {
        n[object as usize] = n[object as usize].max(index as usize + 1);
    }
    n
}

/// The vector lines: start, the loads, the entries (each with its slot),
/// an idle clock (the last record is written one clock after its entry),
/// then the hits.
fn lines(stream: &Streamed) -> Vec<[u32; 5]> {
    let [na, nb] = triangles(stream);
    let mut out = vec![[0, 0, 0, 0, 0]];
    out.extend((0..na).map(|_| [1, 0, 0, 0, 0]));
    out.extend((0..nb).map(|_| [1, 1, 0, 0, 0]));
    let mut slots = [0u32; 2];
    for (k, &(object, index, leaf)) in stream.entries.iter().enumerate() {
        // The unit reads a head a clock before writing it back.
        assert!(
            k == 0 || stream.entries[k - 1].0 != object || stream.entries[k - 1].1 != index,
            "entry {k} repeats the one before"
        );
        out.push([2, object as u32, index, slots[object as usize], leaf]);
        slots[object as usize] += 1;
    }
    out.push([4, 0, 0, 0, 0]);
    out.extend(stream.hits.iter().map(|&(sa, sb)| [3, sa, sb, 0, 0]));
    out
}

/// The record tables' size for the stream.
fn slots(stream: &Streamed) -> usize {
    let b = stream.entries.iter().filter(|e| e.0).count();
    (stream.entries.len() - b).max(b).max(1)
}

/// The stream through the rust-hdl unit, the reader always ready.
pub fn run_rusthdl(stream: &Streamed) -> ChainRun {
    let [na, nb] = triangles(stream);
    let mut uut = OwnerChainFilter::new(na.max(nb), slots(stream));
    uut.connect_all();
    reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
    let lines = lines(stream);
    let first_hit = lines.iter().position(|l| l[0] == 3).unwrap_or(lines.len());
    let mut run = ChainRun::default();
    let mut next = 0;
    let mut edge = 0u64;
    // Enough edges for the slowest case: every hit walking both whole chains.
    let limit = (lines.len() + stream.hits.len() * (4 + stream.entries.len())) as u64;
    while (next < lines.len() || !uut.idle.val() || uut.out_valid.val()) && edge < limit {
        let [kind, f1, f2, f3, f4] = lines.get(next).copied().unwrap_or([4, 0, 0, 0, 0]);
        uut.start.next = kind == 0;
        uut.load_valid.next = kind == 1;
        uut.load_object.next = f1 != 0;
        uut.entry_valid.next = kind == 2;
        uut.entry_object.next = f1 != 0;
        uut.entry_index.next = (f2 as u64).into();
        uut.entry_slot.next = (f3 as u64).into();
        uut.entry_leaf.next = (f4 as u64).into();
        uut.in_valid.next = kind == 3;
        uut.in_slot_a.next = (f1 as u64).into();
        uut.in_slot_b.next = (f2 as u64).into();
        uut.in_hit.next = true;
        uut.in_certain.next = true;
        uut.out_ready.next = true;
        settle(&mut uut);
        let taken = kind != 3 || uut.in_ready.val();
        if uut.out_valid.val() {
            run.pairs.push((
                uut.out_index_a.val().index() as u32,
                uut.out_index_b.val().index() as u32,
            ));
            run.edges.push(edge - first_hit as u64);
        }
        clock_cycle(&mut uut, |u| &mut u.clock);
        if taken && next < lines.len() {
            next += 1;
        }
        edge += 1;
    }
    run
}

/// The stream through the emitted unit in `simulator`.
pub fn run_emitted(stream: &Streamed, simulator: Simulator) -> anyhow::Result<ChainRun> {
    let [na, nb] = triangles(stream);
    let design = emit_owner_chain_filter(na.max(nb), slots(stream))?;
    let longest = decide(&stream.entries, &stream.hits)
        .iter()
        .map(|&(owned, steps)| hit_clocks(owned.is_some(), steps))
        .max()
        .unwrap_or(0) as usize;
    let mut files = vec![(
        "tb_owner_chain_filter.sv".to_string(),
        testbench(&design.top, longest + 8),
    )];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_owner_chain_filter".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let lines = lines(stream);
    let first_hit = lines.iter().position(|l| l[0] == 3).unwrap_or(lines.len()) as u64;
    let vectors: String = lines
        .iter()
        .map(|[k, a, b, c, d]| format!("{k:x} {a:x} {b:x} {c:x} {d:x}\n"))
        .collect();
    let (text, _) = run_on_vectors(&compiled, "owner-chain-filter-run", &vectors, &[])?;
    let (pairs, edges) = pairs_at_edges(&text, first_hit, "owner chain filter")?;
    Ok(ChainRun { pairs, edges })
}

/// The testbench: one line per clock, a hit held until taken; the reader
/// always ready; every owned pair written with its edge.
fn testbench(top: &str, drain: usize) -> String {
    let s1 = CHAIN_SLOT_BITS - 1;
    let l1 = CHAIN_LEAF_BITS - 1;
    let declarations = format!(
        "\
    reg [2:0] kind = 3'd4;
    wire in_ready, out_valid, out_hit, out_certain, idle, overflow;
    wire [31:0] out_index_a, out_index_b;
    {top} dut (
        .clock(clock), .reset(reset), .start(in_valid && kind == 3'd0),
        .load_valid(in_valid && kind == 3'd1), .load_object(f1[0]),
        .entry_valid(in_valid && kind == 3'd2), .entry_object(f1[0]), .entry_index(f2[17:0]),
        .entry_slot(f3[{s1}:0]), .entry_leaf(f4[{l1}:0]),
        .in_valid(in_valid && kind == 3'd3), .in_ready(in_ready), .in_slot_a(f1), .in_slot_b(f2),
        .in_hit(1'b1), .in_certain(1'b1),
        .out_valid(out_valid), .out_ready(1'b1), .out_index_a(out_index_a), .out_index_b(out_index_b),
        .out_hit(out_hit), .out_certain(out_certain), .idle(idle), .overflow(overflow)
    );
"
    );
    filter_testbench(
        "tb_owner_chain_filter",
        &declarations,
        ["out_index_a", "out_index_b"],
        "3'd3",
        drain,
    )
}
