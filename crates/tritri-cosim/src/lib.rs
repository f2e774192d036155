//! Co-simulation of tritri's hardware against the software models.
//!
//! Every engine takes the same input (a [`stream::TriangleStream`] or a
//! schedule of [`stream::InputCycle`]s) and returns a
//! [`stream::StreamResult`], so results compare with `==`:
//!
//! * [`rusthdl_harness`]: the rust-hdl pipeline, driven directly;
//! * [`icarus`] and [`verilator`]: the emitted Verilog with
//!   `testbenches/tb_triangle_pipeline.sv`, on vector files ([`vectors`]);
//! * [`system_harness`] and [`system_verilator`]: the whole system (memories,
//!   address generator, pipelines, result FIFO).
//!
//! [`suites`] holds vector sets shared by the tests of every engine.
pub mod cell_classifier;
pub mod icarus;
pub mod rtl_sim;
pub mod rusthdl_harness;
pub mod stream;
pub mod suites;
pub mod system_harness;
pub mod system_verilator;
pub mod vectors;
pub mod verilator;
