//! The octree engine's software model (`octree_engine.txt`): cubic cells on
//! the integer grid, and the classification of cells against affine test
//! functions by the seed's interpolation rule.
//!
//! * [`cell`]: a cell is a closed cube `[lo, lo + size]` with a power-of-two
//!   side on the integer grid; its eight children halve it.
//! * [`affine`]: an affine function `g · p` tracked over a cell by its value
//!   at the low corner and its increments along the three edges. A child's
//!   values are the parent's plus halved increments: adds and shifts, exact
//!   because every corner of a cell of side >= 2 is a grid point (the seed's
//!   "children's corner distances interpolated from the parent's").
//! * [`triangle_cell`]: does a closed triangle meet a closed cell? Thirteen
//!   affine functions (the three coordinates, the triangle's plane, and the
//!   nine edge functions of the three axis projections) decide it exactly.
//!
//! * [`plane`]: the engine's core circuit, a plane against the grid: the
//!   voxels it crosses and the half-space solid, uniform cells filled whole.
//! * [`voxels`]: the voxel model, one bit per voxel.
//! * [`voxelize`]: meshes to voxels, surface and solid, exact on a fine
//!   grid.
//! * [`clip`]: a model against an axis-aligned box, octants inside,
//!   outside or crossing.
//! * [`stack_schedule`]: the cycle model of the engine's depth-first
//!   traversals in hardware (a classifier of fixed latency and a stack).
//! * [`render`]: shaded pictures of voxel models; [`export`]: `.binvox`
//!   and the boundary faces as a mesh.
//! * [`segments`]: display data, the boundary's edges as segments, clipped
//!   exactly against a view box.
//! * [`tree`]: the octree model in preorder, its file format, conversion
//!   both ways and set operations done directly on trees.
//!
//! The collision system's broad phase ([`crate::scene::octree`]) subdivides
//! the common box with [`triangle_cell::TriangleCellTest::children_touched`].

pub mod affine;
pub mod cell;
pub mod clip;
pub mod export;
pub mod plane;
pub mod render;
pub mod segments;
pub mod stack_schedule;
pub mod tree;
pub mod triangle_cell;
pub mod voxelize;
pub mod voxels;
