//! Co-simulation of the octree engine's set-operation unit and octant
//! clipper ([`tritri_rtl::octree::set_operation_unit`],
//! [`tritri_rtl::octree::octant_clipper`]) in rust-hdl and in the emitted
//! Verilog.
//!
//! Set operations: vectors `op a b` (hex words), one per clock; outputs one
//! result word per line. Clipping: vectors `lo_x lo_y lo_z hi_x hi_y hi_z x
//! y z level` (hex), one octant per clock; outputs one class per line.

use crate::simulator::{
    compile, run_on_vectors, vector_testbench, Simulator, Testbench, VectorTestbench,
};
use anyhow::Context as _;
use rust_hdl::prelude::*;
use tritri_geom::octree::cell::Cell;
use tritri_geom::octree::clip::Side;
use tritri_geom::octree::tree::SetOperation;
use tritri_rtl::emit::voxel_units::{
    emit_octant_clipper, emit_set_operation, OCTANT_CLIPPER_NAME, SET_OPERATION_NAME,
};
use tritri_rtl::emit::EmittedDesign;
use tritri_rtl::octree::octant_clipper::{
    OctantClipper, CLASS_CROSSING, CLASS_INSIDE, CLASS_OUTSIDE,
};
use tritri_rtl::octree::set_operation_unit::{
    SetOperationUnit, OP_DIFFERENCE, OP_INTERSECTION, OP_UNION,
};
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

fn op_code(op: SetOperation) -> u64 {
    match op {
        SetOperation::Union => OP_UNION,
        SetOperation::Intersection => OP_INTERSECTION,
        SetOperation::Difference => OP_DIFFERENCE,
    }
}

fn side_of(class: u64) -> anyhow::Result<Side> {
    match class {
        CLASS_OUTSIDE => Ok(Side::Outside),
        CLASS_INSIDE => Ok(Side::Inside),
        CLASS_CROSSING => Ok(Side::Crossing),
        _ => anyhow::bail!("the clipper gave class {class}"),
    }
}

/// `op(a, b)` word by word through the rust-hdl unit, one word pair per
/// clock; also the edges from the first word in to the last word out.
pub fn set_operation_rusthdl(op: SetOperation, a: &[u64], b: &[u64]) -> (Vec<u64>, u64) {
    let mut uut = SetOperationUnit::default();
    uut.connect_all();
    reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
    uut.op.next = op_code(op).into();
    uut.out_ready.next = true;
    let mut out = Vec::with_capacity(a.len());
    let mut edge = 0u64;
    let mut next = 0;
    while out.len() < a.len() && edge < 4 + 2 * a.len() as u64 {
        uut.in_valid.next = next < a.len();
        if next < a.len() {
            uut.in_a.next = a[next].into();
            uut.in_b.next = b[next].into();
        }
        settle(&mut uut);
        if uut.out_valid.val() {
            out.push(uut.out_word.val().to_u64());
        }
        if uut.in_valid.val() && uut.in_ready.val() {
            next += 1;
        }
        clock_cycle(&mut uut, |u| &mut u.clock);
        edge += 1;
    }
    (out, edge)
}

fn compiled(
    design: &EmittedDesign,
    testbench: String,
    top: &str,
    simulator: Simulator,
) -> anyhow::Result<crate::simulator::Compiled> {
    let mut files = vec![(format!("{top}.sv"), testbench)];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    compile(
        simulator,
        &Testbench {
            top: top.into(),
            files,
            defines: vec![],
            parameters: vec![],
            c_optimization: 2,
            trace: false,
        },
    )
}

