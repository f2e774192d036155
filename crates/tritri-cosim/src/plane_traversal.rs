//! Co-simulation of the plane traversal ([`tritri_rtl::octree::
//! plane_traversal`]): planes through the cycle model
//! (`tritri_geom::octree::plane::traversal_schedule`), the rust-hdl model
//! and the emitted Verilog in Icarus and Verilator.
//!
//! Vectors: one line per plane, seven hex fields `level n_x n_y n_z d
//! root_min centre_offset` (40-bit two's complement). Outputs: per plane,
//! one line per record, `edge x y z level full crossed` (`edge` counted
//! from 0, the edge that issues the root, at which the reader takes it),
//! then `done CYCLES`.

use crate::simulator::{compile, run_on_vectors, Simulator, Testbench};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::octree::plane::{TraversalRecord, TraversalRun};
use tritri_rtl::arith::convert::{from_i128, to_i128};
use tritri_rtl::emit::plane_traversal_unit::{
    emit_plane_traversal, PlaneInputs, PLANE_TRAVERSAL_NAME,
};
use tritri_rtl::octree::plane_traversal::{PlaneTraversal, PLANE_VALUE_BITS, STACK_ADDRESS_BITS};
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

/// What a hardware run reports: the records with their edges, and the
/// edges it was busy (`cells` is the cycle model's only).
fn record(x: u64, y: u64, z: u64, level: u64, full: u64, crossed: u64) -> TraversalRecord {
    TraversalRecord {
        lo: [x as i64, y as i64, z as i64],
        level: level as u32,
        full: full as u8,
        crossed: crossed as u8,
    }
}

/// One plane through the rust-hdl model; the reader is ready at edges
/// where `reader_ready(edge)` is true (always, for edges to compare).
pub fn run_rusthdl(plane: &PlaneInputs, reader_ready: impl Fn(u64) -> bool) -> TraversalRun {
    run_rusthdl_with_stack::<STACK_ADDRESS_BITS>(plane, reader_ready).0
}

/// The same through a unit whose stack has `2^S` entries, and whether its
/// overflow flag rose.
pub fn run_rusthdl_with_stack<const S: usize>(
    plane: &PlaneInputs,
    reader_ready: impl Fn(u64) -> bool,
) -> (TraversalRun, bool) {
    let mut uut = PlaneTraversal::<S>::default();
    uut.connect_all();
    reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
    let v = |x: i64| from_i128::<PLANE_VALUE_BITS>(x as i128);
    uut.gradient_x.next = v(plane.gradient[0]);
    uut.gradient_y.next = v(plane.gradient[1]);
    uut.gradient_z.next = v(plane.gradient[2]);
    uut.d.next = v(plane.d);
    uut.root_min.next = v(plane.root_min);
    uut.centre_offset.next = v(plane.centre_offset);
    uut.level.next = (plane.level as u64).into();
    uut.start.next = true;
    settle(&mut uut);
    clock_cycle(&mut uut, |u| &mut u.clock);
    uut.start.next = false;
    let mut run = TraversalRun::default();
    // Far more than any plane needs: every cell of the grid, twice.
    let limit = 16 + 2 * (8u64 << (3 * plane.level)) / 7;
    let mut edge = 0u64;
    loop {
        uut.out_ready.next = reader_ready(edge);
        settle(&mut uut);
        if !uut.busy.val() || edge > limit {
            break;
        }
        if uut.out_valid.val() && uut.out_ready.val() {
            run.records.push(record(
                uut.out_x.val().index() as u64,
                uut.out_y.val().index() as u64,
                uut.out_z.val().index() as u64,
                uut.out_level.val().index() as u64,
                uut.out_full.val().index() as u64,
                uut.out_crossed.val().index() as u64,
            ));
            run.edges.push(edge);
        }
        clock_cycle(&mut uut, |u| &mut u.clock);
        edge += 1;
    }
    run.cycles = edge;
    (run, uut.overflow.val())
}

