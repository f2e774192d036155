//! The emitted setup of the octree classifier
//! ([`crate::octree::triangle_setup`]): its name, port meanings and latency.

use super::cell_classifier_unit::{UnsupportedGrid, CLASSIFIER_GRID_WIDTHS};
use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::octree::cell_classifier::{AXES, TAG_BITS};
use crate::octree::triangle_setup::{setup_latency, TriangleSetup, SETUP_PRODUCTS};
use crate::octree::value_bits;
use rust_hdl::prelude::*;

/// Top module name for `grid_bits`-bit grids: `tritri_triangle_setup_g<G>`.
pub fn triangle_setup_unit_name(grid_bits: usize) -> String {
    phased_triangle_setup_unit_name(grid_bits, 1)
}

/// Top module name of a setup sharing its products over `phases` clocks:
/// `tritri_triangle_setup_g<G>_ph<R>` (one phase: the name above).
pub fn phased_triangle_setup_unit_name(grid_bits: usize, phases: usize) -> String {
    if phases == 1 {
        format!("tritri_triangle_setup_g{grid_bits}")
    } else {
        format!("tritri_triangle_setup_g{grid_bits}_ph{phases}")
    }
}

#[derive(Debug, thiserror::Error)]
pub enum SetupEmitError {
    #[error(transparent)]
    Grid(#[from] UnsupportedGrid),
    #[error(transparent)]
    Emit(#[from] EmitError),
}

/// rust-hdl's Verilog of the setup for `grid_bits` (the grids the
/// classifier is emitted for).
pub fn raw_triangle_setup_verilog(
    grid_bits: usize,
    phases: usize,
) -> Result<crate::unit::RawDesign, UnsupportedGrid> {
    fn raw<const G: usize, const V: usize, const N: usize>(
        phases: usize,
    ) -> crate::unit::RawDesign {
        let mut uut = TriangleSetup::<G, V, N>::with_phases(phases);
        uut.connect_all();
        crate::unit::RawDesign::of(&uut)
    }
    match grid_bits {
        16 => Ok(raw::<16, { value_bits(16) }, { AXES * value_bits(16) }>(
            phases,
        )),
        24 => Ok(raw::<24, { value_bits(24) }, { AXES * value_bits(24) }>(
            phases,
        )),
        32 => Ok(raw::<32, { value_bits(32) }, { AXES * value_bits(32) }>(
            phases,
        )),
        g => Err(UnsupportedGrid(g)),
    }
}

/// The description of the setup for the emitter.
pub fn triangle_setup_unit(
    grid_bits: usize,
    phases: usize,
) -> Result<UnitDescription, UnsupportedGrid> {
    if !CLASSIFIER_GRID_WIDTHS.contains(&grid_bits) {
        return Err(UnsupportedGrid(grid_bits));
    }
    let v = value_bits(grid_bits);
    let l = setup_latency(phases) as u64;
    let field = |what: &str| {
        format!("{what} of the {AXES} test functions, packed: function i at bits [i*V +: V], V-bit two's complement.")
    };
    let unit = UnitDescription::new(
        &phased_triangle_setup_unit_name(grid_bits, phases),
        &format!(
            "Octree classifier setup for a {grid_bits}-bit grid: one triangle per clock in, its {AXES} affine test functions \
             relative to the root cell's low corner out after {l} clocks, ready for the classifier step at the root."
        ),
    )
    .detail(
        "The functions are the separating axes of a triangle and a cube: x, y, z; the triangle's plane (normal \
         n = e0 x e1); and the nine products of an edge with an axis, edge by edge. Relative to the root's low \
         corner every function is zero there, so the classifier's first entry needs no values. The plane's interval \
         is the single value n . p0, and an edge function's opposite end is its start minus a normal component, so \
         27 multiplications serve a triangle. Exact: equal to tritri_geom::octree::triangle_cell::root_relative_axes.",
    )
    .parameter("G", &format!("{grid_bits}: grid coordinate width in bits"))
    .parameter("V", &format!("{v}: value width, 3G + 6 (two's complement)"))
    .parameter("AXES", &format!("{AXES}: test functions per triangle"))
    .pipelined_control_ports()
    .port("in_valid", "A triangle is on the inputs this cycle.")
    .port("in_tag", &format!("{TAG_BITS}-bit tag of the triangle, returned as `out_tag`."))
    .port("in_root_x", "Low corner of the root cell, x (G-bit two's complement).")
    .port("in_root_y", "Low corner of the root cell, y.")
    .port("in_root_z", "Low corner of the root cell, z.")
    .port("grow", "High: every interval grown by |g|_1, one grid step in every direction (the broad phase). Low: the triangle's own intervals (exact voxelization). Held constant.")
    .port("out_valid", &format!("The functions of the triangle that entered {l} clocks earlier are on the outputs."))
    .port("out_tag", "Tag of the triangle.")
    .port("out_gradient_x", &field("Gradients, x"))
    .port("out_gradient_y", &field("Gradients, y"))
    .port("out_gradient_z", &field("Gradients, z"))
    .port("out_low", &field("Low ends of the triangle's intervals"))
    .port("out_high", &field("High ends of the triangle's intervals"))
    .latency(l);
    let mut unit = if phases == 1 {
        unit.throughput("one triangle per clock while `advance` is high.")
    } else {
        unit.throughput(&format!(
            "one triangle every {phases} clocks: in_valid at most once in any {phases} clocks. Stage 2's \
             {SETUP_PRODUCTS} products share {} multipliers over those clocks; stage 1 holds its triangle until \
             the next in_valid, and the outputs hold theirs until the next triangle's.",
            SETUP_PRODUCTS.div_ceil(phases)
        ))
    };
    for i in 0..3 {
        for c in ["x", "y", "z"] {
            unit = unit.port(
                &format!("in_{c}{i}"),
                &format!("Vertex {i}, {c} (G-bit two's complement grid coordinate)."),
            );
        }
    }
    Ok(unit)
}

/// The emitted setup for a `grid_bits`-bit grid.
pub fn emit_triangle_setup(grid_bits: usize) -> Result<EmittedDesign, SetupEmitError> {
    emit_phased_triangle_setup(grid_bits, 1)
}

/// The emitted setup for a `grid_bits`-bit grid, its products shared over
/// `phases` clocks (`crate::octree::triangle_setup`, "Phases").
pub fn emit_phased_triangle_setup(
    grid_bits: usize,
    phases: usize,
) -> Result<EmittedDesign, SetupEmitError> {
    let unit = triangle_setup_unit(grid_bits, phases)?;
    let raw = raw_triangle_setup_verilog(grid_bits, phases)?;
    Ok(emit(&raw, &unit)?)
}
