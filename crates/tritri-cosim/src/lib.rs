//! placeholder
pub mod stream;
pub mod icarus;
pub mod rtl_sim;
pub mod vectors;
pub mod verilator;
pub mod system_harness;
pub mod rusthdl_harness;
pub mod system_verilator;
