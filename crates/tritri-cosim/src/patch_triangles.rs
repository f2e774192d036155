//! Co-simulation of the tessellation unit with its triangles assembled
//! ([`tritri_rtl::bezier::patch_triangles`]): nets through the rust-hdl
//! model and the emitted Verilog, against the exact fixed-point model
//! `tritri_geom::bezier::fixed::fixed_triangles`.
//!
//! Vectors: one line per patch, the 48 coordinates in hex (as for the
//! tessellator). Outputs: per patch, one line per cell, `edge first second
//! last` (the triangles as hex buses), then `done CLOCKS`.

use crate::patch_tessellator::{net_vectors, pack_net, per_patch_testbench};
use crate::simulator::{compile, run_on_vectors, Simulator, Testbench};
use anyhow::{bail, Context as _};
use rust_hdl::prelude::*;
use tritri_geom::bezier::fixed::FixedNet;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_rtl::arith::convert::to_i128;
use tritri_rtl::bezier::patch_triangles::PatchTriangles;
use tritri_rtl::emit::patch_tessellator_unit::{emit_patch_triangles, patch_triangles_unit_name};
use tritri_rtl::sim_drive::{clock_cycle, reset_one_clock, settle};

/// One patch's run: its triangles in order, the edge each pair was taken
/// at (the start edge is 0), whether `out_last` came with the last pair
/// alone, and the clocks from `start` to idle.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TrianglesRun {
    pub triangles: Vec<FixedTriangle>,
    pub edges: Vec<u64>,
    pub last_flag_right: bool,
    pub clocks: u64,
}

/// A triangle from its nine `w`-bit fields.
fn triangle(field: impl Fn(usize) -> i64) -> FixedTriangle {
    std::array::from_fn(|v| std::array::from_fn(|k| field(3 * v + k)))
}

/// Patches through the rust-hdl model at `(w, k)`, the reader always ready.
pub fn run_rusthdl(w: usize, k: usize, nets: &[FixedNet]) -> Vec<TrianglesRun> {
    fn one<
        const W: usize,
        const K: usize,
        const V: usize,
        const N: usize,
        const C: usize,
        const T: usize,
        const S: usize,
    >(
        nets: &[FixedNet],
    ) -> Vec<TrianglesRun> {
        let mut uut = PatchTriangles::<W, K, V, N, C, T, S>::default();
        uut.connect_all();
        uut.out_ready.next = true;
        reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
        let cells = 1u64 << (2 * K);
        let mut runs = Vec::new();
        for net in nets {
            uut.net.next = pack_net::<W, N>(net);
            uut.start.next = true;
            settle(&mut uut);
            clock_cycle(&mut uut, |u| &mut u.clock);
            uut.start.next = false;
            let mut run = TrianglesRun {
                last_flag_right: true,
                ..Default::default()
            };
            let mut edge = 1u64;
            loop {
                settle(&mut uut);
                if !uut.busy.val() || edge > 4 * cells + 100 {
                    break;
                }
                if uut.out_valid.val() {
                    let (first, second) = (uut.out_first.val(), uut.out_second.val());
                    run.triangles
                        .push(triangle(|f| to_i128(first.get_bits::<W>(f * W)) as i64));
                    run.triangles
                        .push(triangle(|f| to_i128(second.get_bits::<W>(f * W)) as i64));
                    run.edges.push(edge);
                    run.last_flag_right &= uut.out_last.val() == (run.edges.len() as u64 == cells);
                }
                clock_cycle(&mut uut, |u| &mut u.clock);
                edge += 1;
            }
            run.clocks = edge;
            runs.push(run);
        }
        runs
    }
    tritri_rtl::with_patch_triangles!(w, k, one(nets))
        .unwrap_or_else(|| panic!("no patch triangles unit at W = {w}, K = {k}"))
}

/// Patches through the emitted unit in `simulator`, the reader always ready.
pub fn run_emitted(
    w: usize,
    k: usize,
    nets: &[FixedNet],
    simulator: Simulator,
) -> anyhow::Result<Vec<TrianglesRun>> {
    let design = emit_patch_triangles(w, k)?;
    let mut files = vec![("tb_patch_triangles.sv".to_string(), testbench(w, k))];
    files.extend(
        design
            .verilog_files()
            .map(|f| (f.path.clone(), f.contents.clone())),
    );
    let bench = Testbench {
        top: "tb_patch_triangles".into(),
        files,
        defines: vec![],
        parameters: vec![],
        c_optimization: 1,
        trace: false,
    };
    let compiled = compile(simulator, &bench)?;
    let vectors = net_vectors(nets, w);
    let (text, _) = run_on_vectors(&compiled, "patch-triangles-run", &vectors, &[])?;
    let cells = 1u64 << (2 * k);
    // A hex bus, field `f` of `w` bits, two's complement.
    let field = |bus: &str, f: usize| -> i64 {
        let digits: Vec<u32> = bus
            .chars()
            .rev()
            .map(|c| c.to_digit(16).unwrap_or(0))
            .collect();
        let raw: i128 = (0..w)
            .filter(|b| {
                digits
                    .get((f * w + b) / 4)
                    .is_some_and(|d| d >> ((f * w + b) % 4) & 1 == 1)
            })
            .map(|b| 1i128 << b)
            .sum();
        (if raw >> (w - 1) & 1 == 1 {
            raw - (1i128 << w)
        } else {
            raw
        }) as i64
    };
    let mut runs = Vec::new();
    let mut run = TrianglesRun {
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
                    TrianglesRun {
                        last_flag_right: true,
                        ..Default::default()
                    },
                ));
            }
            [edge, first, second, last] => {
                anyhow::ensure!(
                    first
                        .chars()
                        .chain(second.chars())
                        .all(|c| c.is_ascii_hexdigit()),
                    "`{line}` is not hexadecimal"
                );
                run.triangles.push(triangle(|f| field(first, f)));
                run.triangles.push(triangle(|f| field(second, f)));
                run.edges.push(number(edge, 10)?);
                run.last_flag_right &= (number(last, 2)? == 1) == (run.edges.len() as u64 == cells);
            }
            _ => bail!("patch triangles output line `{line}` is neither a pair nor `done CLOCKS`"),
        }
    }
    if runs.len() != nets.len() {
        bail!(
            "the patch triangles unit finished {} of {} patches",
            runs.len(),
            nets.len()
        );
    }
    Ok(runs)
}

