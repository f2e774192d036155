//! Registered signed multiplier `A x B -> P` bits, the one arithmetic block
//! that rust-hdl 0.46 cannot express (its `*` is 16 x 16 only).
//!
//! Thesis, chapter 3: the 25 x 25 and 25 x 51 bit multipliers of the
//! cross-product and dot-product units. Here `P <= A + B`: the product is
//! taken modulo `2^P`, which is exact whenever the caller knows the true
//! product fits in `P` signed bits (differences of W-bit coordinates are at
//! most `2^W - 1` in magnitude, so a `(W+1) x (W+1)` product fits in
//! `2W + 1` bits; see `tritri_geom::widths`).
//!
//! The Verilog is three register stages around `$signed(a) * $signed(b)`:
//! operand registers, product register, output register, all gated by
//! `advance` (the global clock enable). This is the shape FPGA synthesis
//! maps onto DSP blocks with their internal A/B, M and P registers. The
//! simulation model is exact: i128 products of sign-extended operands.

use super::convert::{from_i128, to_i128, wrap_i128};
use rust_hdl::prelude::*;

/// Clock edges from operands to product.
pub const MULTIPLIER_LATENCY: usize = 3;

#[derive(LogicBlock)]
pub struct Multiplier<const A: usize, const B: usize, const P: usize> {
    pub clock: Signal<In, Clock>,
    /// Global clock enable: when low, every register holds.
    pub advance: Signal<In, Bit>,
    pub a: Signal<In, Bits<A>>,
    pub b: Signal<In, Bits<B>>,
    /// `a * b` modulo `2^P`, `MULTIPLIER_LATENCY` enabled edges after `a`, `b`.
    pub product: Signal<Out, Bits<P>>,
    // Simulation model state (mirrors a_q, b_q, m_q of the Verilog).
    _a_q: i128,
    _b_q: i128,
    _m_q: i128,
}

impl<const A: usize, const B: usize, const P: usize> Default for Multiplier<A, B, P> {
    fn default() -> Self {
        assert!(P <= A + B && A + B <= 126, "multiplier {A} x {B} -> {P} bits is not supported");
        Self {
            clock: Default::default(),
            advance: Default::default(),
            a: Default::default(),
            b: Default::default(),
            product: Default::default(),
            _a_q: 0,
            _b_q: 0,
            _m_q: 0,
        }
    }
}

impl<const A: usize, const B: usize, const P: usize> Logic for Multiplier<A, B, P> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            self.product.next = from_i128::<P>(self._m_q);
            self._m_q = wrap_i128(self._a_q * self._b_q, P);
            self._a_q = to_i128(self.a.val());
            self._b_q = to_i128(self.b.val());
        }
    }

    fn connect(&mut self) {
        self.product.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "\
// Registered signed multiplier {A} x {B} -> {P} bits (product modulo 2^{P}).
reg signed [{a1}:0] a_q;
reg signed [{b1}:0] b_q;
reg signed [{p1}:0] m_q;
initial begin
    a_q = {A}'d0;
    b_q = {B}'d0;
    m_q = {P}'d0;
    product = {P}'d0;
end
always @(posedge clock) begin
    if (advance) begin
        a_q <= $signed(a);
        b_q <= $signed(b);
        m_q <= {operands};
        product <= $unsigned(m_q);
    end
end
",
            a1 = A - 1,
            b1 = B - 1,
            p1 = P - 1,
            operands = signed_operands(A, B),
        ))
    }
}

/// `a_q * b_q` with the narrower operand sign-extended to the wider one's
/// width. Verilog extends both to the context width anyway; spelling it out
/// keeps strict front ends (slang's `-Warith-op-mismatch`) quiet without
/// changing the circuit (Yosys maps it to the same cells).
fn signed_operands(a: usize, b: usize) -> String {
    match a.cmp(&b) {
        std::cmp::Ordering::Equal => "a_q * b_q".to_string(),
        std::cmp::Ordering::Less => format!("$signed({{{{{}{{a_q[{}]}}}}, a_q}}) * b_q", b - a, a - 1),
        std::cmp::Ordering::Greater => format!("a_q * $signed({{{{{}{{b_q[{}]}}}}, b_q}})", a - b, b - 1),
    }
}
