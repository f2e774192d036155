//! Co-simulation of the binning unit ([`tritri_rtl::broad_phase::binning_unit`]):
//! a scene's two arrays streamed in, the leaves streamed out, in the rust-hdl
//! model and in the emitted Verilog (Icarus or Verilator), against the
//! cycle-exact model ([`tritri_rtl::broad_phase::binning_machine`]), whose leaves
//! are the broad phase planner's.
//!
//! Vectors for the emitted unit: a first line `0 x y z level enable
//! max_level` (hex) starts the run at the root cell; then one line per
//! triangle, `1 object last x0 y0 z0 x1 y1 z1 x2 y2 z2` (coordinates as
//! G-bit two's complement), each held until the unit takes it. Outputs,
//! each with `edge`, the rising edge counted from reset: `H edge x y z
//! level` a leaf's header, `E edge object index vertices` an entry, `D edge` the
//! first edge with `binned` high, `F edge overflow` at `done`.

use crate::simulator::{
    compile, run_on_vectors, vector_testbench, Simulator, Testbench, VectorTestbench,
};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::cell::Cell;
use tritri_geom::scene::PreparedScene;
use tritri_rtl::broad_phase::binning_machine::{run_binning, BinningParams, BinningRun};
use tritri_rtl::broad_phase::binning_unit::{
    on_unit_stack, BinningUnit, BinningUnitConfig, BINNING_GRID_WIDTHS,
};
use tritri_rtl::broad_phase::broad_phase_system::leaf_tiles;
use tritri_rtl::emit::binning_unit_unit::emit_binning_unit;
use tritri_rtl::octree::cell_classifier::AXES;
use tritri_rtl::octree::value_bits;
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

/// One leaf as the unit streams it: its cell and its arrays (indices into
/// the host's arrays).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StreamedLeaf {
    pub cell: Cell,
    pub a: Vec<u32>,
    pub b: Vec<u32>,
}

/// What a run gives: the leaves, and the clocks from the first triangle in
/// to the end of binning (the first clock the leaves stream).
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct BinningOutput {
    pub leaves: Vec<StreamedLeaf>,
    pub cycles: u64,
    /// The unit's `overflow` at `done`: a memory was too small.
    pub overflow: bool,
}

/// The model's leaves as the unit streams them for a system of memory
/// depth `depth`: a leaf larger than that as its tiles (every A tile with
/// every B tile, as the host's `scene::tile` cuts it), each under a header.
pub fn expected_leaves(run: &BinningRun, depth: usize) -> Vec<StreamedLeaf> {
    leaf_tiles(&run.leaf_lists, depth)
        .map(|(leaf, a, b)| StreamedLeaf {
            cell: run.leaves[leaf].cell,
            a: a.to_vec(),
            b: b.to_vec(),
        })
        .collect()
}

