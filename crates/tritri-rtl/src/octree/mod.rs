//! The octree engine in hardware (`octree_engine.txt`): the grid
//! classified against a plane, triangles against cells, voxel models and
//! their set operations, clipping and building. The broad phase of the
//! collision system bins triangles with this engine's classifier; its own
//! units are in [`crate::broad_phase`].
//!
//! * [`axis_step`]: one affine test function of one entry: its value moved
//!   into a child by interpolation, and the eight children's ranges against
//!   the triangle's interval;
//! * [`triangle_setup`]: one triangle per clock, its thirteen test
//!   functions relative to the root cell (the multiplications);
//! * [`cell_classifier`]: thirteen axis steps side by side, one entry
//!   (triangle in a cell) per clock, the children mask out;
//!   [`corner_classifier`] the same for entries set up at their cell's
//!   own corner, of [`corner_step`]s that compare at the gradient's width;
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
//! * [`octree_builder`]: a voxel model to its octree
//!   ([`octree_builder_machine`], its model).

pub mod axis_step;
pub mod cell_classifier;
pub mod centre_test;
pub mod corner_classifier;
pub mod corner_step;
pub mod octant_clipper;
pub mod octree_builder;
pub mod octree_builder_machine;
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
