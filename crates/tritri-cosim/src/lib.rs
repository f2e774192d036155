//! Co-simulation of tritri's hardware against the software models, and the
//! route from a scene or a list of pairs to verdicts.
//!
//! * [`scene_query`]: the route from two objects to their exact pairs as
//!   one call, [`scene_query::find_pairs`]: the host's preparation, the
//!   accelerator on an engine, the uncertain verdicts decided again, the
//!   cycles first in to last out, the checks; typed [`fault::Fault`]s.
//! * [`engine`]: one [`engine::Engine`] (model, rusthdl, icarus,
//!   verilator) and one function per kind of work: [`engine::run_pipeline`]
//!   for a schedule of pairs through a pipeline, [`engine::run_scene`] for
//!   a prepared scene's batches through the system. The command line only
//!   parses arguments and prints what these return.
//! * The pipeline: [`rusthdl_harness`] drives the rust-hdl pipeline
//!   directly; [`pipeline_rtl`] runs its emitted Verilog with
//!   `testbenches/tb_triangle_pipeline.sv` on vector files ([`vectors`]).
//!   Both take a schedule of `tritri_rtl::pipeline::pipeline_for_width::PipelineInput`s
//!   (or a [`stream::TriangleStream`]) and return a
//!   [`stream::StreamResult`], so results compare with `==`.
//! * The system: [`system_harness`] (rust-hdl) and [`system_rtl`] (emitted
//!   Verilog with `testbenches/tb_collision_system.sv`) take the same
//!   batches and return the same [`system_harness::SystemResult`].
//! * The octree classifier and its setup: [`cell_classifier`],
//!   [`triangle_setup`]; surface voxelization: [`triangle_voxelizer`];
//!   voxel → octree conversion: [`octree_builder`].
//! * The AXI4 memory port: [`axi_copy`] (the copy unit that proves the
//!   port) and [`list_pass`] (a cell's pass with its lists in external
//!   memory), each in the clock-exact model, rust-hdl and the emitted
//!   Verilog against `testbenches/axi_memory.sv`; [`dram_binning`] the
//!   planner's tree walked pass by pass with every list in that memory.
//! * [`simulator`]: the one place that compiles and runs a testbench in
//!   Icarus or Verilator; [`suites`]: vector sets every engine's tests share.
pub mod axi_copy;
mod axi_drive;
pub mod binning_unit;
pub mod broad_phase_system;
pub mod cell_classifier;
pub mod cgal;
pub mod cone_unit;
pub mod dram_binning;
pub mod dram_broad_phase;
pub mod dram_query;
pub mod engine;
pub mod fault;
pub mod leaf_reader;
pub mod list_pass;
pub mod octree_builder;
pub mod owner_chain_filter;
pub mod owner_filter;
pub mod patch_tessellator;
pub mod patch_triangles;
pub mod pipeline_rtl;
pub mod plane_traversal;
pub mod rusthdl_harness;
pub mod scene_query;
pub mod shared_rare_cases;
pub mod simulator;
pub mod stream;
pub mod suites;
pub mod system_harness;
pub mod system_rtl;
pub mod triangle_setup;
pub mod triangle_voxelizer;
pub mod vectors;
pub mod voxel_fill;
pub mod voxel_units;