/// The scene through the rust-hdl model of the unit built for `config`;
/// `reader_ready(clock)` drives `out_ready`.
pub fn run_rusthdl(
    config: &BinningUnitConfig,
    a: &[FixedTriangle],
    b: &[FixedTriangle],
    root: Cell,
    max_leaf_level: Option<u32>,
    reader_ready: &(dyn Fn(u64) -> bool + Sync),
) -> anyhow::Result<BinningOutput> {
    fn run<const G: usize, const V: usize, const N: usize, const T: usize>(
        config: &BinningUnitConfig,
        a: &[FixedTriangle],
        b: &[FixedTriangle],
        root: Cell,
        max_leaf_level: Option<u32>,
        reader_ready: &dyn Fn(u64) -> bool,
    ) -> anyhow::Result<BinningOutput> {
        let mut uut =
            BinningUnit::<G, V, N, T>::new(config.triangles, config.list_words, config.leaves)
                .with_system(config.log_depth, config.log_pipelines);
        uut.connect_all();
        reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
        let g = grid_value::<G>;
        uut.root_x.next = g(root.lo[0]);
        uut.root_y.next = g(root.lo[1]);
        uut.root_z.next = g(root.lo[2]);
        uut.root_level.next = (root.level as u64).into();
        uut.max_leaf_enable.next = max_leaf_level.is_some();
        uut.max_leaf_level.next = (max_leaf_level.unwrap_or(0) as u64).into();
        uut.start.next = true;
        clock_cycle(&mut uut, |u| &mut u.clock);
        uut.start.next = false;
        let stream = triangle_stream(a, b);
        let mut clock = 0u64;
        let mut next = 0;
        let mut out = BinningOutput::default();
        let mut binned_at = None;
        let mut current: Option<StreamedLeaf> = None;
        let limit = 20_000_000u64;
        loop {
            uut.in_valid.next = next < stream.len();
            if let Some(&(object, t)) = stream.get(next) {
                uut.in_object.next = object;
                uut.in_last.next = next + 1 == stream.len();
                uut.in_vertices.next = vertices_word::<G, T>(t);
            }
            uut.out_ready.next = reader_ready(clock);
            settle(&mut uut);
            if uut.binned.val() && binned_at.is_none() {
                binned_at = Some(clock);
            }
            if uut.done.val() {
                out.overflow = uut.overflow.val();
                break;
            }
            let taken = uut.in_valid.val() && uut.in_ready.val();
            if uut.out_valid.val() && uut.out_ready.val() {
                if uut.out_header.val() {
                    out.leaves.extend(current.take());
                    let lo = [
                        signed::<G>(uut.out_x.val().index() as u64),
                        signed::<G>(uut.out_y.val().index() as u64),
                        signed::<G>(uut.out_z.val().index() as u64),
                    ];
                    current = Some(StreamedLeaf {
                        cell: Cell {
                            lo,
                            level: uut.out_level.val().index() as u32,
                        },
                        a: Vec::new(),
                        b: Vec::new(),
                    });
                } else {
                    let Some(leaf) = current.as_mut() else {
                        bail!("an entry before the first header at clock {clock}")
                    };
                    let index = uut.out_index.val().index() as u32;
                    let object = uut.out_object.val();
                    let vertices = uut.out_vertices.val();
                    let word: Vec<i64> = (0..9)
                        .map(|k| signed::<G>(vertices.get_bits::<G>(k * G).index() as u64))
                        .collect();
                    check_vertices(object, index, &word, a, b)?;
                    if object {
                        leaf.b.push(index)
                    } else {
                        leaf.a.push(index)
                    }
                }
            }
            clock_cycle(&mut uut, |u| &mut u.clock);
            if taken {
                next += 1;
            }
            clock += 1;
            if clock > limit {
                bail!("the binning unit did not finish in {limit} clocks");
            }
        }
        out.leaves.extend(current.take());
        // Clocks are counted from the first triangle taken (clock 0).
        out.cycles = binned_at.unwrap_or(clock);
        Ok(out)
    }
    on_unit_stack(|| match config.grid_bits {
        16 => run::<16, { value_bits(16) }, { AXES * value_bits(16) }, { 9 * 16 }>(
            config,
            a,
            b,
            root,
            max_leaf_level,
            reader_ready,
        ),
        24 => run::<24, { value_bits(24) }, { AXES * value_bits(24) }, { 9 * 24 }>(
            config,
            a,
            b,
            root,
            max_leaf_level,
            reader_ready,
        ),
        32 => run::<32, { value_bits(32) }, { AXES * value_bits(32) }, { 9 * 32 }>(
            config,
            a,
            b,
            root,
            max_leaf_level,
            reader_ready,
        ),
        g => bail!("the binning unit is built for {BINNING_GRID_WIDTHS:?}-bit grids, not {g}"),
    })
}