/// Planes through the emitted traversal in `simulator`, the reader always
/// ready.
pub fn run_emitted(
    planes: &[PlaneInputs],
    simulator: Simulator,
) -> anyhow::Result<Vec<TraversalRun>> {
    let design = emit_plane_traversal()?;
    let mut files = vec![("tb_plane_traversal.sv".to_string(), testbench())];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_plane_traversal".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let hex = |x: i64| {
        format!(
            "{:x}",
            to_i128(from_i128::<PLANE_VALUE_BITS>(x as i128)) as u128
                & ((1u128 << PLANE_VALUE_BITS) - 1)
        )
    };
    let vectors: String = planes
        .iter()
        .map(|p| {
            format!(
                "{:x} {} {} {} {} {} {}\n",
                p.level,
                hex(p.gradient[0]),
                hex(p.gradient[1]),
                hex(p.gradient[2]),
                hex(p.d),
                hex(p.root_min),
                hex(p.centre_offset)
            )
        })
        .collect();
    let (text, _) = run_on_vectors(&compiled, "plane-traversal-run", &vectors, &[])?;
    let mut runs = Vec::new();
    let mut run = TraversalRun::default();
    for line in text.lines() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        let number = |s: &str, radix| {
            u64::from_str_radix(s, radix).with_context(|| format!("`{s}` in `{line}`"))
        };
        match fields.as_slice() {
            ["done", cycles] => {
                run.cycles = number(cycles, 10)?;
                runs.push(std::mem::take(&mut run));
            }
            [edge, x, y, z, level, full, crossed] => {
                run.records.push(record(
                    number(x, 16)?,
                    number(y, 16)?,
                    number(z, 16)?,
                    number(level, 16)?,
                    number(full, 16)?,
                    number(crossed, 16)?,
                ));
                run.edges.push(number(edge, 10)?);
            }
            ["overflow"] => bail!("the plane traversal's stack overflowed"),
            _ => {
                bail!("plane traversal output line `{line}` is neither a record nor `done CYCLES`")
            }
        }
    }
    if runs.len() != planes.len() {
        bail!(
            "the plane traversal finished {} of {} planes",
            runs.len(),
            planes.len()
        );
    }
    Ok(runs)
}

/// The testbench: per plane, start for one clock, then every record with
/// its edge until busy falls.
fn testbench() -> String {
    let open_files = crate::simulator::OPEN_VECTOR_FILES;
    format!(
        "\
// Generated by tritri-cosim: the plane traversal, one plane per vector line.
`timescale 1ns/1ps
module tb_plane_traversal;
    reg clock = 1'b0;
    reg reset = 1'b1;
    reg start = 1'b0;
    reg [3:0] level = 4'd1;
    reg [39:0] gx = 40'd0, gy = 40'd0, gz = 40'd0, d = 40'd0, root_min = 40'd0, centre_offset = 40'd0;
    wire busy, overflow, out_valid;
    wire [10:0] out_x, out_y, out_z;
    wire [3:0] out_level;
    wire [7:0] out_full, out_crossed;
    reg [63:0] edge_count = 64'd0, base = 64'd0;
    integer vectors, outputs, r;
    reg [8*4096-1:0] vectors_path, outputs_path;
    {PLANE_TRAVERSAL_NAME} dut (
        .clock(clock), .reset(reset),
        .gradient_x(gx), .gradient_y(gy), .gradient_z(gz), .d(d), .root_min(root_min), .centre_offset(centre_offset),
        .level(level), .start(start), .busy(busy), .overflow(overflow),
        .out_valid(out_valid), .out_ready(1'b1), .out_x(out_x), .out_y(out_y), .out_z(out_z),
        .out_level(out_level), .out_full(out_full), .out_crossed(out_crossed)
    );
    always #5 clock = ~clock;
    always @(posedge clock) edge_count <= edge_count + 64'd1;

    initial begin
{open_files}
        repeat (2) @(negedge clock);
        reset = 1'b0;
        while ($fscanf(vectors, \"%h %h %h %h %h %h %h\", level, gx, gy, gz, d, root_min, centre_offset) == 7) begin
            start = 1'b1;
            @(negedge clock);
            start = 1'b0;
            // The next rising edge issues the root: edge 0.
            base = edge_count;
            while (busy) begin
                // Shown now, taken at the next rising edge.
                if (out_valid) $fwrite(outputs, \"%0d %h %h %h %h %h %h\\n\", edge_count - base, out_x, out_y, out_z, out_level, out_full, out_crossed);
                @(negedge clock);
            end
            if (overflow) $fwrite(outputs, \"overflow\\n\");
            $fwrite(outputs, \"done %0d\\n\", edge_count - base);
        end
        $fclose(outputs);
        $finish;
    end
endmodule
"
    )
}

/// One plane through `engine`: the cycle model, the rust-hdl model or the
/// emitted Verilog (the reader always ready).
pub fn run(
    engine: crate::engine::Engine,
    level: u32,
    normal: [i64; 3],
    d: i64,
) -> anyhow::Result<TraversalRun> {
    let plane = PlaneInputs::new(level, normal, d).map_err(anyhow::Error::msg)?;
    let model = tritri_geom::octree::plane::traversal_schedule(level, normal, plane.d);
    // The RAM's overflow is flagged, not survived: the cycle model says
    // first whether the plane fits (the most seen on 512^3 and 1024^3
    // planes is 42 entries).
    let capacity = 1usize << STACK_ADDRESS_BITS;
    anyhow::ensure!(
        model.stack_depth <= capacity,
        "the plane needs {} stack entries, more than the traversal's {capacity}",
        model.stack_depth
    );
    Ok(match (engine, engine.simulator()) {
        (crate::engine::Engine::Model, _) => model,
        (_, None) => run_rusthdl(&plane, |_| true),
        (_, Some(simulator)) => run_emitted(&[plane], simulator)?.remove(0),
    })
}
