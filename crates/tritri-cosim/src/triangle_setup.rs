//! Co-simulation of the classifier's setup
//! ([`tritri_rtl::octree::triangle_setup`]): the same triangles through the
//! software model (`tritri_geom::octree::triangle_cell::root_relative_axes`),
//! the rust-hdl model and the emitted Verilog in Icarus and Verilator.
//!
//! Vectors: one triangle per line, `tag x0 y0 z0 x1 y1 z1 x2 y2 z2 rx ry rz`
//! (hex, coordinates as G-bit two's complement). Outputs: one line per
//! triangle, `tag` then the five packed buses (gradient x, y, z, low,
//! high) in hex.

use crate::simulator::{
    compile, run_on_vectors, vector_testbench, Simulator, Testbench, VectorTestbench,
};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::triangle_cell::{root_relative_axes, BROAD_PHASE_MARGIN, MAX_AXES};
use tritri_rtl::arith::convert::{from_i128, to_i128};
use tritri_rtl::emit::cell_classifier_unit::CLASSIFIER_GRID_WIDTHS;
use tritri_rtl::emit::triangle_setup_unit::emit_phased_triangle_setup;
use tritri_rtl::octree::cell_classifier::AXES;
use tritri_rtl::octree::triangle_setup::{setup_latency, TriangleSetup};
use tritri_rtl::octree::value_bits;
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock};

/// One triangle's functions, `(gradient, low, high)` in the fixed order.
pub type SetupAnswer = (u16, [([i128; 3], i128, i128); MAX_AXES]);

/// The margin the setup grows the triangles by: one step when `grow` is
/// high (the broad phase), none for voxelization.
fn margin(grow: bool) -> i128 {
    if grow {
        BROAD_PHASE_MARGIN
    } else {
        0
    }
}

/// What the software model says for each triangle (tags `0..`).
pub fn expected(triangles: &[FixedTriangle], root: [i64; 3], grow: bool) -> Vec<SetupAnswer> {
    triangles
        .iter()
        .enumerate()
        .map(|(i, t)| (i as u16, root_relative_axes(t, root, margin(grow))))
        .collect()
}

/// The triangles through the rust-hdl model of the `grid_bits` setup
/// sharing its products over `phases` clocks, one triangle every `phases`
/// clocks (other values on the vertex inputs between them, which a phased
/// setup must not take).
pub fn run_rusthdl(
    grid_bits: usize,
    phases: usize,
    triangles: &[FixedTriangle],
    root: [i64; 3],
    grow: bool,
) -> anyhow::Result<Vec<SetupAnswer>> {
    match grid_bits {
        16 => Ok(run_rusthdl_g::<
            16,
            { value_bits(16) },
            { AXES * value_bits(16) },
        >(phases, triangles, root, grow)),
        24 => Ok(run_rusthdl_g::<
            24,
            { value_bits(24) },
            { AXES * value_bits(24) },
        >(phases, triangles, root, grow)),
        32 => Ok(run_rusthdl_g::<
            32,
            { value_bits(32) },
            { AXES * value_bits(32) },
        >(phases, triangles, root, grow)),
        g => bail!("no setup for a {g}-bit grid (have {CLASSIFIER_GRID_WIDTHS:?})"),
    }
}

fn unpack<const N: usize, const V: usize>(bus: Bits<N>) -> [i128; AXES] {
    std::array::from_fn(|i| to_i128(bus.get_bits::<V>(i * V)))
}

fn run_rusthdl_g<const G: usize, const V: usize, const N: usize>(
    phases: usize,
    triangles: &[FixedTriangle],
    root: [i64; 3],
    grow: bool,
) -> Vec<SetupAnswer> {
    let mut uut = TriangleSetup::<G, V, N>::with_phases(phases);
    uut.connect_all();
    uut.advance.next = true;
    uut.grow.next = grow;
    reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
    let g = |x: i64| from_i128::<G>(x as i128);
    uut.in_root_x.next = g(root[0]);
    uut.in_root_y.next = g(root[1]);
    uut.in_root_z.next = g(root[2]);
    let mut answers = Vec::new();
    let idle = std::iter::repeat_n(None, setup_latency(phases) + 1);
    // Each triangle, then `phases - 1` clocks of the next triangle's
    // vertices (or the first's) without in_valid.
    let spaced = triangles.iter().enumerate().flat_map(|(i, t)| {
        let other = &triangles[(i + 1) % triangles.len()];
        std::iter::once((i, t, true)).chain(std::iter::repeat_n((i, other, false), phases - 1))
    });
    for (tag, t, valid) in spaced
        .map(Some)
        .chain(idle)
        .map(|x| x.map_or((0, None, false), |(i, t, valid)| (i, Some(t), valid)))
    {
        uut.in_valid.next = valid;
        uut.in_tag.next = (if valid { tag } else { !tag & 0xffff } as u64).into();
        if let Some(t) = t {
            let inputs = [
                &mut uut.in_x0,
                &mut uut.in_y0,
                &mut uut.in_z0,
                &mut uut.in_x1,
                &mut uut.in_y1,
                &mut uut.in_z1,
                &mut uut.in_x2,
                &mut uut.in_y2,
                &mut uut.in_z2,
            ];
            for (signal, value) in inputs.into_iter().zip(t.iter().flatten()) {
                signal.next = g(*value);
            }
        }
        clock_cycle(&mut uut, |u| &mut u.clock);
        if uut.out_valid.val() {
            let (gx, gy, gz) = (
                unpack::<N, V>(uut.out_gradient_x.val()),
                unpack::<N, V>(uut.out_gradient_y.val()),
                unpack::<N, V>(uut.out_gradient_z.val()),
            );
            let (low, high) = (
                unpack::<N, V>(uut.out_low.val()),
                unpack::<N, V>(uut.out_high.val()),
            );
            let axes = std::array::from_fn(|i| ([gx[i], gy[i], gz[i]], low[i], high[i]));
            answers.push((uut.out_tag.val().index() as u16, axes));
        }
    }
    answers
}

