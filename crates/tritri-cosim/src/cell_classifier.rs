//! Co-simulation of the octree classifier step
//! ([`tritri_rtl::octree::cell_classifier`]): the same entries through the
//! software classifier (`tritri_geom::octree::triangle_cell`), the rust-hdl
//! model, and the emitted Verilog in Icarus and Verilator.
//!
//! The testbench is generated here from the port list (78 value ports), so
//! the port names are written in one place, the rust-hdl struct.

pub use crate::simulator::Simulator;
use crate::simulator::{compile, run_on_vectors, vector_testbench, Testbench, VectorTestbench};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::octree::cell::Cell;
use tritri_geom::octree::triangle_cell::{CellValues, TriangleCellTest, MAX_AXES};
use tritri_rtl::arith::convert::{from_i128, to_i128};
use tritri_rtl::emit::cell_classifier_unit::{emit_cell_classifier, CLASSIFIER_GRID_WIDTHS};
use tritri_rtl::octree::cell_classifier::{CellClassifier, AXES, CELL_CLASSIFIER_LATENCY};
use tritri_rtl::octree::value_bits;
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock};

/// One entry on the classifier's inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClassifierEntry {
    pub tag: u16,
    /// Level of the classified cell (>= 1).
    pub level: u32,
    /// `Some(o)`: the values are over the parent; classify its child `o`.
    pub descend: Option<u8>,
    pub at_lo: [i128; MAX_AXES],
    /// `(gradient, low, high)` per test function.
    pub axes: [([i128; 3], i128, i128); MAX_AXES],
}

/// What the classifier answers for one entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClassifierAnswer {
    pub tag: u16,
    pub mask: u8,
    pub at_lo: [i128; MAX_AXES],
}

/// The values over the classified cell: the entry's own, or its child's.
fn classified(test: &TriangleCellTest, values: &CellValues, descend: Option<u8>) -> CellValues {
    match descend {
        Some(o) => test.child(values, o as usize),
        None => *values,
    }
}

/// The software classifier's answer: the values over the classified cell
/// and its children mask.
pub fn expected_answer(
    test: &TriangleCellTest,
    values: &CellValues,
    descend: Option<u8>,
    tag: u16,
) -> ClassifierAnswer {
    let cell = classified(test, values, descend);
    ClassifierAnswer {
        tag,
        mask: test.children_touched(&cell),
        at_lo: cell.at_lo(),
    }
}

/// Entries with their software answers, as a binning pass meets them: each
/// triangle from the root down every child it meets, to `levels` levels
/// below the root; and, so that misses are exercised as often as hits, one
/// descent per cell into a child it does not meet (while the answer counts
/// stay below `limit`).
pub fn harvest(
    triangles: &[[[i64; 3]; 3]],
    root: Cell,
    levels: u32,
    limit: usize,
) -> Vec<(ClassifierEntry, ClassifierAnswer)> {
    let mut out = Vec::new();
    for t in triangles {
        let test = TriangleCellTest::new(t);
        let axes = test.padded_axes();
        let mut stack = vec![(test.values(&root), None::<u8>, 0u32)];
        while let Some((values, descend, depth)) = stack.pop() {
            if out.len() >= limit {
                return out;
            }
            let tag = out.len() as u16;
            let answer = expected_answer(&test, &values, descend, tag);
            let level = values.level() - descend.map_or(0, |_| 1);
            out.push((
                ClassifierEntry {
                    tag,
                    level,
                    descend,
                    at_lo: values.at_lo(),
                    axes,
                },
                answer,
            ));
            let cell = classified(&test, &values, descend);
            if depth < levels && cell.level() >= 2 {
                for o in (0..8u8).filter(|o| answer.mask >> o & 1 == 1) {
                    stack.push((cell, Some(o), depth + 1));
                }
                if let Some(o) = (0..8u8).find(|o| answer.mask >> o & 1 == 0) {
                    stack.push((cell, Some(o), levels));
                }
            }
        }
    }
    out
}