/// An entry's vertices must be the triangle streamed in at its index.
fn check_vertices(
    object: bool,
    index: u32,
    vertices: &[i64],
    a: &[FixedTriangle],
    b: &[FixedTriangle],
) -> anyhow::Result<()> {
    let array = if object { b } else { a };
    let Some(t) = array.get(index as usize) else {
        bail!(
            "entry {index} of object {} is past its {} triangles",
            object as u8,
            array.len()
        )
    };
    let streamed: Vec<i64> = t.iter().flatten().copied().collect();
    if vertices != streamed {
        bail!(
            "entry {index} of object {}: vertices {vertices:?}, streamed {streamed:?}",
            object as u8
        );
    }
    Ok(())
}

/// A hex word of nine `G`-bit fields, field 0 in the low bits, as signed values.
fn hex_fields(text: &str, grid_bits: usize) -> anyhow::Result<Vec<i64>> {
    let digits: Vec<u8> = text
        .bytes()
        .rev()
        .map(|c| (c as char).to_digit(16).map(|d| d as u8))
        .collect::<Option<_>>()
        .with_context(|| format!("`{text}` is not hex"))?;
    let bit = |i: usize| digits.get(i / 4).is_some_and(|d| d >> (i % 4) & 1 == 1);
    Ok((0..9)
        .map(|k| {
            let raw = (0..grid_bits).fold(0u64, |v, i| v | (bit(k * grid_bits + i) as u64) << i);
            signed_grid_value(raw, grid_bits)
        })
        .collect())
}

/// A `G`-bit two's complement value.
fn signed<const G: usize>(v: u64) -> i64 {
    signed_grid_value(v, G)
}

/// The `bits`-bit two's complement value in the low bits of `v` (a grid
/// coordinate as the units write it).
pub(crate) fn signed_grid_value(v: u64, bits: usize) -> i64 {
    ((v as i64) << (64 - bits)) >> (64 - bits)
}

/// The scene through the emitted unit built for `config` in `simulator`
/// (the reader always ready). `clock_bound` bounds the clocks the run may
/// take after its last triangle (binning and the leaves out).
pub fn run_emitted(
    config: &BinningUnitConfig,
    a: &[FixedTriangle],
    b: &[FixedTriangle],
    root: Cell,
    max_leaf_level: Option<u32>,
    clock_bound: u64,
    simulator: Simulator,
) -> anyhow::Result<BinningOutput> {
    let design = emit_binning_unit(config)?;
    let mut files = vec![(
        "tb_binning_unit.sv".to_string(),
        testbench(&design.top, config.grid_bits, clock_bound as usize),
    )];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_binning_unit".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 1,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let vectors = input_vectors(config.grid_bits, a, b, root, max_leaf_level);
    let (text, _) = run_on_vectors(&compiled, "binning-unit-run", &vectors, &[])?;
    parse_outputs(&text, config.grid_bits, a, b)
}

/// The testbench's output lines as leaves and cycles. The start line is
/// offered before edge 0 and the first triangle at edge 1, the unit's
/// clock 0: an output at edge `k` is the model's clock `k - 1`.
fn parse_outputs(
    text: &str,
    grid_bits: usize,
    a: &[FixedTriangle],
    b: &[FixedTriangle],
) -> anyhow::Result<BinningOutput> {
    let mut out = BinningOutput::default();
    let mut current: Option<StreamedLeaf> = None;
    let mut binned = None;
    for line in text.lines() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        let number = |k: usize, radix| -> anyhow::Result<u64> {
            let s = fields
                .get(k)
                .with_context(|| format!("binning unit output line `{line}` has no field {k}"))?;
            u64::from_str_radix(s, radix).with_context(|| format!("`{s}` in `{line}`"))
        };
        let coordinate = |v: u64| signed_grid_value(v, grid_bits);
        match fields.first().copied() {
            Some("H") => {
                out.leaves.extend(current.take());
                let lo = [
                    coordinate(number(2, 16)?),
                    coordinate(number(3, 16)?),
                    coordinate(number(4, 16)?),
                ];
                current = Some(StreamedLeaf {
                    cell: Cell {
                        lo,
                        level: number(5, 16)? as u32,
                    },
                    a: Vec::new(),
                    b: Vec::new(),
                });
            }
            Some("E") => {
                let Some(leaf) = current.as_mut() else {
                    bail!("an entry before the first header: `{line}`")
                };
                let index = number(3, 16)? as u32;
                let object = number(2, 16)? == 1;
                let vertices = fields.get(4).with_context(|| {
                    format!("binning unit output line `{line}` has no vertices")
                })?;
                check_vertices(object, index, &hex_fields(vertices, grid_bits)?, a, b)?;
                if object {
                    leaf.b.push(index)
                } else {
                    leaf.a.push(index)
                }
            }
            Some("D") => binned = Some(number(1, 10)?),
            Some("F") => out.overflow = number(2, 16)? == 1,
            _ => bail!("binning unit output line `{line}` is not H, E, D or F"),
        }
    }
    out.leaves.extend(current.take());
    let Some(edge) = binned else {
        bail!("the emitted binning unit never raised `binned`")
    };
    out.cycles = edge
        .checked_sub(1)
        .context("`binned` at edge 0, before the first triangle")?;
    Ok(out)
}

