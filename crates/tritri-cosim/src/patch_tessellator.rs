//! Co-simulation of the patch tessellation unit
//! ([`tritri_rtl::bezier::patch_tessellator`]): nets through the rust-hdl
//! model and the emitted Verilog, against the exact fixed-point model
//! `tritri_geom::bezier::fixed::fixed_grid`.
//!
//! Vectors: one line per patch, the 48 coordinates in hex (W-bit two's
//! complement, row by row, point by point, x y z), read one `$fscanf` at
//! a time into an array and packed into `net` by one concatenation
//! (Verilator 5.006 gave wrong nets for a wide `%h` read and for writes
//! through a variable part-select of `net`; Icarus did not). Outputs: per
//! patch, one line per vertex taken, `edge i j x y z last`, then `done
//! CLOCKS`.

use crate::simulator::{compile, run_on_vectors, Simulator, Testbench};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::bezier::fixed::FixedNet;
use tritri_rtl::arith::convert::{from_i128, to_i128};
use tritri_rtl::bezier::patch_tessellator::{net_bits, PatchTessellator};
use tritri_rtl::emit::patch_tessellator_unit::{
    emit_patch_tessellator, patch_tessellator_unit_name,
};
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

/// One patch's run: its vertices in order (row `i`, column `j`, point),
/// the edges they were taken at, and the clocks from `start` to idle.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TessellationRun {
    pub vertices: Vec<(u64, u64, [i64; 3])>,
    pub edges: Vec<u64>,
    /// Whether `out_last` came with the last vertex and no other.
    pub last_flag_right: bool,
    pub clocks: u64,
}

/// The net's coordinates in port order.
fn coordinates(net: &FixedNet) -> Vec<i64> {
    net.iter()
        .flatten()
        .flat_map(|p| p.iter().copied())
        .collect()
}

/// Patches through the rust-hdl model of the unit at `(w, k)`; the reader
/// is ready at edges where `ready(edge)` is true.
pub fn run_rusthdl(
    w: usize,
    k: usize,
    nets: &[FixedNet],
    ready: &dyn Fn(u64) -> bool,
) -> Vec<TessellationRun> {
    fn one<const W: usize, const K: usize, const V: usize, const N: usize>(
        nets: &[FixedNet],
        ready: &dyn Fn(u64) -> bool,
    ) -> Vec<TessellationRun> {
        let mut uut = PatchTessellator::<W, K, V, N>::default();
        uut.connect_all();
        reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
        let mut runs = Vec::new();
        for net in nets {
            let mut packed = Bits::<N>::default();
            for (index, c) in coordinates(net).into_iter().enumerate() {
                packed.set_bits::<W>(index * W, from_i128::<W>(c as i128));
            }
            uut.net.next = packed;
            uut.start.next = true;
            settle(&mut uut);
            clock_cycle(&mut uut, |u| &mut u.clock);
            uut.start.next = false;
            let mut run = TessellationRun {
                last_flag_right: true,
                ..Default::default()
            };
            let mut edge = 1u64;
            let side = (1u64 << K) + 1;
            loop {
                uut.out_ready.next = ready(edge);
                settle(&mut uut);
                if !uut.busy.val() || edge > 16 * side * side + 100 {
                    break;
                }
                if uut.out_valid.val() && uut.out_ready.val() {
                    let point = [uut.out_x.val(), uut.out_y.val(), uut.out_z.val()]
                        .map(|c| to_i128(c) as i64);
                    run.vertices.push((
                        uut.out_i.val().index() as u64,
                        uut.out_j.val().index() as u64,
                        point,
                    ));
                    run.edges.push(edge);
                    let last = run.vertices.len() as u64 == side * side;
                    run.last_flag_right &= uut.out_last.val() == last;
                }
                clock_cycle(&mut uut, |u| &mut u.clock);
                edge += 1;
            }
            run.clocks = edge;
            runs.push(run);
        }
        runs
    }
    tritri_rtl::with_patch_tessellator!(w, k, one(nets, ready))
        .unwrap_or_else(|| panic!("no patch tessellator at W = {w}, K = {k}"))
}