/// The triangles through the emitted `grid_bits` setup sharing its
/// products over `phases` clocks, spaced as [`run_rusthdl`] spaces them.
pub fn run_emitted(
    grid_bits: usize,
    phases: usize,
    triangles: &[FixedTriangle],
    root: [i64; 3],
    grow: bool,
    simulator: Simulator,
) -> anyhow::Result<Vec<SetupAnswer>> {
    let design = emit_phased_triangle_setup(grid_bits, phases)?;
    let v = value_bits(grid_bits);
    let mut files = vec![(
        "tb_triangle_setup.sv".to_string(),
        testbench(&design.top, grid_bits, v, phases),
    )];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_triangle_setup".into(),
        files,
        defines: vec![],
        parameters: vec![("GROW".into(), u8::from(grow).to_string())],
        c_optimization: 2,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let mask = (1u64 << grid_bits) - 1;
    let hex = |x: i64| format!("{:x}", (x as u64) & mask);
    let mut vectors = String::new();
    for (tag, t) in triangles.iter().enumerate() {
        let fields: Vec<String> = std::iter::once(format!("{tag:x}"))
            .chain(t.iter().flatten().chain(&root).map(|&x| hex(x)))
            .collect();
        vectors += &fields.join(" ");
        vectors.push('\n');
    }
    let (text, _) = run_on_vectors(&compiled, "setup-run", &vectors, &[])?;
    text.lines().map(|line| parse_answer(line, v)).collect()
}

fn parse_answer(line: &str, v: usize) -> anyhow::Result<SetupAnswer> {
    let fields: Vec<&str> = line.split_whitespace().collect();
    if fields.len() != 6 {
        bail!(
            "setup output line `{line}` has {} fields, not 6",
            fields.len()
        );
    }
    let tag = u16::from_str_radix(fields[0], 16)
        .with_context(|| format!("tag `{}` in `{line}`", fields[0]))?;
    // A bus is AXES * V bits of hex, most significant first.
    let bus = |s: &str| -> anyhow::Result<[i128; AXES]> {
        let fields = crate::simulator::signed_hex_fields(s, v, AXES)?;
        Ok(std::array::from_fn(|i| fields[i]))
    };
    let (gx, gy, gz, low, high) = (
        bus(fields[1])?,
        bus(fields[2])?,
        bus(fields[3])?,
        bus(fields[4])?,
        bus(fields[5])?,
    );
    Ok((
        tag,
        std::array::from_fn(|i| ([gx[i], gy[i], gz[i]], low[i], high[i])),
    ))
}

/// The testbench: reads one triangle per line, drives it for one clock
/// after `phases - 1` clocks of other values without `in_valid`, and
/// writes `tag` and the five buses for every valid output.
fn testbench(top: &str, g: usize, v: usize, phases: usize) -> String {
    let (g1, n1) = (g - 1, AXES * v - 1);
    let body = format!(
        "\
    parameter GROW = 1;
    reg [15:0] tag = 16'd0;
    reg [{g1}:0] c [0:11];
    reg [{g1}:0] field;
    wire out_valid;
    wire [15:0] out_tag;
    wire [{n1}:0] gx, gy, gz, low, high;
    {top} dut (
        .clock(clock), .reset(reset), .advance(advance), .in_valid(in_valid), .in_tag(tag),
        .in_x0(c[0]), .in_y0(c[1]), .in_z0(c[2]), .in_x1(c[3]), .in_y1(c[4]), .in_z1(c[5]),
        .in_x2(c[6]), .in_y2(c[7]), .in_z2(c[8]), .in_root_x(c[9]), .in_root_y(c[10]), .in_root_z(c[11]), .grow(GROW != 0),
        .out_valid(out_valid), .out_tag(out_tag),
        .out_gradient_x(gx), .out_gradient_y(gy), .out_gradient_z(gz), .out_low(low), .out_high(high)
    );

    // Registered outputs are stable at the falling edge.
    always @(negedge clock) begin
        if (!reset && out_valid) begin
            $fwrite(outputs, \"%h %h %h %h %h %h\\n\", out_tag, gx, gy, gz, low, high);
        end
    end
"
    );
    vector_testbench(&VectorTestbench {
        name: "tb_triangle_setup",
        body,
        start: "        for (i = 0; i < 12; i = i + 1) c[i] = 0;".into(),
        read: "$fscanf(vectors, \"%h\", tag) == 1".into(),
        fill: format!(
            "            in_valid = 1'b0;
            for (i = 0; i < 9; i = i + 1) c[i] = $random;
            repeat ({}) @(negedge clock);
            for (i = 0; i < 12; i = i + 1) begin r = $fscanf(vectors, \"%h\", field); c[i] = field; end",
            phases - 1
        ),
        drain: setup_latency(phases) + 2,
    })
}
