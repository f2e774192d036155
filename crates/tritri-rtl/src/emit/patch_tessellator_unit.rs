//! The emitted patch tessellation unit ([`crate::bezier::patch_tessellator`]):
//! its name, port meanings and timing, at the widths it is built for.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
pub use crate::bezier::patch_tessellator::TESSELLATOR_CONFIGURATIONS;
use crate::bezier::patch_tessellator::{
    net_bits, tessellation_clocks, value_bits, PatchTessellator,
};
use rust_hdl::prelude::*;

/// `tritri_patch_tessellator_w<W>_k<K>`.
pub fn patch_tessellator_unit_name(w: usize, k: usize) -> String {
    format!("tritri_patch_tessellator_w{w}_k{k}")
}

pub fn patch_tessellator_unit(w: usize, k: usize) -> UnitDescription {
    let n = 1usize << k;
    UnitDescription::new(
        &patch_tessellator_unit_name(w, k),
        &format!(
            "A bicubic Bezier patch on the collision grid tessellated by forward differences (adds and shifts only), {}^2 vertices \
             one per clock, each exactly the patch's point at (i/{n}, j/{n}) rounded to the grid (tritri_geom::bezier::fixed::fixed_grid).",
            n + 1
        ),
    )
    .detail(&format!(
        "Values are offset binary modulo 2^{} (6K + W bits): no sign extension; the offset passes through to the vertex. \
         Two triangles per cell, [(i, j), (i+1, j), (i+1, j+1)] and [(i, j), (i+1, j+1), (i, j+1)], give the collision \
         system's triangles.",
        value_bits(w, k)
    ))
    .parameter("W", &format!("{w}: bits of a coordinate, two's complement"))
    .parameter("K", &format!("{k}: 2^K = {n} steps a side"))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: idle.")
    .port("start", "One clock high while idle: tessellate the patch on net.")
    .port("net", &format!("The 16 control points, read with start: coordinate a of the point in row r, column c at bits [(3 (4 r + c) + a) {w} +: {w}] ({} bits).", net_bits(w)))
    .port("busy", "From start until the last vertex is taken.")
    .port("out_valid", "A vertex is offered.")
    .port("out_ready", "The reader takes it.")
    .port("out_x", "The vertex, x, on the grid.")
    .port("out_y", "The vertex, y.")
    .port("out_z", "The vertex, z.")
    .port("out_i", "Its row i (along the first parameter), 0 to 2^K.")
    .port("out_j", "Its column j, 0 to 2^K.")
    .port("out_last", "The patch's last vertex.")
    .throughput(&format!(
        "one vertex per clock; a patch takes {} clocks from start with the reader always ready (the column setup, the first row's, then a vertex a clock).",
        tessellation_clocks(k as u32)
    ))
}

pub fn emit_patch_tessellator(w: usize, k: usize) -> Result<EmittedDesign, EmitError> {
    fn one<const W: usize, const K: usize, const V: usize, const N: usize>(
    ) -> Result<EmittedDesign, EmitError> {
        let mut uut = PatchTessellator::<W, K, V, N>::default();
        uut.connect_all();
        emit(
            &crate::unit::RawDesign::of(&uut),
            &patch_tessellator_unit(W, K),
        )
    }
    crate::with_patch_tessellator!(w, k, one())
        .unwrap_or_else(|| panic!("the patch tessellator is built for {TESSELLATOR_CONFIGURATIONS:?}, not W = {w}, K = {k}"))
}

/// `tritri_patch_triangles_w<W>_k<K>`.
pub fn patch_triangles_unit_name(w: usize, k: usize) -> String {
    format!("tritri_patch_triangles_w{w}_k{k}")
}

pub fn patch_triangles_unit(w: usize, k: usize) -> UnitDescription {
    let n = 1usize << k;
    UnitDescription::new(
        &patch_triangles_unit_name(w, k),
        &format!(
            "The patch tessellation unit with its triangles assembled: a bicubic Bezier patch on the collision grid, \
             {} triangles out, two a clock, in the collision system's triangle format (x0 y0 z0 x1 ... z2, {w} bits each, \
             from bit 0 up), exactly tritri_geom::bezier::fixed::fixed_triangles.",
            2 * n * n
        ),
    )
    .detail(&format!(
        "The tessellator ({}) gives a vertex a clock; a shift register of 2^K + 2 vertices holds the previous row, \
         and each vertex (i, j) with i, j >= 1 completes the cell below and left of it: [(i-1, j-1), (i, j-1), (i, j)] \
         and [(i-1, j-1), (i, j), (i-1, j)] leave together a clock later.",
        patch_tessellator_unit_name(w, k)
    ))
    .parameter("W", &format!("{w}: bits of a coordinate, two's complement"))
    .parameter("K", &format!("{k}: 2^K = {n} steps a side"))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: idle.")
    .port("start", "One clock high while idle: tessellate the patch on net.")
    .port("net", &format!("The 16 control points: coordinate a of the point in row r, column c at bits [(3 (4 r + c) + a) {w} +: {w}] ({} bits).", net_bits(w)))
    .port("busy", "From start until the last pair is taken.")
    .port("out_valid", "A cell's two triangles are offered.")
    .port("out_ready", "The reader takes them.")
    .port("out_first", "The cell's first triangle, nine coordinates from bit 0 up.")
    .port("out_second", "Its second triangle.")
    .port("out_last", "The patch's last cell.")
    .throughput(&format!(
        "one cell (two triangles) per clock after each row's first vertex; a patch takes {} clocks from start with the reader always ready.",
        tessellation_clocks(k as u32) + 1
    ))
}

pub fn emit_patch_triangles(w: usize, k: usize) -> Result<EmittedDesign, EmitError> {
    fn one<
        const W: usize,
        const K: usize,
        const V: usize,
        const N: usize,
        const C: usize,
        const T: usize,
        const S: usize,
    >() -> Result<EmittedDesign, EmitError> {
        let mut uut =
            crate::bezier::patch_triangles::PatchTriangles::<W, K, V, N, C, T, S>::default();
        uut.connect_all();
        emit(
            &crate::unit::RawDesign::of(&uut),
            &patch_triangles_unit(W, K),
        )
    }
    crate::with_patch_triangles!(w, k, one())
        .unwrap_or_else(|| panic!("the patch triangles unit is built for {TESSELLATOR_CONFIGURATIONS:?}, not W = {w}, K = {k}"))
}
