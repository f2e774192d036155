//! The emitted plane traversal ([`crate::octree::plane_traversal`]): its
//! name, port meanings, timing, and the host's preparation of a plane.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
use crate::octree::plane_traversal::{
    PlaneTraversal, CLASSIFY_LATENCY, MAX_LEVEL, PLANE_VALUE_BITS, STACK_ADDRESS_BITS,
};
use rust_hdl::prelude::*;

/// Top module name.
pub const PLANE_TRAVERSAL_NAME: &str = "tritri_plane_traversal";

/// Largest normal component the values' width holds for every level.
pub const MAX_NORMAL_COMPONENT: i64 = 1 << 20;

/// The unit's inputs for one plane, as the host computes them: the plane
/// `n · p = d` on the `2^level` grid, with `d` clamped to one step beyond
/// the values the grid takes (which changes no voxel's class) so that every
/// value fits [`PLANE_VALUE_BITS`] signed bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlaneInputs {
    pub level: u32,
    pub gradient: [i64; 3],
    pub d: i64,
    /// The least value of `n · p` over the grid.
    pub root_min: i64,
    /// `2d - Σn`.
    pub centre_offset: i64,
}

impl PlaneInputs {
    pub fn new(level: u32, normal: [i64; 3], d: i64) -> Result<PlaneInputs, String> {
        if !(1..=MAX_LEVEL).contains(&level) {
            return Err(format!(
                "the plane traversal classifies grids of 2 to {} voxels a side, not 2^{level}",
                1 << MAX_LEVEL
            ));
        }
        if normal.iter().any(|c| c.abs() > MAX_NORMAL_COMPONENT) {
            return Err(format!("normal {normal:?}: components of at most 2^20 in size fit the traversal's {PLANE_VALUE_BITS}-bit values"));
        }
        let side = 1i64 << level;
        let root_min: i64 = normal.iter().map(|&n| (n * side).min(0)).sum();
        let root_max: i64 = normal.iter().map(|&n| (n * side).max(0)).sum();
        let d = d.clamp(root_min - 1, root_max + 1);
        Ok(PlaneInputs {
            level,
            gradient: normal,
            d,
            root_min,
            centre_offset: 2 * d - normal.iter().sum::<i64>(),
        })
    }
}

/// rust-hdl's Verilog of the traversal.
pub fn raw_plane_traversal_verilog() -> crate::unit::RawDesign {
    let mut uut = PlaneTraversal::<STACK_ADDRESS_BITS>::default();
    uut.connect_all();
    crate::unit::RawDesign::of(&uut)
}

pub fn plane_traversal_unit() -> UnitDescription {
    let v = PLANE_VALUE_BITS;
    UnitDescription::new(
        PLANE_TRAVERSAL_NAME,
        "The octree engine's plane classification (octree_engine.txt): the 2^level voxel grid against the plane n.p = d, \
         one octant per clock, children's values interpolated from the parent's (adds and shifts, no multiplier).",
    )
    .detail(
        "For each classified cell a record says which children belong to the half-space n.p <= d as wholes (entirely \
         below the plane; for a level-1 cell, the voxels whose centre is) and, for a level-1 cell, which voxels the \
         closed plane crosses. Crossing children of a cell of level >= 2 are classified in turn, from a stack whose \
         top is in registers and the rest in block RAM. Software model and cycle model: \
         tritri_geom::octree::plane::traversal_schedule.",
    )
    .detail(&format!(
        "Cycles: one issue per clock; a result {CLASSIFY_LATENCY} clocks after its issue; one clock without an issue when \
         the stack's top comes back from the RAM. The unit stalls while a record waits for out_ready."
    ))
    .parameter("VALUE_BITS", &format!("{v}: signed bits of the plane's values (|n_k| <= 2^20, up to 1024 voxels a side)"))
    .parameter("STACK_DEPTH", &format!("{}: stack entries in block RAM", 1 << STACK_ADDRESS_BITS))
    .port("clock", "Clock; every register updates on the rising edge.")
    .port("reset", "Synchronous reset, active high: idle, stack empty.")
    .port("gradient_x", "n_x, two's complement; held from start until busy falls.")
    .port("gradient_y", "n_y.")
    .port("gradient_z", "n_z.")
    .port("d", "The plane's offset d, clamped by the host to [root_min - 1, root_max + 1].")
    .port("root_min", "The least value of n.p over the grid: the sum of min(0, n_k 2^level).")
    .port("centre_offset", "2d - (n_x + n_y + n_z): voxel centres are in the half-space when 2 n.lo + n_x + n_y + n_z <= 2d.")
    .port("level", "The grid is 2^level voxels a side (1 to 10).")
    .port("start", "High for one clock while idle: classify the grid.")
    .port("busy", "From the edge after start until the last record is taken.")
    .port("overflow", "Sticky until reset: a push found the stack's RAM full; the records since are incomplete.")
    .port("out_valid", "A record is offered.")
    .port("out_ready", "The reader takes it.")
    .port("out_x", "Low corner of the classified cell, in voxels.")
    .port("out_y", "Low corner, y.")
    .port("out_z", "Low corner, z.")
    .port("out_level", "The classified cell's level (side 2^level voxels).")
    .port("out_full", "Bit o: child o (bit k of o: upper half along axis k) is in the half-space as a whole.")
    .port("out_crossed", "For a level-1 cell, bit o: the closed plane crosses voxel o; 0 otherwise.")
    .throughput("one octant per clock while the stack has work; the pipeline's 5 clocks show where a cell's children wait for it.")
}

/// The emitted traversal.
pub fn emit_plane_traversal() -> Result<EmittedDesign, EmitError> {
    emit(&raw_plane_traversal_verilog(), &plane_traversal_unit())
}
