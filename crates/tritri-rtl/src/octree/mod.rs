//! The octree engine in hardware (`octree_engine.txt`): plane
//! classification of the grid, the triangle–cell classifier step that bins
//! triangles into the broad phase's leaves, and the filter that reports
//! each pair of the leaves once.
//!
//! * [`axis_step`]: one affine test function of one entry: its value moved
//!   into a child by interpolation, and the eight children's ranges against
//!   the triangle's interval;
//! * [`triangle_setup`]: one triangle per clock, its thirteen test
//!   functions relative to the root cell (the multiplications);
//! * [`cell_classifier`]: thirteen axis steps side by side, one entry
//!   (triangle in a cell) per clock, the children mask out;
//! * [`classify_lane`]: a setup and a classifier step, a triangle and a
//!   cell in, the children it meets out;
//! * [`binning_unit`]: the broad phase's binning unit: triangles streamed in
//!   once, the common box subdivided depth first, the leaves streamed out;
//!   [`binning_machine`] is its cycle-exact model, [`list_packer`] and
//!   [`leaf_cost`] two of its parts (index lists two to a word, the split
//!   rule's leaf cost); [`binning_model`] is the cost formula the planner
//!   and the cycle model charge a cell's pass;
//! * [`leaf_batcher`]: the binning unit's leaf stream as the collision
//!   system's batches (a leaf's frame, an end word per leaf);
//!   [`broad_phase_system`]: the binning unit, the batcher and the system
//!   in one top, triangles in, each leaf's pairs out;
//! * [`list_pass`]: a cell's pass with its lists in external memory over
//!   AXI4, its A and B lists read in bursts and each entry appended to the
//!   lists of the children it meets; [`list_entry`] is the 32-byte entry
//!   (vertices and index), [`child_select`] the child written each clock,
//!   [`list_pass_machine`] the clock-exact model;
//!   [`dram_binning_machine`]: the controller that walks the octree over
//!   such passes, every list in external memory, leaves out as decided,
//!   and [`dram_binning_unit`] that controller in rust-hdl
//!   ([`dram_split_terms`]: its split rule's terms);
//!   [`leaf_reader`]: a leaf's two lists read back for the narrow phase, as
//!   the binning unit's leaf stream ([`leaf_reader_machine`], its model);
//!   [`dram_broad_phase`]: the accelerator with its scene in DRAM, all of
//!   these and the system on one port ([`dram_broad_phase_machine`], its
//!   model to the last verdict);
//! * [`plane_traversal`]: the seed's core circuit, the grid classified
//!   against a plane one octant per clock, with a stack in block RAM
//!   ([`centre_test`]: the half-space test of a level-1 cell's voxels);
//! * [`set_operation_unit`]: union, intersection, difference of two voxel
//!   models streamed a 64-voxel word per clock;
//! * [`voxel_fill`]: cells with children to fill (the plane traversal's
//!   records) written into the voxel memory a word per clock;
//! * [`traversal_stack`]: the two traversals' stack, which cell to issue
//!   each clock and the cells with children left;
//! * [`triangle_voxelizer`]: surface voxelization, triangles in and the
//!   voxels each meets out, the setup and the classifier step driven by a
//!   depth-first traversal; [`voxelizer_machine`] is its cycle model;
//! * [`octant_clipper`]: one octant per clock against a box: inside,
//!   outside or crossing;
//! * [`owner_filter`]: behind the system's result stream, lets each
//!   intersecting pair through once, from the first leaf holding both
//!   triangles.

pub mod axis_step;
pub mod binning_machine;
pub mod binning_model;
pub mod binning_unit;
pub mod broad_phase_system;
pub mod cell_classifier;
pub mod centre_test;
pub mod child_select;
pub mod classify_lane;
pub mod dram_binning_machine;
pub mod dram_binning_unit;
pub mod dram_broad_phase;
pub mod dram_broad_phase_machine;
pub mod dram_split_terms;
pub mod leaf_batcher;
pub mod leaf_cost;
pub mod leaf_reader;
pub mod leaf_reader_machine;
pub mod list_entry;
pub mod list_packer;
pub mod list_pass;
pub mod list_pass_machine;
pub mod octant_clipper;
pub mod octree_builder;
pub mod octree_builder_machine;
pub mod owner_chain_filter;
pub mod owner_filter;
pub mod plane_traversal;
pub mod set_operation_unit;
pub mod traversal_stack;
pub mod triangle_setup;
pub mod triangle_voxelizer;
pub mod voxel_fill;
pub mod voxelizer_machine;

/// Bits of the classifier's values for `grid_bits`-bit coordinates: cell
/// corners stay below `2^(G+1)` in magnitude and gradients below
/// `2^(2G+1)` (a normal), so a value `g · p` stays below `2^(3G+4)` and
/// `δ`, `ε` below `2^(3G+5)`: `3G + 6` signed bits hold everything.
pub const fn value_bits(grid_bits: usize) -> usize {
    3 * grid_bits + 6
}
