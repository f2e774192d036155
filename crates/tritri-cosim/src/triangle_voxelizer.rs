//! Co-simulation of the triangle voxelizer ([`tritri_rtl::octree::
//! triangle_voxelizer`]): a stream of triangles through the cycle model
//! ([`tritri_rtl::octree::voxelizer_machine::voxelizer_schedule`]), the
//! rust-hdl model and the emitted Verilog in Icarus and Verilator, the
//! reader always ready.
//!
//! Vectors: the grid's level on the first line, then one triangle per line,
//! nine hex fine-grid coordinates `x0 y0 z0 x1 … z2`. Outputs: one line per
//! record, `edge x y z mask` (`edge` counted from 0, the edge the first
//! triangle is offered at, at which the reader takes the record), then
//! `done CYCLES`.

use crate::simulator::{compile, run_on_vectors, Simulator, Testbench};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_rtl::emit::triangle_voxelizer_unit::{emit_triangle_voxelizer, TRIANGLE_VOXELIZER_NAME};
use tritri_rtl::octree::cell_classifier::AXES;
use tritri_rtl::octree::triangle_voxelizer::{
    TriangleVoxelizer, VOXELIZER_GRID_BITS, VOXELIZER_MAX_LEVEL, VOXELIZER_STACK_BITS,
};
use tritri_rtl::octree::value_bits;
use tritri_rtl::octree::voxelizer_machine::{voxelizer_schedule, VoxelRecord, VoxelizerRun};
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

const G: usize = VOXELIZER_GRID_BITS;

/// The unit's vertices bus for one triangle.
fn vertices(t: &FixedTriangle) -> Bits<{ 9 * G }> {
    let mut bus = Bits::<{ 9 * G }>::default();
    for (k, &c) in t.iter().flatten().enumerate() {
        bus.set_bits::<G>(k * G, (c as u64).into());
    }
    bus
}

/// The triangles through the rust-hdl model (`level` 1 to 10, vertices on
/// the fine grid inside the `2^level` grid).
pub fn run_rusthdl(triangles: &[FixedTriangle], level: u32) -> VoxelizerRun {
    run_rusthdl_with_stack::<VOXELIZER_STACK_BITS>(triangles, level).0
}

/// The same through a unit whose stack has `2^S` entries, and whether its
/// overflow flag rose.
pub fn run_rusthdl_with_stack<const S: usize>(
    triangles: &[FixedTriangle],
    level: u32,
) -> (VoxelizerRun, bool) {
    let mut uut =
        TriangleVoxelizer::<G, { value_bits(G) }, { AXES * value_bits(G) }, { 9 * G }, S>::default(
        );
    uut.connect_all();
    uut.level.next = (level as u64).into();
    uut.out_ready.next = true;
    reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
    let mut run = VoxelizerRun::default();
    let mut next = 0usize;
    let mut edge = 0u64;
    loop {
        uut.in_valid.next = next < triangles.len();
        if let Some(t) = triangles.get(next) {
            uut.in_vertices.next = vertices(t);
        }
        settle(&mut uut);
        if next == triangles.len() && !uut.busy.val() {
            break;
        }
        if uut.out_valid.val() {
            let lo = [&uut.out_x, &uut.out_y, &uut.out_z].map(|s| s.val().index() as i64);
            run.records.push(VoxelRecord {
                lo,
                mask: uut.out_mask.val().index() as u8,
            });
            run.edges.push(edge);
        }
        if uut.in_valid.val() && uut.in_ready.val() {
            next += 1;
        }
        clock_cycle(&mut uut, |u| &mut u.clock);
        edge += 1;
    }
    run.cycles = edge;
    (run, uut.overflow.val())
}

/// The triangles through the emitted voxelizer in `simulator`.
pub fn run_emitted(
    triangles: &[FixedTriangle],
    level: u32,
    simulator: Simulator,
) -> anyhow::Result<VoxelizerRun> {
    let design = emit_triangle_voxelizer()?;
    let mut files = vec![("tb_triangle_voxelizer.sv".to_string(), testbench())];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_triangle_voxelizer".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let mut vectors = format!("{level:x}\n");
    for t in triangles {
        let fields: Vec<String> = t.iter().flatten().map(|c| format!("{c:x}")).collect();
        vectors += &fields.join(" ");
        vectors.push('\n');
    }
    let (text, _) = run_on_vectors(&compiled, "triangle-voxelizer-run", &vectors, &[])?;
    let mut run = VoxelizerRun::default();
    let mut done = false;
    for line in text.lines() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        let number = |s: &str, radix| {
            u64::from_str_radix(s, radix).with_context(|| format!("`{s}` in `{line}`"))
        };
        match fields.as_slice() {
            ["done", cycles] => {
                run.cycles = number(cycles, 10)?;
                done = true;
            }
            [edge, x, y, z, mask] => {
                let lo = [
                    number(x, 16)? as i64,
                    number(y, 16)? as i64,
                    number(z, 16)? as i64,
                ];
                run.records.push(VoxelRecord {
                    lo,
                    mask: number(mask, 16)? as u8,
                });
                run.edges.push(number(edge, 10)?);
            }
            ["overflow"] => bail!("the voxelizer's stack overflowed"),
            _ => bail!("voxelizer output line `{line}` is neither a record nor `done CYCLES`"),
        }
    }
    if !done {
        bail!("the voxelizer's testbench stopped before the end of the stream");
    }
    Ok(run)
}

