//! placeholder
pub mod arith;
pub mod pipeline;
pub mod sim_drive;
pub mod emit;
pub mod route;
pub mod synth;
pub mod tools;
pub mod system;
pub mod octree;
pub mod configurations;
pub use configurations::raw_verilog;
