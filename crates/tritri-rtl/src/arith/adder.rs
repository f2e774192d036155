//! Registered wide additions: `a - b` and `a + b + c` modulo `2^N`.
//!
//! The last stage of the cross-product unit (a difference of two products)
//! and of the dot-product unit (a sum of three products), thesis figures
//! 3.9, 3.10, 3.12 and 3.13 (adder, subtractor); the segment-triangle
//! case's third determinant from the other two (two differences, one a
//! stage). Results wrap modulo `2^N`, exact whenever the true value fits in
//! `N` signed bits, which the widths of `tritri_geom::widths` guarantee.
//!
//! Like [`super::multiplier::Multiplier`], these are primitives with custom
//! Verilog and an exact i128 simulation model evaluated only at clock edges:
//! rust-hdl simulates values wider than 32 bits as bit arrays, and doing the
//! arithmetic there on every delta cycle dominated the simulation time.

use super::convert::{from_i128, to_i128, wrap_i128};
use rust_hdl::prelude::*;

/// Clock edges from operands to result.
pub const ADDER_LATENCY: usize = 1;

/// `difference = a - b` (mod `2^N`), registered.
#[derive(LogicBlock, Default)]
pub struct RegisteredDifference<const N: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: Signal<In, Bits<N>>,
    pub b: Signal<In, Bits<N>>,
    pub difference: Signal<Out, Bits<N>>,
}

impl<const N: usize> crate::unit::Unit for RegisteredDifference<N> {
    const LATENCY: Option<usize> = Some(ADDER_LATENCY);
}

impl<const N: usize> Logic for RegisteredDifference<N> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            let v = wrap_i128(to_i128(self.a.val()) - to_i128(self.b.val()), N);
            self.difference.next = from_i128::<N>(v);
        }
    }

    fn connect(&mut self) {
        self.difference.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "\
// Registered {N}-bit difference (modulo 2^{N}).
initial difference = {N}'d0;
always @(posedge clock) begin
    if (advance) begin
        difference <= a - b;
    end
end
"
        ))
    }
}

/// Clock edges from operands to [`RegisteredSum3::sum`].
pub const SUM3_LATENCY: usize = 2;

/// `sum = a + b + c` (mod `2^N`), in two register stages: `a + b` and `c`,
/// then their sum, one carry chain each. (In one stage, two carry chains
/// in series behind the multipliers' long wires; the sum then fans out to
/// the sign, its certificate's comparisons and the third determinant:
/// W = 16 on ECP5, 6.7 ns of 6.67 at the plane sides' distances.)
#[derive(LogicBlock, Default)]
pub struct RegisteredSum3<const N: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: Signal<In, Bits<N>>,
    pub b: Signal<In, Bits<N>>,
    pub c: Signal<In, Bits<N>>,
    pub sum: Signal<Out, Bits<N>>,
    // Simulation model state: the first stage's registers.
    _ab: i128,
    _c: i128,
}

impl<const N: usize> crate::unit::Unit for RegisteredSum3<N> {
    const LATENCY: Option<usize> = Some(SUM3_LATENCY);
}

impl<const N: usize> Logic for RegisteredSum3<N> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            self.sum.next = from_i128::<N>(wrap_i128(self._ab + self._c, N));
            self._ab = wrap_i128(to_i128(self.a.val()) + to_i128(self.b.val()), N);
            self._c = to_i128(self.c.val());
        }
    }

    fn connect(&mut self) {
        self.sum.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "\
// {N}-bit sum of three (modulo 2^{N}) in two register stages.
reg [{n1}:0] ab_q;
reg [{n1}:0] c_q;
initial begin
    ab_q = {N}'d0;
    c_q = {N}'d0;
    sum = {N}'d0;
end
always @(posedge clock) begin
    if (advance) begin
        ab_q <= a + b;
        c_q <= c;
        sum <= ab_q + c_q;
    end
end
",
            n1 = N - 1
        ))
    }
}