/// Patches through the emitted unit in `simulator`, the reader always ready.
pub fn run_emitted(
    w: usize,
    k: usize,
    nets: &[FixedNet],
    simulator: Simulator,
) -> anyhow::Result<Vec<TessellationRun>> {
    let design = emit_patch_tessellator(w, k)?;
    let mut files = vec![("tb_patch_tessellator.sv".to_string(), testbench(w, k))];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_patch_tessellator".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 1,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let mask = (1u128 << w) - 1;
    let vectors: String = nets
        .iter()
        .map(|net| {
            coordinates(net)
                .iter()
                .map(|&c| format!("{:x}", c as i128 as u128 & mask))
                .collect::<Vec<_>>()
                .join(" ")
                + "\n"
        })
        .collect();
    let (text, _) = run_on_vectors(&compiled, "patch-tessellator-run", &vectors, &[])?;
    let side = (1u64 << k) + 1;
    let signed = |s: &str| -> anyhow::Result<i64> {
        let u = u128::from_str_radix(s, 16).with_context(|| format!("`{s}`"))?;
        Ok(if u >> (w - 1) & 1 == 1 {
            (u as i128 - (1i128 << w)) as i64
        } else {
            u as i64
        })
    };
    let mut runs = Vec::new();
    let mut run = TessellationRun {
        last_flag_right: true,
        ..Default::default()
    };
    for line in text.lines() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        let number = |s: &str, radix| {
            u64::from_str_radix(s, radix).with_context(|| format!("`{s}` in `{line}`"))
        };
        match fields.as_slice() {
            ["done", clocks] => {
                run.clocks = number(clocks, 10)?;
                runs.push(std::mem::replace(
                    &mut run,
                    TessellationRun {
                        last_flag_right: true,
                        ..Default::default()
                    },
                ));
            }
            [edge, i, j, x, y, z, last] => {
                run.vertices.push((
                    number(i, 16)?,
                    number(j, 16)?,
                    [signed(x)?, signed(y)?, signed(z)?],
                ));
                run.edges.push(number(edge, 10)?);
                run.last_flag_right &=
                    (number(last, 2)? == 1) == (run.vertices.len() as u64 == side * side);
            }
            _ => bail!(
                "patch tessellator output line `{line}` is neither a vertex nor `done CLOCKS`"
            ),
        }
    }
    if runs.len() != nets.len() {
        bail!(
            "the patch tessellator finished {} of {} patches",
            runs.len(),
            nets.len()
        );
    }
    Ok(runs)
}

/// The testbench: per patch, the net and start for one clock, then every
/// vertex with its edge (the start edge is edge 0) until busy falls.
fn testbench(w: usize, k: usize) -> String {
    let open_files = crate::simulator::OPEN_VECTOR_FILES;
    let top = patch_tessellator_unit_name(w, k);
    let n = net_bits(w);
    let w1 = w - 1;
    let packed = (0..48)
        .rev()
        .map(|m| format!("c[{m}]"))
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        "\
// Generated by tritri-cosim: the patch tessellator, one patch per vector line.
`timescale 1ns/1ps
module tb_patch_tessellator;
    reg clock = 1'b0;
    reg reset = 1'b1;
    reg start = 1'b0;
    reg [{n1}:0] net = {n}'d0;
    wire busy, out_valid, out_last;
    wire [{w1}:0] out_x, out_y, out_z;
    wire [7:0] out_i, out_j;
    reg [63:0] edge_count = 64'd0, base = 64'd0;
    reg [{w1}:0] c [0:47];
    integer vectors, outputs, r, m, got;
    reg [8*4096-1:0] vectors_path, outputs_path;
    {top} dut (
        .clock(clock), .reset(reset), .start(start), .net(net), .busy(busy),
        .out_valid(out_valid), .out_ready(1'b1), .out_x(out_x), .out_y(out_y), .out_z(out_z),
        .out_i(out_i), .out_j(out_j), .out_last(out_last)
    );
    always #5 clock = ~clock;
    always @(posedge clock) edge_count <= edge_count + 64'd1;

    initial begin
{open_files}
        repeat (2) @(negedge clock);
        reset = 1'b0;
        got = 48;
        while (got == 48) begin
            got = 0;
            for (m = 0; m < 48; m = m + 1) begin
                r = $fscanf(vectors, \"%h\", c[m]);
                if (r == 1) got = got + 1;
            end
            if (got == 48) begin
                net = {{{packed}}};
                start = 1'b1;
                base = edge_count;
                @(negedge clock);
                start = 1'b0;
                while (busy) begin
                    if (out_valid) $fwrite(outputs, \"%0d %h %h %h %h %h %b\\n\", edge_count - base, out_i, out_j, out_x, out_y, out_z, out_last);
                    @(negedge clock);
                end
                $fwrite(outputs, \"done %0d\\n\", edge_count - base);
            end
        end
        $fclose(outputs);
        $finish;
    end
endmodule
",
        n1 = n - 1
    )
}