/// Runs the entries through the rust-hdl model of the `grid_bits` classifier.
pub fn run_rusthdl(
    grid_bits: usize,
    entries: &[ClassifierEntry],
) -> anyhow::Result<Vec<ClassifierAnswer>> {
    match grid_bits {
        16 => Ok(run_rusthdl_v::<{ value_bits(16) }>(entries)),
        24 => Ok(run_rusthdl_v::<{ value_bits(24) }>(entries)),
        32 => Ok(run_rusthdl_v::<{ value_bits(32) }>(entries)),
        g => bail!("no classifier for a {g}-bit grid (have {CLASSIFIER_GRID_WIDTHS:?})"),
    }
}

fn run_rusthdl_v<const V: usize>(entries: &[ClassifierEntry]) -> Vec<ClassifierAnswer> {
    let mut uut = CellClassifier::<V>::default();
    uut.connect_all();
    uut.advance.next = true;
    reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
    let mut answers = Vec::new();
    let idle = std::iter::repeat_n(None, CELL_CLASSIFIER_LATENCY + 1);
    for entry in entries.iter().map(Some).chain(idle) {
        uut.in_valid.next = entry.is_some();
        if let Some(e) = entry {
            uut.in_tag.next = (e.tag as u64).into();
            uut.in_level.next = (e.level as u64).into();
            uut.in_descend.next = e.descend.is_some();
            uut.in_octant.next = (e.descend.unwrap_or(0) as u64).into();
            for i in 0..AXES {
                let (g, low, high) = e.axes[i];
                uut.in_at_lo[i].next = from_i128::<V>(e.at_lo[i]);
                uut.in_gradient_x[i].next = from_i128::<V>(g[0]);
                uut.in_gradient_y[i].next = from_i128::<V>(g[1]);
                uut.in_gradient_z[i].next = from_i128::<V>(g[2]);
                uut.in_low[i].next = from_i128::<V>(low);
                uut.in_high[i].next = from_i128::<V>(high);
            }
        }
        clock_cycle(&mut uut, |u| &mut u.clock);
        if uut.out_valid.val() {
            answers.push(ClassifierAnswer {
                tag: uut.out_tag.val().index() as u16,
                mask: uut.out_mask.val().index() as u8,
                at_lo: std::array::from_fn(|i| to_i128(uut.out_at_lo[i].val())),
            });
        }
    }
    answers
}

/// Runs the entries through the emitted `grid_bits` classifier.
pub fn run_emitted(
    grid_bits: usize,
    entries: &[ClassifierEntry],
    simulator: Simulator,
) -> anyhow::Result<Vec<ClassifierAnswer>> {
    let design = emit_cell_classifier(grid_bits)?;
    let v = value_bits(grid_bits);
    let mut files = vec![(
        "tb_cell_classifier.sv".to_string(),
        testbench(&design.top, v),
    )];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_cell_classifier".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let (text, _) = run_on_vectors(&compiled, "classifier-run", &vector_text(entries, v), &[])?;
    text.lines().map(|line| parse_answer(line, v)).collect()
}

fn hex(value: i128, bits: usize) -> String {
    format!("{:x}", (value as u128) & ((1u128 << bits) - 1))
}

fn vector_text(entries: &[ClassifierEntry], v: usize) -> String {
    let mut text = String::new();
    for e in entries {
        let mut fields = vec![
            format!("{:x}", e.tag),
            format!("{:x}", e.level),
            format!("{}", e.descend.is_some() as u8),
            format!("{}", e.descend.unwrap_or(0)),
        ];
        fields.extend(e.at_lo.iter().map(|x| hex(*x, v)));
        for k in 0..3 {
            fields.extend(e.axes.iter().map(|a| hex(a.0[k], v)));
        }
        fields.extend(e.axes.iter().map(|a| hex(a.1, v)));
        fields.extend(e.axes.iter().map(|a| hex(a.2, v)));
        text += &fields.join(" ");
        text.push('\n');
    }
    text
}

