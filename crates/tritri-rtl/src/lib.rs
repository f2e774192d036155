//! The hardware of tritri as rust-hdl units, their cycle and memory models,
//! and the emitter that writes them out as reviewed Verilog packages.
//!
//! * [`arith`]: registered arithmetic primitives in exact widths
//!   (subtractors, multipliers, cross and dot products, signs, the
//!   certificates' sums of magnitudes and thresholds, delay lines);
//! * [`pipeline`]: the Devillers–Guigue pipeline, one unit per step of the
//!   test, its ports ([`pipeline::ports`]), the supported widths (one
//!   list) and the pipeline instantiated at each
//!   ([`pipeline::pipeline_for_width`]), and its emitter description
//!   ([`pipeline::pipeline_unit`]); the system's are beside it in
//!   [`system`];
//! * [`system`]: the thesis's bounding-volume system (memories, address
//!   generator, P pipelines, result FIFO) and its cycle model;
//! * [`octree`]: the octree engine's units (its classifier among them);
//!   [`broad_phase`]: the collision system's broad phase (binning unit,
//!   list passes over DRAM, owner filters, the broad-phase tops);
//!   [`bezier`]: the patch tessellation unit;
//! * [`mod@unit`]: what every unit tells the emitter (its type, latency and
//!   sub-units); [`emit`]: rust-hdl's Verilog to a package an FPGA flow
//!   takes (names, headers, widths, ANSI ports, README, FuseSoC core);
//! * [`synth`], [`route`], [`tools`]: Yosys, nextpnr and the simulators;
//!   [`measured`]: what they measured, kept for reports;
//! * [`sim_drive`]: direct drive of a rust-hdl simulation.
//!
//! docs/ARCHITECTURE.md puts each unit beside its software model and test.
pub mod arith;
pub mod axi;
pub mod bezier;
pub mod broad_phase;
pub mod emit;
pub mod measured;
pub mod octree;
pub mod pipeline;
pub mod route;
pub mod sim_drive;
pub mod synth;
pub mod system;
pub mod tools;
pub mod unit;
pub mod utilisation;
pub use pipeline::pipeline_for_width::raw_design;
