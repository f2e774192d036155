//! The emitted triangle voxelizer ([`crate::octree::triangle_voxelizer`]):
//! its name, port meanings and timing.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::octree::cell_classifier::{AXES, CELL_CLASSIFIER_LATENCY};
use crate::octree::triangle_setup::TRIANGLE_SETUP_LATENCY;
use crate::octree::triangle_voxelizer::{
    TriangleVoxelizer, VOXELIZER_GRID_BITS, VOXELIZER_MAX_LEVEL, VOXELIZER_STACK_BITS,
};
use crate::octree::value_bits;
use rust_hdl::prelude::*;
use tritri_geom::octree::voxelize::SUB_BITS;

/// Top module name.
pub const TRIANGLE_VOXELIZER_NAME: &str = "tritri_triangle_voxelizer";

/// rust-hdl's Verilog of the voxelizer.
pub fn raw_triangle_voxelizer_verilog() -> crate::unit::RawDesign {
    const G: usize = VOXELIZER_GRID_BITS;
    let mut uut = TriangleVoxelizer::<
        G,
        { value_bits(G) },
        { AXES * value_bits(G) },
        { 9 * G },
        VOXELIZER_STACK_BITS,
    >::default();
    uut.connect_all();
    crate::unit::RawDesign::of(&uut)
}

pub fn triangle_voxelizer_unit() -> UnitDescription {
    let g = VOXELIZER_GRID_BITS;
    UnitDescription::new(
        TRIANGLE_VOXELIZER_NAME,
        "The octree engine's surface voxelization (octree_engine.txt, boundary representation to voxels): triangles \
         streamed in, the voxels each closed triangle meets streamed out, exactly as \
         tritri_geom::octree::voxelize::surface marks them.",
    )
    .detail(&format!(
        "Per triangle, a setup forms its {AXES} separating-axis functions relative to the grid's origin (the only \
         multiplications); a depth-first traversal then classifies cells from the whole grid down, one cell per clock, \
         each child's values interpolated from its parent's (adds and shifts). Cells met by the triangle go onto a \
         stack whose top is in registers and the rest in block RAM with their {AXES} values; a level-1 cell's \
         children are voxels and leave as a record. The vertices are on a fine grid of 2^{SUB_BITS} steps per voxel."
    ))
    .detail(&format!(
        "Cycles: the setup takes {TRIANGLE_SETUP_LATENCY} clocks and works on the next triangles while the traversal \
         runs; a triangle's functions are loaded the clock its predecessor's traversal is over, and its root issued \
         the clock after. One issue per clock; a result {CELL_CLASSIFIER_LATENCY} clocks after its issue; one clock \
         without an issue when the stack's top comes back from the RAM. Cycle model: \
         tritri_rtl::octree::voxelizer_machine::voxelizer_schedule. The traversal stalls while a record waits for \
         out_ready."
    ))
    .parameter("G", &format!("{g}: bits of a fine-grid coordinate (two's complement)"))
    .parameter("V", &format!("{}: bits of a test function's value, 3G + 6", value_bits(g)))
    .parameter("STACK_DEPTH", &format!("{}: stack entries in block RAM", 1 << VOXELIZER_STACK_BITS))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: idle, stack and setup empty, overflow cleared.")
    .port("level", &format!("The grid is 2^level voxels a side (1 to {VOXELIZER_MAX_LEVEL}); held."))
    .port("in_valid", "A triangle is offered.")
    .port("in_ready", "The unit takes it (its setup advances).")
    .port(
        "in_vertices",
        &format!("x0 y0 z0 x1 y1 z1 x2 y2 z2 from bit 0 up, {g} bits each: fine-grid coordinates in [0, 2^(level + {SUB_BITS})]."),
    )
    .port("busy", "A triangle is in the unit or a record waits.")
    .port("overflow", "Sticky: a push found the stack's RAM full; the records since are incomplete.")
    .port("out_valid", "A record is offered.")
    .port("out_ready", "The reader takes it.")
    .port("out_x", "Low corner of the level-1 cell, in voxels (even).")
    .port("out_y", "Low corner, y.")
    .port("out_z", "Low corner, z.")
    .port("out_mask", "Bit o: the triangle meets voxel o of the cell (bit k of o: upper half along axis k).")
    .throughput("one cell per clock while the stack has work; a triangle's traversal waits for its parents' results.")
}

/// The emitted voxelizer.
pub fn emit_triangle_voxelizer() -> Result<EmittedDesign, EmitError> {
    emit(
        &raw_triangle_voxelizer_verilog(),
        &triangle_voxelizer_unit(),
    )
}
