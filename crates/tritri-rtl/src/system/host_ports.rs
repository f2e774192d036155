//! The system's host ports as plain values, so that a test bench can drive
//! any generated system top ([`crate::collision_system!`]) through one trait.

use super::SystemConfig;
use rust_hdl::core::bitvec::BitVec;
use rust_hdl::prelude::*;

/// What the host drives in one cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HostInputs {
    pub reset: bool,
    pub in_valid: bool,
    /// End-of-batch word (no triangle).
    pub in_end: bool,
    /// `false`: object A (bases); `true`: object B (streamed).
    pub in_object: bool,
    pub in_id: u32,
    /// `x0 y0 z0 x1 y1 z1 x2 y2 z2`, signed `W`-bit values.
    pub in_coordinates: [i64; 9],
    pub out_ready: bool,
}

/// What the system shows in one cycle (after its inputs have settled).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HostOutputs {
    pub in_ready: bool,
    pub out_valid: bool,
    pub out_id_a: u32,
    pub out_id_b: u32,
    /// The reported pair's verdict on the grid, and its certificate.
    pub out_hit: bool,
    pub out_certain: bool,
    pub done: bool,
    pub results_empty: bool,
    pub overflow: bool,
    pub pairs_tested: u32,
    pub hits: u32,
    pub stall_cycles: u32,
}

/// A system top seen from the host.
pub trait HostPorts: Block {
    fn clock_signal(&mut self) -> &mut Signal<In, Clock>;
    fn set_inputs(&mut self, inputs: &HostInputs);
    fn outputs(&self) -> HostOutputs;
    fn system_config(&self) -> SystemConfig;
    /// rust-hdl's Verilog of the whole system (top module `top`) and its units.
    fn raw_design(&self) -> crate::unit::RawDesign;
}

/// `v` as an `N`-bit two's-complement vector (wraps modulo `2^N`).
pub fn signed_bits<const N: usize>(v: i64) -> Bits<N> {
    let u = v as u64;
    if N <= 32 {
        Bits::from(u & ((1u64 << N) - 1))
    } else {
        let mut b = [false; N];
        for (i, bit) in b.iter_mut().enumerate() {
            *bit = if i < 64 { (u >> i) & 1 == 1 } else { v < 0 };
        }
        Bits::Long(BitVec::from(b))
    }
}
