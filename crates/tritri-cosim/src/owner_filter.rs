//! Co-simulation of the owner filter ([`tritri_rtl::broad_phase::owner_filter`]):
//! the hits of an octree schedule's leaves, as slots, through the software
//! model (`tritri_geom::scene::owner_slots`), the rust-hdl model and the
//! emitted Verilog in Icarus and Verilator.
//!
//! Vectors: one line per cycle, five hex fields `kind f1 f2 f3 f4`: kind 0
//! writes A's slot table (`slot id leaf first`), kind 1 B's, kind 2 offers
//! a hit (`slot_a slot_b 0 0`) and waits until the filter takes it. Every
//! table write comes before the first hit. Outputs: one line per owned
//! pair, `edge id_a id_b`, `edge` the rising edge (counted from reset) at
//! which it left.

use crate::simulator::{
    compile, run_on_vectors, vector_testbench, Simulator, Testbench, VectorTestbench,
};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::scene::owner_slots::{OwnerSlots, Slot};
use tritri_rtl::broad_phase::owner_filter::{pair_cycles, slot_word, OwnerFilter, SLOT_BITS};
use tritri_rtl::emit::owner_filter_unit::emit_owner_filter;
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

/// Owned pairs `(id_a, id_b)` in the order they left, and the edge at
/// which each left, counted from the edge that took the first hit.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct OwnerRun {
    pub pairs: Vec<(u32, u32)>,
    pub edges: Vec<u64>,
}

/// What the model says the filter does with `hits` offered back to back.
pub fn expected(slots: &OwnerSlots, hits: &[(u32, u32)]) -> OwnerRun {
    model(slots, hits).0
}

/// [`expected`], and the edge at which the filter has finished the last
/// hit (its cycles for the hits back to back).
pub fn model(slots: &OwnerSlots, hits: &[(u32, u32)]) -> (OwnerRun, u64) {
    let decisions: Vec<_> = hits.iter().map(|&(sa, sb)| slots.decide(sa, sb)).collect();
    let (edges, busy) = pair_cycles(decisions.iter().map(|d| (d.owner, d.comparisons)));
    let pairs = hits
        .iter()
        .zip(&decisions)
        .filter(|(_, d)| d.owner)
        .map(|(&(sa, sb), _)| slots.ids(sa, sb))
        .collect();
    (OwnerRun { pairs, edges }, busy)
}

fn word(slot: &Slot) -> Bits<{ tritri_rtl::broad_phase::owner_filter::SLOT_WORD_BITS }> {
    slot_word(slot.id, slot.leaf, slot.first)
}

/// The hits through the rust-hdl model; the reader is ready in cycles
/// where `reader_ready(edge)` is true (always, for cycles to compare).
pub fn run_rusthdl(
    slots: &OwnerSlots,
    hits: &[(u32, u32)],
    reader_ready: impl Fn(u64) -> bool,
) -> OwnerRun {
    let mut uut = OwnerFilter::new(slots.a.len().max(1), slots.b.len().max(1));
    uut.connect_all();
    reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
    let s = |x: u32| -> Bits<SLOT_BITS> { (x as u64).into() };
    for (k, slot) in slots.a.iter().enumerate() {
        uut.write_a_enable.next = true;
        uut.write_a_slot.next = s(k as u32);
        uut.write_a_word.next = word(slot);
        clock_cycle(&mut uut, |u| &mut u.clock);
    }
    uut.write_a_enable.next = false;
    for (k, slot) in slots.b.iter().enumerate() {
        uut.write_b_enable.next = true;
        uut.write_b_slot.next = s(k as u32);
        uut.write_b_word.next = word(slot);
        clock_cycle(&mut uut, |u| &mut u.clock);
    }
    uut.write_b_enable.next = false;
    let mut run = OwnerRun::default();
    let mut next = 0;
    let mut edge = 0u64;
    // Enough edges for the slowest case: every hit merging both whole lists.
    let limit = 8 + hits.len() as u64 * (4 + slots.a.len() as u64 + slots.b.len() as u64);
    while (next < hits.len() || !uut.in_ready.val() || uut.out_valid.val()) && edge < limit {
        uut.in_valid.next = next < hits.len();
        if let Some(&(sa, sb)) = hits.get(next) {
            uut.in_slot_a.next = s(sa);
            uut.in_slot_b.next = s(sb);
        }
        uut.out_ready.next = reader_ready(edge);
        settle(&mut uut);
        let taken = uut.in_valid.val() && uut.in_ready.val();
        if uut.out_valid.val() && uut.out_ready.val() {
            run.pairs.push((
                uut.out_id_a.val().index() as u32,
                uut.out_id_b.val().index() as u32,
            ));
            run.edges.push(edge);
        }
        clock_cycle(&mut uut, |u| &mut u.clock);
        if taken {
            next += 1;
        }
        edge += 1;
    }
    run
}