/// The testbench: per patch, the net and start for one clock, then every
/// pair with its edge (the start edge is edge 0) until busy falls.
fn testbench(w: usize, k: usize) -> String {
    let t1 = 9 * w - 1;
    per_patch_testbench(
        "tb_patch_triangles",
        &patch_triangles_unit_name(w, k),
        w,
        &format!("    wire out_last;\n    wire [{t1}:0] out_first, out_second;"),
        ".out_first(out_first), .out_second(out_second), .out_last(out_last)",
        "\"%0d %h %h %b\\n\", edge_count - base, out_first, out_second, out_last",
    )
}

/// Query pieces tessellated through the unit (or its fixed-point model):
/// the f64 triangles and the patch each comes from, and the unit's clocks.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UnitTessellation {
    pub triangles: Vec<tritri_geom::triangle::Triangle>,
    pub face_of: Vec<usize>,
    /// Pieces after recutting to the unit's largest `2^K`.
    pub pieces: usize,
    /// Clocks with the reader always ready, patch after patch.
    pub clocks: u64,
    /// The grid's step: each vertex is within one step per coordinate of
    /// the f64 surface point at its parameters.
    pub step: f64,
}

/// `pieces` (from `tritri_geom::bezier::query::query_pieces`) on a `w`-bit
/// grid fit to them, each recut to at most `2^4` samples a side and
/// tessellated at the unit's least `2^K` (K from 1 to 4) that is at least
/// its samples, through `engine`: the fixed-point model, or the unit in
/// rust-hdl or the emitted Verilog, checked against the model.
pub fn tessellate_pieces(
    engine: crate::engine::Engine,
    w: usize,
    pieces: &[tritri_geom::bezier::query::QueryPiece],
    tolerance: f64,
) -> anyhow::Result<UnitTessellation> {
    use tritri_geom::bezier::fixed::{fixed_triangles, PatchFrame};
    use tritri_geom::bezier::query::pieces_within;
    let recut = pieces_within(pieces, 1 << 4, tolerance);
    let shapes: Vec<_> = recut.iter().map(|p| p.piece).collect();
    let frame = PatchFrame::fit(&shapes, w as u32);
    let mut out = UnitTessellation {
        pieces: recut.len(),
        step: frame.step,
        ..Default::default()
    };
    for k in 1usize..=4 {
        // The least 2^K that covers the piece's samples.
        let group: Vec<_> = recut
            .iter()
            .filter(|p| p.samples.next_power_of_two().max(2).trailing_zeros() as usize == k)
            .collect();
        if group.is_empty() {
            continue;
        }
        let nets: Vec<FixedNet> = group.iter().map(|p| frame.quantize(&p.piece)).collect();
        let model: Vec<Vec<FixedTriangle>> =
            nets.iter().map(|n| fixed_triangles(n, k as u32)).collect();
        let hardware = match (engine, engine.simulator()) {
            (crate::engine::Engine::Model, _) => None,
            (_, None) => Some(run_rusthdl(w, k, &nets)),
            (_, Some(simulator)) => Some(run_emitted(w, k, &nets, simulator)?),
        };
        if let Some(runs) = &hardware {
            let wrong = runs
                .iter()
                .zip(&model)
                .filter(|(r, m)| r.triangles != **m)
                .count()
                + runs.len().abs_diff(model.len());
            anyhow::ensure!(wrong == 0, "the tessellation unit in {} gave {wrong} pieces' triangles that differ from the fixed-point model (a bug)", engine.name());
        }
        let clocks = tritri_rtl::bezier::patch_tessellator::tessellation_clocks(k as u32) + 1;
        out.clocks += clocks * group.len() as u64;
        for (piece, triangles) in group.iter().zip(model) {
            for t in triangles {
                // Degenerate triangles (a collapsed row) touch nothing new.
                if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
                    continue;
                }
                out.triangles.push(t.map(|v| frame.dequantize(v)));
                out.face_of.push(piece.patch);
            }
        }
    }
    Ok(out)
}
