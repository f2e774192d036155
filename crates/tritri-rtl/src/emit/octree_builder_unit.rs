//! The emitted octree builder ([`crate::octree::octree_builder`]): its
//! name, port meanings and timing.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::octree::octree_builder::{
    OctreeBuilder, BUILDER_MAX_LEVEL, NODE_EMPTY, NODE_FULL, NODE_MIXED,
};
use rust_hdl::prelude::*;

/// Top module name.
pub const OCTREE_BUILDER_NAME: &str = "tritri_octree_builder";

/// rust-hdl's Verilog of the builder.
pub fn raw_octree_builder_verilog() -> crate::unit::RawDesign {
    let mut uut = OctreeBuilder::default();
    uut.connect_all();
    crate::unit::RawDesign::of(&uut)
}

pub fn octree_builder_unit() -> UnitDescription {
    UnitDescription::new(
        OCTREE_BUILDER_NAME,
        "The octree engine's voxel to octree conversion (octree_engine.txt): a voxel model's bricks (4x4x4 voxels, \
         a 64-bit word) in, one a clock in reverse Morton order, its canonical octree's nodes out in postorder.",
    )
    .detail(
        "Written into a node memory from its top address down, the postorder becomes the preorder of the octree file \
         format (docs/octree-format.md): a node, then its children octant 0 first. A brick that is not uniform is a mixed \
         cell whose eight 2x2x2 cells are written at once. Leaf children above the bricks are held at their \
         parent's level (a count and a type) while they agree, so eight equal leaves become one; the first child that \
         differs, or a mixed brick inside, makes the parent and its ancestors mixed and \
         writes their held leaves first, outermost level first. The result is canonical without a second pass. \
         Cycle model: tritri_rtl::octree::octree_builder_machine::builder_schedule.",
    )
    .detail(
        "Cycles: one per brick taken, one per node written, one per uniform cell passed up a level, one per mixed \
         2x2x2 cell looked at, and one that ends each flush of held leaves. The unit stalls while a node waits for \
         out_ready.",
    )
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: waiting for a model's first cell.")
    .port("level", &format!("The grid is 2^level voxels a side (2 to {BUILDER_MAX_LEVEL}); held for a model."))
    .port("in_valid", "A brick is offered.")
    .port("in_ready", "The unit takes it.")
    .port("in_brick", "Bit 8c + o: voxel o of the brick's 2x2x2 cell c is full (bit k of an octant: upper half along axis k).")
    .port("busy", "A model is under way (some of its cells taken) or a node waits.")
    .port("out_valid", "A node is offered.")
    .port("out_ready", "The writer takes it.")
    .port("out_node", &format!("{NODE_EMPTY}: empty leaf, {NODE_FULL}: full leaf, {NODE_MIXED}: mixed (after its eight children's nodes)."))
    .throughput("one brick or one node per clock.")
}

/// The emitted builder.
pub fn emit_octree_builder() -> Result<EmittedDesign, EmitError> {
    emit(&raw_octree_builder_verilog(), &octree_builder_unit())
}