fn parse_answer(line: &str, v: usize) -> anyhow::Result<ClassifierAnswer> {
    let fields: Vec<&str> = line.split_whitespace().collect();
    if fields.len() != 2 + AXES {
        bail!(
            "classifier output line `{line}` has {} fields, not {}",
            fields.len(),
            2 + AXES
        );
    }
    let number = |s: &str| {
        u128::from_str_radix(s, 16).with_context(|| format!("`{s}` in `{line}` is not hexadecimal"))
    };
    let signed = |u: u128| {
        if u >> (v - 1) & 1 == 1 {
            u as i128 - (1i128 << v)
        } else {
            u as i128
        }
    };
    let mut at_lo = [0i128; MAX_AXES];
    for (i, s) in fields[2..].iter().enumerate() {
        at_lo[i] = signed(number(s)?);
    }
    Ok(ClassifierAnswer {
        tag: number(fields[0])? as u16,
        mask: number(fields[1])? as u8,
        at_lo,
    })
}

/// The testbench: reads one entry per line, drives it for one clock, and
/// writes `tag mask at_lo...` for every valid output.
fn testbench(top: &str, v: usize) -> String {
    let mut ports = String::new();
    for i in 0..AXES {
        for (port, array) in [
            ("in_at_lo", "at_lo"),
            ("in_gradient_x", "gx"),
            ("in_gradient_y", "gy"),
            ("in_gradient_z", "gz"),
            ("in_low", "low"),
            ("in_high", "high"),
        ] {
            ports += &format!("        .{port}_{i}({array}[{i}]),\n");
        }
        ports += &format!("        .out_at_lo_{i}(out_at_lo_{i}),\n");
    }
    let out_wires: String = (0..AXES)
        .map(|i| format!("    wire [V-1:0] out_at_lo_{i};\n"))
        .collect();
    let out_format = " %h".repeat(AXES);
    let out_args: String = (0..AXES).map(|i| format!(", out_at_lo_{i}")).collect();
    let body = format!(
        "\
    localparam V = {v};
    localparam AXES = {AXES};
    reg [15:0] tag = 16'd0;
    reg [5:0] level = 6'd0;
    reg descend = 1'b0;
    reg [2:0] octant = 3'd0;
    reg [V-1:0] at_lo [0:AXES-1];
    reg [V-1:0] gx [0:AXES-1];
    reg [V-1:0] gy [0:AXES-1];
    reg [V-1:0] gz [0:AXES-1];
    reg [V-1:0] low [0:AXES-1];
    reg [V-1:0] high [0:AXES-1];
    reg [V-1:0] field;
    wire out_valid;
    wire [15:0] out_tag;
    wire [7:0] out_mask;
{out_wires}
    {top} dut (
        .clock(clock),
        .reset(reset),
        .advance(advance),
        .in_valid(in_valid),
        .in_tag(tag),
        .in_level(level),
        .in_descend(descend),
        .in_octant(octant),
{ports}        .out_valid(out_valid),
        .out_tag(out_tag),
        .out_mask(out_mask)
    );

    // Registered outputs are stable at the falling edge.
    always @(negedge clock) begin
        if (!reset && out_valid) begin
            $fwrite(outputs, \"%h %h{out_format}\\n\", out_tag, out_mask{out_args});
        end
    end
"
    );
    let read_array = |array: &str| {
        format!("            for (i = 0; i < AXES; i = i + 1) begin r = $fscanf(vectors, \"%h\", field); {array}[i] = field; end\n")
    };
    vector_testbench(&VectorTestbench {
        name: "tb_cell_classifier",
        body,
        start: "        for (i = 0; i < AXES; i = i + 1) begin\n            at_lo[i] = 0; gx[i] = 0; gy[i] = 0; gz[i] = 0; low[i] = 0; high[i] = 0;\n        end".into(),
        read: "$fscanf(vectors, \"%h %h %h %h\", tag, level, descend, octant) == 4".into(),
        fill: ["at_lo", "gx", "gy", "gz", "low", "high"].map(read_array).concat().trim_end().to_string(),
        drain: CELL_CLASSIFIER_LATENCY + 2,
    })
}
