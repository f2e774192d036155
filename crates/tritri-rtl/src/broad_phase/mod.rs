//! The collision system's broad phase in hardware: triangles binned into
//! the leaves of an octree over the common box with the octree engine's
//! classifier ([`crate::octree::cell_classifier`]), each leaf's arrays sent
//! to the Devillers–Guigue system ([`crate::system`]), and each
//! intersecting pair let through once.
//!
//! * [`classify_lane`]: a setup and a classifier step, a triangle and a
//!   cell in, the children it meets out;
//! * [`binning_unit`]: the binning unit with its scene on chip: triangles
//!   streamed in once, the common box subdivided depth first, the leaves
//!   streamed out; [`binning_machine`] is its cycle-exact model,
//!   [`list_packer`] and [`leaf_cost`] two of its parts (index lists two to
//!   a word, the split rule's leaf cost); [`binning_cost`] is the cost
//!   formula the planner and the cycle model charge a cell's pass;
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
//! * [`owner_filter`] (a table of slots) and [`owner_chain_filter`] (the
//!   form inside the tops): behind the system's result stream, each
//!   intersecting pair let through once, from the first leaf holding both
//!   triangles.

pub mod binning_cost;
pub mod binning_machine;
pub mod binning_unit;
pub mod broad_phase_system;
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
pub mod owner_chain_filter;
pub mod owner_filter;