/// The testbench: the start line for one clock, each triangle held until
/// taken, the reader always ready; every leaf word written with its edge;
/// the run ends when the unit says `done` (or `drain` clocks after the
/// last triangle).
fn testbench(top: &str, g: usize, drain: usize) -> String {
    let g1 = g - 1;
    let t1 = 9 * g - 1;
    let body = format!(
        "\
{registers}
    reg [63:0] edge_count = 64'd0;
    reg binned_seen = 1'b0;
    wire in_ready, out_valid, out_header, out_object, binned, done, overflow;
    wire [17:0] out_index;
    wire [{t1}:0] out_vertices;
    wire [{g1}:0] out_x, out_y, out_z;
    wire [5:0] out_level;
    wire [19:0] out_count_a, out_count_b;
    {top} dut (
        .clock(clock), .reset(reset),
{ports}
        .out_valid(out_valid), .out_ready(1'b1), .out_header(out_header), .out_object(out_object), .out_index(out_index), .out_vertices(out_vertices),
        .out_x(out_x), .out_y(out_y), .out_z(out_z), .out_level(out_level), .out_count_a(out_count_a), .out_count_b(out_count_b),
        .binned(binned), .done(done), .overflow(overflow)
    );

    always @(posedge clock) if (!reset) edge_count <= edge_count + 64'd1;

    // Outputs are registered, stable at the falling edge; a word shown
    // there leaves at the next rising edge, number edge_count.
    always @(negedge clock) begin
        if (!reset && binned && !binned_seen) begin
            $fwrite(outputs, \"D %0d\\n\", edge_count);
            binned_seen = 1'b1;
        end
        if (!reset && out_valid && out_header) $fwrite(outputs, \"H %0d %h %h %h %h\\n\", edge_count, out_x, out_y, out_z, out_level);
        if (!reset && out_valid && !out_header) $fwrite(outputs, \"E %0d %h %h %h\\n\", edge_count, out_object, out_index, out_vertices);
        if (!reset && done) begin
            $fwrite(outputs, \"F %0d %h\\n\", edge_count, overflow);
            $fclose(outputs);
            $finish;
        end
    end
",
        registers = INPUT_REGISTERS,
        ports = input_ports(g),
    );
    vector_testbench(&input_testbench("tb_binning_unit", body, drain))
}

// ---- The host's side of the binning unit's input ports, shared with the
// broad-phase top, whose input ports are the unit's.

/// Each object's triangles in the order the host streams them: A's, then
/// B's (`true`).
pub(crate) fn triangle_stream<'t>(
    a: &'t [FixedTriangle],
    b: &'t [FixedTriangle],
) -> Vec<(bool, &'t FixedTriangle)> {
    a.iter()
        .map(|t| (false, t))
        .chain(b.iter().map(|t| (true, t)))
        .collect()
}

/// `v` as a `G`-bit two's complement grid coordinate.
pub(crate) fn grid_value<const G: usize>(v: i64) -> Bits<G> {
    Bits::from((v as u64) & ((1u64 << G) - 1))
}

/// A triangle on `in_vertices`: `x0 y0 z0 x1 … z2` from bit 0 up.
pub(crate) fn vertices_word<const G: usize, const T: usize>(t: &FixedTriangle) -> Bits<T> {
    let mut word = Bits::<T>::default();
    for (k, v) in t.iter().flatten().enumerate() {
        word.set_bits::<G>(k * G, grid_value::<G>(*v));
    }
    word
}

/// The vector file of a run: the start line (root corner and level, leaf
/// limit), then one line per triangle (object, last, nine coordinates).
pub(crate) fn input_vectors(
    grid_bits: usize,
    a: &[FixedTriangle],
    b: &[FixedTriangle],
    root: Cell,
    max_leaf_level: Option<u32>,
) -> String {
    let mask = |v: i64| (v as u64) & ((1u64 << grid_bits) - 1);
    let mut vectors = format!(
        "0 {:x} {:x} {:x} {:x} {:x} {:x}\n",
        mask(root.lo[0]),
        mask(root.lo[1]),
        mask(root.lo[2]),
        root.level,
        max_leaf_level.is_some() as u8,
        max_leaf_level.unwrap_or(0)
    );
    let stream = triangle_stream(a, b);
    for (k, (object, t)) in stream.iter().enumerate() {
        vectors += &format!("1 {} {}", *object as u8, (k + 1 == stream.len()) as u8);
        for v in t.iter().flatten() {
            vectors += &format!(" {:x}", mask(*v));
        }
        vectors.push('\n');
    }
    vectors
}

/// The testbench's registers for [`input_vectors`]' fields.
pub(crate) const INPUT_REGISTERS: &str = "    reg [3:0] kind = 4'd0;
    // Scalars, not an array: Verilator's $fscanf does not fill array elements.
    reg [31:0] f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10;
    // The run's root and leaf limit, held from the start line to the end.
    reg [31:0] held_x, held_y, held_z, held_level, held_enable, held_max;";

/// The input ports' connections to those registers, for a `g`-bit grid.
pub(crate) fn input_ports(g: usize) -> String {
    let g1 = g - 1;
    format!(
        "        .start(in_valid && kind == 4'd0),
        .root_x(held_x[{g1}:0]), .root_y(held_y[{g1}:0]), .root_z(held_z[{g1}:0]), .root_level(held_level[5:0]),
        .max_leaf_enable(held_enable[0]), .max_leaf_level(held_max[5:0]),
        .in_valid(in_valid && kind == 4'd1), .in_ready(in_ready), .in_last(f1[0]), .in_object(f0[0]),
        .in_vertices({{f10[{g1}:0], f9[{g1}:0], f8[{g1}:0], f7[{g1}:0], f6[{g1}:0], f5[{g1}:0], f4[{g1}:0], f3[{g1}:0], f2[{g1}:0]}}),"
    )
}

/// The vector testbench's start, read and fill for [`input_vectors`]: the
/// start line held for one clock, a triangle offered until taken.
pub(crate) fn input_testbench(
    name: &'static str,
    body: String,
    drain: usize,
) -> VectorTestbench<'static> {
    VectorTestbench {
        name,
        body,
        start: "        f0 = 0; f1 = 0; f2 = 0; f3 = 0; f4 = 0; f5 = 0; f6 = 0; f7 = 0; f8 = 0; f9 = 0; f10 = 0;\n        held_x = 0; held_y = 0; held_z = 0; held_level = 0; held_enable = 0; held_max = 0;".into(),
        read: "$fscanf(vectors, \"%h\", kind) == 1".into(),
        // The start line: six fields, one clock. A triangle: eleven,
        // offered until the unit takes it.
        fill: "            if (kind == 4'd0) r = $fscanf(vectors, \"%h %h %h %h %h %h\", held_x, held_y, held_z, held_level, held_enable, held_max);\n            \
               else begin\n                \
               r = $fscanf(vectors, \"%h %h %h %h %h %h %h %h %h %h %h\", f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10);\n                \
               in_valid = 1'b1; while (!in_ready) @(negedge clock);\n            \
               end"
            .into(),
        drain,
    }
}

/// Why [`bin_scene`] has no run of the binning unit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BinningError {
    /// The unit is not built for this configuration; the reason.
    NotBuilt(String),
    /// The unit's clock-exact model streams other leaves than the broad
    /// phase's planner (a bug in one of them).
    DiffersFromPlanner { unit: usize, planner: usize },
}

impl std::fmt::Display for BinningError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BinningError::NotBuilt(why) => write!(f, "not built for this configuration: {why}"),
            BinningError::DiffersFromPlanner { unit, planner } => write!(
                f,
                "the binning unit's model streams other leaves than the broad phase's planner ({unit} against {planner}; a bug)"
            ),
        }
    }
}