/// The hits through the emitted filter in `simulator` (reader always ready).
pub fn run_emitted(
    slots: &OwnerSlots,
    hits: &[(u32, u32)],
    simulator: Simulator,
) -> anyhow::Result<OwnerRun> {
    let size = slots.a.len().max(slots.b.len()).max(1);
    let design = emit_owner_filter(size)?;
    // After the last hit: its comparisons, Head and Emit, and a margin.
    let longest = hits
        .iter()
        .map(|&(sa, sb)| slots.decide(sa, sb).comparisons)
        .max()
        .unwrap_or(0) as usize;
    let mut files = vec![(
        "tb_owner_filter.sv".to_string(),
        testbench(&design.top, longest + 8),
    )];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_owner_filter".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let mut vectors = String::new();
    for (kind, table) in [(0, &slots.a), (1, &slots.b)] {
        for (k, slot) in table.iter().enumerate() {
            vectors += &format!(
                "{kind} {k:x} {:x} {:x} {:x}\n",
                slot.id, slot.leaf, slot.first
            );
        }
    }
    for (sa, sb) in hits {
        vectors += &format!("2 {sa:x} {sb:x} 0 0\n");
    }
    let (text, _) = run_on_vectors(&compiled, "owner-filter-run", &vectors, &[])?;
    // The first hit is offered at the edge after the table writes.
    let first_hit_edge = (slots.a.len() + slots.b.len()) as u64;
    let (pairs, edges) = pairs_at_edges(&text, first_hit_edge, "owner filter")?;
    Ok(OwnerRun { pairs, edges })
}

/// The pairs an owner filter's testbench wrote, `edge a b` a line (`edge`
/// in decimal from reset, `a` and `b` in hex), and their edges counted
/// from `first_hit_edge`; `unit` names the filter in errors.
pub(crate) fn pairs_at_edges(
    text: &str,
    first_hit_edge: u64,
    unit: &str,
) -> anyhow::Result<(Vec<(u32, u32)>, Vec<u64>)> {
    let (mut pairs, mut edges) = (Vec::new(), Vec::new());
    for line in text.lines() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.len() != 3 {
            bail!(
                "{unit} output line `{line}` has {} fields, not 3",
                fields.len()
            );
        }
        let number = |s: &str, radix| {
            u64::from_str_radix(s, radix).with_context(|| format!("`{s}` in `{line}`"))
        };
        let edge = number(fields[0], 10)?;
        edges.push(
            edge.checked_sub(first_hit_edge)
                .with_context(|| format!("a pair left at edge {edge}, before the first hit"))?,
        );
        pairs.push((number(fields[1], 16)? as u32, number(fields[2], 16)? as u32));
    }
    Ok((pairs, edges))
}

/// The testbench: table writes one per clock, then each hit held until
/// taken; the reader always ready; every owned pair written with its edge.
fn testbench(top: &str, drain: usize) -> String {
    let s1 = SLOT_BITS - 1;
    let declarations = format!(
        "\
    reg [1:0] kind = 2'd0;
    wire in_ready, out_valid;
    wire [31:0] out_id_a, out_id_b;
    wire [71:0] word = {{f2, f3[15:0], f4[{s1}:0]}};
    {top} dut (
        .clock(clock), .reset(reset),
        .write_a_enable(in_valid && kind == 2'd0), .write_a_slot(f1[{s1}:0]), .write_a_word(word),
        .write_b_enable(in_valid && kind == 2'd1), .write_b_slot(f1[{s1}:0]), .write_b_word(word),
        .in_valid(in_valid && kind == 2'd2), .in_ready(in_ready), .in_slot_a(f1[{s1}:0]), .in_slot_b(f2[{s1}:0]),
        .out_valid(out_valid), .out_ready(1'b1), .out_id_a(out_id_a), .out_id_b(out_id_b)
    );
"
    );
    filter_testbench(
        "tb_owner_filter",
        &declarations,
        ["out_id_a", "out_id_b"],
        "2'd2",
        drain,
    )
}

/// What both owner filters' testbenches share around `declarations` (the
/// `kind` register, the unit's wires and instance, reading the fields
/// `f1`..`f4`): a line of `kind f1 f2 f3 f4` a clock, a hit (kind
/// `hit_kind`, a Verilog literal) held until `in_ready`; the edges counted
/// from reset; each pair `out_valid` shows written with its edge and the
/// two output wires `pair` ([`pairs_at_edges`] reads them).
pub(crate) fn filter_testbench(
    name: &str,
    declarations: &str,
    pair: [&str; 2],
    hit_kind: &str,
    drain: usize,
) -> String {
    let [a, b] = pair;
    let body = format!(
        "\
    reg [31:0] f1, f2, f3, f4;
    reg [63:0] edge_count = 64'd0;
{declarations}
    always @(posedge clock) if (!reset) edge_count <= edge_count + 64'd1;

    // Outputs are registered, stable at the falling edge; a pair shown
    // there leaves at the next rising edge, number edge_count.
    always @(negedge clock) begin
        if (!reset && out_valid) begin
            $fwrite(outputs, \"%0d %h %h\\n\", edge_count, {a}, {b});
        end
    end
"
    );
    vector_testbench(&VectorTestbench {
        name,
        body,
        start: "        f1 = 0; f2 = 0; f3 = 0; f4 = 0;".into(),
        read: "$fscanf(vectors, \"%h\", kind) == 1".into(),
        // A hit waits, offered, until the filter is ready to take it.
        fill: format!(
            "            r = $fscanf(vectors, \"%h %h %h %h\", f1, f2, f3, f4);\n            \
             if (kind == {hit_kind}) begin in_valid = 1'b1; while (!in_ready) @(negedge clock); end"
        ),
        drain,
    })
}
