//! The emitted set-operation unit ([`crate::octree::set_operation_unit`]),
//! octant clipper ([`crate::octree::octant_clipper`]) and voxel fill
//! ([`crate::octree::voxel_fill`]): names, port meanings and timing.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::octree::octant_clipper::{OctantClipper, CLIPPER_LATENCY};
use crate::octree::set_operation_unit::{SetOperationUnit, WORD_BITS};
use crate::octree::voxel_fill::{VoxelFill, ADDRESS_BITS};
use rust_hdl::prelude::*;

pub const SET_OPERATION_NAME: &str = "tritri_set_operation";
pub const OCTANT_CLIPPER_NAME: &str = "tritri_octant_clipper";
pub const VOXEL_FILL_NAME: &str = "tritri_voxel_fill";

pub fn voxel_fill_unit() -> UnitDescription {
    UnitDescription::new(
        VOXEL_FILL_NAME,
        "The octree engine's memory side: cells with a mask of children to fill (the plane traversal's records) written \
         into the voxel memory, one 64-voxel word per clock.",
    )
    .detail(
        "The memory holds the 2^level grid x fastest, voxel i in bit i % 64 of word i / 64. A full child of side s is s^2 \
         rows, each s / 64 whole words (s >= 64) or s bits of one word; rows x fastest, then y, then z; children in octant \
         order. A record without children to fill costs one clock; the next record is taken with the last write of the \
         previous one.",
    )
    .parameter("ADDRESS_BITS", &format!("{ADDRESS_BITS}: bits of a word address (1024^3 voxels)"))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: idle.")
    .port("level", "The grid is 2^level voxels a side (1 to 10), held.")
    .port("in_valid", "A record is offered.")
    .port("in_ready", "The unit takes it: idle, or sending the last write of the record before.")
    .port("in_x", "The cell's low corner, x, in voxels.")
    .port("in_y", "Low corner, y.")
    .port("in_z", "Low corner, z.")
    .port("in_level", "The cell's level (>= 1); its children's side is 2^(in_level - 1).")
    .port("in_full", "Bit o: fill child o (bit k of o: upper half along axis k).")
    .port("write_valid", "A word write is offered.")
    .port("write_ready", "The memory takes it.")
    .port("write_address", "The word's address.")
    .port("write_mask", "The bits to set: word |= write_mask.")
    .throughput("one word write per clock.")
}

pub fn emit_voxel_fill() -> Result<EmittedDesign, EmitError> {
    let mut uut = VoxelFill::default();
    uut.connect_all();
    emit(&crate::unit::RawDesign::of(&uut), &voxel_fill_unit())
}

pub fn set_operation_unit() -> UnitDescription {
    UnitDescription::new(
        SET_OPERATION_NAME,
        "The octree engine's set operations on two voxel models streamed from memory, one word of 64 voxels per clock: \
         union, intersection, difference.",
    )
    .detail("Words hold voxels x fastest, voxel i in bit i % 64 of word i / 64 (tritri_geom::octree::voxels::VoxelGrid).")
    .parameter("WORD_BITS", &format!("{WORD_BITS}: voxels per word"))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: the output register empty.")
    .port("op", "0: a | b (union); 1: a & b (intersection); 2 or 3: a & ~b (difference a \\ b).")
    .port("in_valid", "A pair of words is offered.")
    .port("in_ready", "The unit takes it: its output register is empty or being read.")
    .port("in_a", "A word of model A.")
    .port("in_b", "The same word of model B.")
    .port("out_valid", "A result word is offered.")
    .port("out_ready", "The reader takes it.")
    .port("out_word", "op(a, b), one clock after the words were taken.")
    .throughput("one word (64 voxels) per clock; a 512^3 model is 2,097,152 words.")
}

pub fn octant_clipper_unit() -> UnitDescription {
    UnitDescription::new(
        OCTANT_CLIPPER_NAME,
        "The octree engine's 3D clipping: one octant per clock against an axis-aligned box of voxels, out as outside (0), \
         inside (1) or crossing (2) (tritri_geom::octree::clip::classify).",
    )
    .detail(&format!(
        "The box is half-open, lo <= v < hi, in voxels, clamped by the host into [0, 2^level]. Latency {CLIPPER_LATENCY} clocks, no stall."
    ))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: no valid output.")
    .port("box_lo_x", "The box's low corner, x (held while octants flow).")
    .port("box_lo_y", "Low corner, y.")
    .port("box_lo_z", "Low corner, z.")
    .port("box_hi_x", "The box's high corner (exclusive), x.")
    .port("box_hi_y", "High corner, y.")
    .port("box_hi_z", "High corner, z.")
    .port("in_valid", "An octant is offered (taken every clock).")
    .port("in_x", "The octant's low corner, x, in voxels.")
    .port("in_y", "Low corner, y.")
    .port("in_z", "Low corner, z.")
    .port("in_level", "The octant's side is 2^in_level voxels (0 to 10).")
    .port("out_valid", "A class is out, for the octant offered two clocks before.")
    .port("out_class", "0 outside the box, 1 inside it, 2 crossing its boundary.")
    .throughput("one octant per clock.")
}

pub fn emit_set_operation() -> Result<EmittedDesign, EmitError> {
    let mut uut = SetOperationUnit::default();
    uut.connect_all();
    emit(&crate::unit::RawDesign::of(&uut), &set_operation_unit())
}

pub fn emit_octant_clipper() -> Result<EmittedDesign, EmitError> {
    let mut uut = OctantClipper::default();
    uut.connect_all();
    emit(&crate::unit::RawDesign::of(&uut), &octant_clipper_unit())
}