/// Several set operations through the emitted unit in one simulation.
pub fn set_operations_emitted(
    jobs: &[(SetOperation, &[u64], &[u64])],
    simulator: Simulator,
) -> anyhow::Result<Vec<Vec<u64>>> {
    let design = emit_set_operation()?;
    let body = format!(
        "\
    reg [1:0] op = 2'd0;
    reg [63:0] a = 64'd0, b = 64'd0;
    wire in_ready, out_valid;
    wire [63:0] out_word;
    {SET_OPERATION_NAME} dut (
        .clock(clock), .reset(reset), .op(op), .in_valid(in_valid), .in_ready(in_ready), .in_a(a), .in_b(b),
        .out_valid(out_valid), .out_ready(1'b1), .out_word(out_word)
    );
    always @(negedge clock) if (!reset && out_valid) $fwrite(outputs, \"%h\\n\", out_word);
"
    );
    let bench = vector_testbench(&VectorTestbench {
        name: "tb_set_operation",
        body,
        start: String::new(),
        read: "$fscanf(vectors, \"%h\", op) == 1".into(),
        fill: "            r = $fscanf(vectors, \"%h %h\", a, b);".into(),
        drain: 4,
    });
    let compiled = compiled(&design, bench, "tb_set_operation", simulator)?;
    let mut vectors = String::new();
    for (op, a, b) in jobs {
        for (x, y) in a.iter().zip(b.iter()) {
            vectors += &format!("{:x} {x:x} {y:x}\n", op_code(*op));
        }
    }
    let (text, _) = run_on_vectors(&compiled, "set-operation-run", &vectors, &[])?;
    let words: Vec<u64> = text
        .lines()
        .map(|l| u64::from_str_radix(l.trim(), 16).with_context(|| format!("output `{l}`")))
        .collect::<Result<_, _>>()?;
    let mut out = Vec::new();
    let mut at = 0;
    for (_, a, _) in jobs {
        let end = at + a.len();
        anyhow::ensure!(
            end <= words.len(),
            "the unit gave {} words for {} in",
            words.len(),
            jobs.iter().map(|j| j.1.len()).sum::<usize>()
        );
        out.push(words[at..end].to_vec());
        at = end;
    }
    Ok(out)
}

/// Octants against a box through the rust-hdl clipper, one per clock.
pub fn clip_rusthdl(lo: [i64; 3], hi: [i64; 3], octants: &[Cell]) -> anyhow::Result<Vec<Side>> {
    let mut uut = OctantClipper::default();
    uut.connect_all();
    reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
    let c = |v: i64| -> Bits<11> { (v as u64).into() };
    uut.box_lo_x.next = c(lo[0]);
    uut.box_lo_y.next = c(lo[1]);
    uut.box_lo_z.next = c(lo[2]);
    uut.box_hi_x.next = c(hi[0]);
    uut.box_hi_y.next = c(hi[1]);
    uut.box_hi_z.next = c(hi[2]);
    let mut out = Vec::new();
    for k in 0..octants.len() + 3 {
        uut.in_valid.next = k < octants.len();
        if let Some(o) = octants.get(k) {
            uut.in_x.next = c(o.lo[0]);
            uut.in_y.next = c(o.lo[1]);
            uut.in_z.next = c(o.lo[2]);
            uut.in_level.next = (o.level as u64).into();
        }
        settle(&mut uut);
        if uut.out_valid.val() {
            out.push(side_of(uut.out_class.val().to_u64())?);
        }
        clock_cycle(&mut uut, |u| &mut u.clock);
    }
    Ok(out)
}

/// Boxes and their octants through the emitted clipper in one simulation.
pub fn clip_emitted(
    jobs: &[([i64; 3], [i64; 3], &[Cell])],
    simulator: Simulator,
) -> anyhow::Result<Vec<Vec<Side>>> {
    let design = emit_octant_clipper()?;
    let body = format!(
        "\
    reg [10:0] lx = 0, ly = 0, lz = 0, hx = 0, hy = 0, hz = 0, x = 0, y = 0, z = 0;
    reg [3:0] level = 0;
    wire out_valid;
    wire [1:0] out_class;
    {OCTANT_CLIPPER_NAME} dut (
        .clock(clock), .reset(reset),
        .box_lo_x(lx), .box_lo_y(ly), .box_lo_z(lz), .box_hi_x(hx), .box_hi_y(hy), .box_hi_z(hz),
        .in_valid(in_valid), .in_x(x), .in_y(y), .in_z(z), .in_level(level),
        .out_valid(out_valid), .out_class(out_class)
    );
    always @(negedge clock) if (!reset && out_valid) $fwrite(outputs, \"%h\\n\", out_class);
"
    );
    let bench = vector_testbench(&VectorTestbench {
        name: "tb_octant_clipper",
        body,
        start: String::new(),
        read: "$fscanf(vectors, \"%h\", lx) == 1".into(),
        fill: "            r = $fscanf(vectors, \"%h %h %h %h %h %h %h %h %h\", ly, lz, hx, hy, hz, x, y, z, level);".into(),
        drain: 4,
    });
    let compiled = compiled(&design, bench, "tb_octant_clipper", simulator)?;
    // One run per box: the box is held while its octants flow.
    let mut out = Vec::new();
    for (lo, hi, octants) in jobs {
        let vectors: String = octants
            .iter()
            .map(|o| {
                format!(
                    "{:x} {:x} {:x} {:x} {:x} {:x} {:x} {:x} {:x} {:x}\n",
                    lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], o.lo[0], o.lo[1], o.lo[2], o.level
                )
            })
            .collect();
        let (text, _) = run_on_vectors(&compiled, "octant-clipper-run", &vectors, &[])?;
        let classes: Vec<Side> = text
            .lines()
            .map(|l| {
                side_of(u64::from_str_radix(l.trim(), 16).with_context(|| format!("output `{l}`"))?)
            })
            .collect::<anyhow::Result<_>>()?;
        anyhow::ensure!(
            classes.len() == octants.len(),
            "the clipper gave {} classes for {} octants",
            classes.len(),
            octants.len()
        );
        out.push(classes);
    }
    Ok(out)
}
