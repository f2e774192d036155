//! The emitted octree classifier step ([`crate::octree::cell_classifier`]):
//! its name, port meanings and latency.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::octree::cell_classifier::{CellClassifier, AXES, CELL_CLASSIFIER_LATENCY, TAG_BITS};
use crate::octree::value_bits;
use rust_hdl::prelude::*;

/// Grid widths with an emitted classifier (values of `3G + 6` bits must
/// stay within the i128 simulation model).
pub const CLASSIFIER_GRID_WIDTHS: [usize; 3] = [16, 24, 32];

/// Top module name for `grid_bits`-bit grids: `tritri_cell_classifier_g<G>`.
pub fn cell_classifier_unit_name(grid_bits: usize) -> String {
    format!("tritri_cell_classifier_g{grid_bits}")
}

#[derive(Debug, thiserror::Error)]
#[error("no classifier for a {0}-bit grid (have {CLASSIFIER_GRID_WIDTHS:?})")]
pub struct UnsupportedGrid(pub usize);

#[derive(Debug, thiserror::Error)]
pub enum ClassifierEmitError {
    #[error(transparent)]
    Grid(#[from] UnsupportedGrid),
    #[error(transparent)]
    Emit(#[from] EmitError),
}

/// rust-hdl's Verilog of the classifier for `grid_bits`.
pub fn raw_cell_classifier_verilog(
    grid_bits: usize,
) -> Result<crate::unit::RawDesign, UnsupportedGrid> {
    fn raw<const V: usize>() -> crate::unit::RawDesign {
        let mut uut = CellClassifier::<V>::default();
        uut.connect_all();
        crate::unit::RawDesign::of(&uut)
    }
    match grid_bits {
        16 => Ok(raw::<{ value_bits(16) }>()),
        24 => Ok(raw::<{ value_bits(24) }>()),
        32 => Ok(raw::<{ value_bits(32) }>()),
        g => Err(UnsupportedGrid(g)),
    }
}

/// The description of the classifier for the emitter.
pub fn cell_classifier_unit(grid_bits: usize) -> Result<UnitDescription, UnsupportedGrid> {
    if !CLASSIFIER_GRID_WIDTHS.contains(&grid_bits) {
        return Err(UnsupportedGrid(grid_bits));
    }
    let v = value_bits(grid_bits);
    let l = CELL_CLASSIFIER_LATENCY as u64;
    let mut unit = UnitDescription::new(
        &cell_classifier_unit_name(grid_bits),
        &format!(
            "Octree triangle classifier step for a {grid_bits}-bit grid: one entry (a triangle's {AXES} affine test \
             functions over a cell) per clock, the mask of the cell's children the closed triangle meets after {l} clocks."
        ),
    )
    .detail(
        "An entry holds the values of the triangle's test functions at the low corner of a cell (x, y, z, the \
         triangle's plane, and the nine edge-axis cross products: separating axes), the functions' gradients and \
         the triangle's interval along each. With `in_descend` the values are over the parent of the classified \
         cell and are first moved into its child `in_octant` by interpolation: adds and shifts only, as in the \
         octree engine of the seed. A child is met when every function's range over it meets the triangle's \
         interval; the decision is exact (tritri_geom::octree::triangle_cell).",
    )
    .detail("Unused functions are padded with gradient 0 and interval [0, 0], which meet every cell.")
    .parameter("G", &format!("{grid_bits}: grid coordinate width in bits"))
    .parameter("V", &format!("{v}: value width, 3G + 6 (two's complement)"))
    .parameter("AXES", &format!("{AXES}: test functions per triangle"))
    .pipelined_control_ports()
    .port("in_valid", "An entry is on the inputs this cycle.")
    .port("in_tag", &format!("{TAG_BITS}-bit tag of the entry (the controller's index), returned as `out_tag`."))
    .port("in_level", "Level of the classified cell (side 2^level grid steps), at least 1.")
    .port("in_descend", "1: the values are over the parent; classify its child `in_octant` (level `in_level`).")
    .port("in_octant", "Child of the parent (bit k: the upper half along axis k), used with `in_descend`.")
    .port("out_valid", &format!("A mask is on the outputs: the entry entered {l} clocks earlier."))
    .port("out_tag", "Tag of the entry.")
    .port("out_mask", "Bit o: the triangle meets child o of the classified cell (closed cells, touching counts).")
    .latency(l)
    .throughput("one entry per clock while `advance` is high.");
    for i in 0..AXES {
        let axis = |what: &str| format!("{what} of test function {i}, V-bit two's complement.");
        unit = unit
            .port(
                &format!("in_at_lo_{i}"),
                &axis("Value at the cell's (or, with `in_descend`, the parent's) low corner"),
            )
            .port(&format!("in_gradient_x_{i}"), &axis("Gradient x"))
            .port(&format!("in_gradient_y_{i}"), &axis("Gradient y"))
            .port(&format!("in_gradient_z_{i}"), &axis("Gradient z"))
            .port(
                &format!("in_low_{i}"),
                &axis("Low end of the triangle's interval"),
            )
            .port(
                &format!("in_high_{i}"),
                &axis("High end of the triangle's interval"),
            )
            .port(
                &format!("out_at_lo_{i}"),
                &axis("Value at the classified cell's low corner"),
            );
    }
    Ok(unit)
}

/// The emitted classifier for a `grid_bits`-bit grid.
pub fn emit_cell_classifier(grid_bits: usize) -> Result<EmittedDesign, ClassifierEmitError> {
    let unit = cell_classifier_unit(grid_bits)?;
    let raw = raw_cell_classifier_verilog(grid_bits)?;
    Ok(emit(&raw, &unit)?)
}