impl std::error::Error for BinningError {}

/// The binning unit on a scene's broad phase: the unit built for it and
/// its run (the cycle-exact model, which the rust-hdl model and the
/// emitted Verilog equal: tests/binning_unit.rs).
#[derive(Clone, Debug)]
pub struct SceneBinning {
    pub config: BinningUnitConfig,
    pub run: BinningRun,
}

/// Bins the scene's arrays (the triangles in the common box, which the
/// broad phase's planner bins into `scene.octree`) as the unit does, for a system of
/// `depth` triangles per array and `pipelines` pipelines on a `grid_bits`
/// grid (leaves at most `max_leaf_level` with local frames). An error says
/// why the unit does not apply ([`BinningError::NotBuilt`]: a depth or
/// pipeline count that is not a power of two, a grid it is not built for,
/// triangles left to the host), or that its leaves differ from the
/// planner's ([`BinningError::DiffersFromPlanner`], a bug).
pub fn bin_scene(
    scene: &PreparedScene,
    grid_bits: usize,
    depth: usize,
    pipelines: usize,
    max_leaf_level: Option<u32>,
) -> Result<SceneBinning, BinningError> {
    use BinningError::NotBuilt;
    if !depth.is_power_of_two() || !pipelines.is_power_of_two() {
        return Err(NotBuilt(format!("its split rule takes a power-of-two depth and pipeline count, not depth {depth}, P = {pipelines}")));
    }
    if !BINNING_GRID_WIDTHS.contains(&grid_bits) {
        return Err(NotBuilt(format!(
            "it is built for {BINNING_GRID_WIDTHS:?}-bit grids, not {grid_bits}"
        )));
    }
    let Some(octree) = &scene.octree else {
        return Err(NotBuilt("the scene has no octree broad phase".into()));
    };
    if !octree.host_arrays.is_empty() {
        return Err(NotBuilt(
            "some triangles are too long for a leaf's window and go to the host".into(),
        ));
    }
    let Some(root) = octree.root else {
        return Err(NotBuilt("the common box is empty".into()));
    };
    let params = BinningParams {
        log_depth: depth.trailing_zeros(),
        log_pipelines: pipelines.trailing_zeros(),
        max_leaf_level,
    };
    let a: Vec<FixedTriangle> = scene.kept_a.iter().map(|t| t.triangle).collect();
    let b: Vec<FixedTriangle> = scene.kept_b.iter().map(|t| t.triangle).collect();
    let run = run_binning(&a, &b, root, params);
    let planned: Vec<Cell> = octree.leaves.iter().map(|l| l.cell).collect();
    if run
        .leaves
        .iter()
        .map(|l| l.cell)
        .ne(planned.iter().copied())
    {
        return Err(BinningError::DiffersFromPlanner {
            unit: run.leaves.len(),
            planner: planned.len(),
        });
    }
    let config = BinningUnitConfig::sized_for(grid_bits, params, a.len().max(b.len()), &run);
    config.check().map_err(NotBuilt)?;
    Ok(SceneBinning { config, run })
}