/// The testbench: the level, then the triangles offered one after another
/// (the next is put on at the falling edge after one is taken); every
/// record with its edge until the stream is over and busy falls.
fn testbench() -> String {
    let open_files = crate::simulator::OPEN_VECTOR_FILES;
    let (g1, t1) = (G - 1, 9 * G - 1);
    format!(
        "\
// Generated by tritri-cosim: the triangle voxelizer, one triangle per vector line.
`timescale 1ns/1ps
module tb_triangle_voxelizer;
    reg clock = 1'b0;
    reg reset = 1'b1;
    reg [3:0] level = 4'd1;
    reg in_valid = 1'b0;
    reg [{g1}:0] c [0:8];
    reg [{g1}:0] field;
    wire [{t1}:0] in_vertices = {{c[8], c[7], c[6], c[5], c[4], c[3], c[2], c[1], c[0]}};
    wire in_ready, busy, overflow, out_valid;
    wire [10:0] out_x, out_y, out_z;
    wire [7:0] out_mask;
    reg [63:0] edge_count = 64'd0, base = 64'd0;
    integer vectors, outputs, r, i, more, taken;
    reg [8*4096-1:0] vectors_path, outputs_path;
    {TRIANGLE_VOXELIZER_NAME} dut (
        .clock(clock), .reset(reset), .level(level),
        .in_valid(in_valid), .in_ready(in_ready), .in_vertices(in_vertices),
        .busy(busy), .overflow(overflow),
        .out_valid(out_valid), .out_ready(1'b1), .out_x(out_x), .out_y(out_y), .out_z(out_z), .out_mask(out_mask)
    );
    always #5 clock = ~clock;
    always @(posedge clock) edge_count <= edge_count + 64'd1;

    task next_triangle;
        begin
            more = 1;
            for (i = 0; i < 9; i = i + 1) begin
                if ($fscanf(vectors, \"%h\", field) != 1) more = 0;
                c[i] = field;
            end
            in_valid = (more != 0);
        end
    endtask

    initial begin
{open_files}
        for (i = 0; i < 9; i = i + 1) c[i] = 0;
        r = $fscanf(vectors, \"%h\", level);
        repeat (2) @(negedge clock);
        reset = 1'b0;
        // The next rising edge is edge 0.
        base = edge_count;
        next_triangle;
        while (more != 0 || busy) begin
            // Shown now, taken at the next rising edge.
            if (out_valid) $fwrite(outputs, \"%0d %h %h %h %h\\n\", edge_count - base, out_x, out_y, out_z, out_mask);
            taken = in_valid && in_ready;
            @(negedge clock);
            if (taken != 0) next_triangle;
        end
        if (overflow) $fwrite(outputs, \"overflow\\n\");
        $fwrite(outputs, \"done %0d\\n\", edge_count - base);
        $fclose(outputs);
        $finish;
    end
endmodule
"
    )
}

/// Why the unit cannot take a stream as given.
pub fn check_stream(triangles: &[FixedTriangle], level: u32) -> anyhow::Result<VoxelizerRun> {
    anyhow::ensure!(
        (1..=VOXELIZER_MAX_LEVEL).contains(&level),
        "the voxelizer takes grids of 2 to {} voxels a side, not 2^{level}",
        1 << VOXELIZER_MAX_LEVEL
    );
    let top = 1i64 << (level + tritri_geom::octree::voxelize::SUB_BITS);
    if let Some(i) = triangles
        .iter()
        .position(|t| t.iter().flatten().any(|&c| !(0..=top).contains(&c)))
    {
        bail!("triangle {i} has a vertex outside the grid's fine coordinates [0, {top}]");
    }
    let model = voxelizer_schedule(triangles, level);
    // The RAM's overflow is flagged, not survived: the cycle model says
    // first whether the stream fits.
    let capacity = 1usize << VOXELIZER_STACK_BITS;
    anyhow::ensure!(
        model.stack_depth <= capacity,
        "the stream needs {} stack entries, more than the voxelizer's {capacity}",
        model.stack_depth
    );
    Ok(model)
}

/// The triangles through `engine`: the cycle model, the rust-hdl model or
/// the emitted Verilog (the reader always ready).
pub fn run(
    engine: crate::engine::Engine,
    triangles: &[FixedTriangle],
    level: u32,
) -> anyhow::Result<VoxelizerRun> {
    let model = check_stream(triangles, level)?;
    Ok(match (engine, engine.simulator()) {
        (crate::engine::Engine::Model, _) => model,
        (_, None) => run_rusthdl(triangles, level),
        (_, Some(simulator)) => run_emitted(triangles, level, simulator)?,
    })
}
