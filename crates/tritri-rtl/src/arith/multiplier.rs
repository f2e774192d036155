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
//! The Verilog is four register stages around `$signed(a) * $signed(b)`:
//! operand registers, product register, output register and a register
//! in fabric, all gated by `advance` (the global clock enable). The first
//! three are the shape FPGA synthesis maps onto DSP blocks with their
//! internal A/B, M and P registers; the fourth lets the wide products that
//! take two DSP blocks add their partial products after the blocks'
//! output registers (see [`ecp5_verilog`]), so every multiplier has the
//! same latency whatever the mapping. The simulation model is exact: i128
//! products of sign-extended operands.
//!
//! Yosys maps `*` onto ECP5's MULT18X18D without its registers, and
//! post-route that path (an operand register in fabric, across the chip
//! into the multiplier's array) limits a whole pipeline to about 72 MHz.
//! [`ecp5_verilog`] is the same module instantiating MULT18X18D blocks with
//! all three of their registers; the emitter swaps it in with
//! `EmitOptions::multipliers` (`tritri gen --dsp ecp5`).

use super::convert::{from_i128, to_i128, wrap_i128};
use rust_hdl::prelude::*;

/// Clock edges from operands to product.
pub const MULTIPLIER_LATENCY: usize = 4;

#[derive(LogicBlock)]
pub struct Multiplier<const A: usize, const B: usize, const P: usize> {
    pub clock: Signal<In, Clock>,
    /// Global clock enable: when low, every register holds.
    pub advance: Signal<In, Bit>,
    pub a: Signal<In, Bits<A>>,
    pub b: Signal<In, Bits<B>>,
    /// `a * b` modulo `2^P`, `MULTIPLIER_LATENCY` enabled edges after `a`, `b`.
    pub product: Signal<Out, Bits<P>>,
    // Simulation model state (mirrors a_q, b_q, m_q, p_q of the Verilog).
    _a_q: i128,
    _b_q: i128,
    _m_q: i128,
    _p_q: i128,
}

impl<const A: usize, const B: usize, const P: usize> crate::unit::Unit for Multiplier<A, B, P> {
    const LATENCY: Option<usize> = Some(MULTIPLIER_LATENCY);
}

impl<const A: usize, const B: usize, const P: usize> Default for Multiplier<A, B, P> {
    fn default() -> Self {
        assert!(
            P <= A + B && A + B <= 126,
            "multiplier {A} x {B} -> {P} bits is not supported"
        );
        Self {
            clock: Default::default(),
            advance: Default::default(),
            a: Default::default(),
            b: Default::default(),
            product: Default::default(),
            _a_q: 0,
            _b_q: 0,
            _m_q: 0,
            _p_q: 0,
        }
    }
}

impl<const A: usize, const B: usize, const P: usize> Logic for Multiplier<A, B, P> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            self.product.next = from_i128::<P>(self._p_q);
            self._p_q = self._m_q;
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
reg signed [{p1}:0] p_q;
initial begin
    a_q = {A}'d0;
    b_q = {B}'d0;
    m_q = {P}'d0;
    p_q = {P}'d0;
    product = {P}'d0;
end
always @(posedge clock) begin
    if (advance) begin
        a_q <= $signed(a);
        b_q <= $signed(b);
        m_q <= {operands};
        p_q <= m_q;
        product <= $unsigned(p_q);
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
        std::cmp::Ordering::Less => {
            format!("$signed({{{{{}{{a_q[{}]}}}}, a_q}}) * b_q", b - a, a - 1)
        }
        std::cmp::Ordering::Greater => {
            format!("a_q * $signed({{{{{}{{b_q[{}]}}}}, b_q}})", a - b, b - 1)
        }
    }
}

/// The widest product one MULT18X18D takes: 18 x 18 signed bits.
const DSP_BITS: usize = 18;
/// The bits of the low limb when an operand is split over two blocks: an
/// 18-bit signed input holds 17 unsigned bits.
const LOW_LIMB_BITS: usize = DSP_BITS - 1;

/// Whether [`ecp5_verilog`] maps an `A x B` multiplier: one operand of at
/// most 18 bits and the other of at most 35 (two MULT18X18D blocks). The
/// pipeline's widths up to W = 17 qualify.
pub fn ecp5_maps(a: usize, b: usize) -> bool {
    let (narrow, wide) = (a.min(b), a.max(b));
    narrow <= DSP_BITS && wide <= DSP_BITS + LOW_LIMB_BITS
}

/// The body of `Multiplier<A, B, P>` for ECP5 (after the port list), or
/// `None` where [`ecp5_maps`] says no. Same ports, same four clocks of
/// latency, same product modulo `2^P` as the inferred body:
///
/// * one block when both operands fit 18 bits: its input, pipeline and
///   output registers are the first three stages, `product` the fourth;
/// * otherwise the wider operand splits into a low limb of 17 unsigned
///   bits and a signed high limb, one block each, and the fourth stage adds
///   the two partial products, `(hi << 17) + lo`.
///
/// Simulators need [`ECP5_MULT18X18D_MODEL`]; synthesis reads the
/// primitive from Yosys's ECP5 cell library.
pub fn ecp5_verilog(a: usize, b: usize, p: usize) -> Option<String> {
    if !ecp5_maps(a, b) {
        return None;
    }
    // `x` is the operand that stays whole, `y` the one that may split.
    let (x, xb, y, yb) = if a > DSP_BITS {
        ("b", b, "a", a)
    } else {
        ("a", a, "b", b)
    };
    let mut v = format!(
        "// Registered signed multiplier {a} x {b} -> {p} bits (product modulo 2^{p}), on ECP5\n\
         // MULT18X18D blocks with their input, pipeline and output registers.\n"
    );
    v.push_str(&format!(
        "wire [17:0] {x}_x = {};\n",
        sign_extend(x, xb, 0, DSP_BITS)
    ));
    let two = yb > DSP_BITS;
    if two {
        v.push_str(&format!(
            "wire [17:0] {y}_lo = {{1'b0, {y}[{}:0]}};\n",
            LOW_LIMB_BITS - 1
        ));
        v.push_str(&format!(
            "wire [17:0] {y}_hi = {};\n",
            sign_extend(y, yb, LOW_LIMB_BITS, DSP_BITS)
        ));
    } else {
        v.push_str(&format!(
            "wire [17:0] {y}_x = {};\n",
            sign_extend(y, yb, 0, DSP_BITS)
        ));
    }
    v.push_str("// verilator lint_off UNUSED\n");
    let blocks: &[(&str, String)] = if two {
        &[("lo", format!("{y}_lo")), ("hi", format!("{y}_hi"))]
    } else {
        &[("", format!("{y}_x"))]
    };
    for (suffix, _) in blocks {
        v.push_str(&format!("wire [35:0] m{};\n", limb(suffix)));
    }
    v.push_str("// verilator lint_on UNUSED\n");
    for (suffix, y_operand) in blocks {
        v.push_str(&dsp_instance(
            &format!("u_dsp{}", limb(suffix)),
            &format!("{x}_x"),
            y_operand,
            &format!("m{}", limb(suffix)),
        ));
    }
    v.push_str(&format!(
        "initial product = {p}'d0;\nalways @(posedge clock) begin\n    if (advance) begin\n"
    ));
    if two {
        // lo is 35 significant signed bits, hi lands at bit 17.
        let lo = if p <= 36 {
            format!("m_lo[{}:0]", p - 1)
        } else {
            format!("{{{{{}{{m_lo[35]}}}}, m_lo}}", p - 36)
        };
        v.push_str(&format!(
            "        product <= {{m_hi[{}:0], {}'d0}} + {lo};\n",
            p - LOW_LIMB_BITS - 1,
            LOW_LIMB_BITS
        ));
    } else {
        v.push_str(&format!("        product <= m[{}:0];\n", p - 1));
    }
    v.push_str("    end\nend\n");
    Some(v)
}

fn limb(suffix: &str) -> String {
    if suffix.is_empty() {
        String::new()
    } else {
        format!("_{suffix}")
    }
}

/// `name[bits - 1:from]` sign-extended to `to` bits, as a Verilog expression.
fn sign_extend(name: &str, bits: usize, from: usize, to: usize) -> String {
    let width = bits - from;
    let slice = if from == 0 {
        name.to_string()
    } else {
        format!("{name}[{}:{from}]", bits - 1)
    };
    if width == to {
        slice
    } else {
        format!("{{{{{}{{{name}[{}]}}}}, {slice}}}", to - width, bits - 1)
    }
}

/// One MULT18X18D, signed 18 x 18 -> 36, every register on `clock` and
/// enabled by `advance` (the parameters [`ECP5_MULT18X18D_MODEL`] models).
fn dsp_instance(name: &str, a: &str, b: &str, p: &str) -> String {
    let bus = |port: &str, signal: &str, bits: usize| -> Vec<String> {
        (0..bits)
            .map(|i| format!(".{port}{i}({signal}[{i}])"))
            .collect()
    };
    let mut pins = bus("A", a, 18);
    pins.extend(bus("B", b, 18));
    pins.extend((0..18).map(|i| format!(".C{i}(1'b0)")));
    pins.extend(
        [
            "SIGNEDA(1'b1)",
            "SIGNEDB(1'b1)",
            "SOURCEA(1'b0)",
            "SOURCEB(1'b0)",
            "CLK0(clock)",
            "CE0(advance)",
            "RST0(1'b0)",
        ]
        .iter()
        .map(|s| format!(".{s}")),
    );
    pins.extend(bus("P", p, 36));
    let mut v = format!(
        "MULT18X18D #(\n    .REG_INPUTA_CLK(\"CLK0\"), .REG_INPUTA_CE(\"CE0\"), .REG_INPUTA_RST(\"RST0\"),\n    \
         .REG_INPUTB_CLK(\"CLK0\"), .REG_INPUTB_CE(\"CE0\"), .REG_INPUTB_RST(\"RST0\"),\n    \
         .REG_PIPELINE_CLK(\"CLK0\"), .REG_PIPELINE_CE(\"CE0\"), .REG_PIPELINE_RST(\"RST0\"),\n    \
         .REG_OUTPUT_CLK(\"CLK0\"), .REG_OUTPUT_CE(\"CE0\"), .REG_OUTPUT_RST(\"RST0\"),\n    \
         .GSR(\"DISABLED\"), .RESETMODE(\"SYNC\")\n) {name} (\n"
    );
    for chunk in pins.chunks(6) {
        v.push_str(&format!("    {},\n", chunk.join(", ")));
    }
    v.truncate(v.len() - 2);
    v.push_str("\n);\n");
    v
}

/// A simulation model of the Lattice ECP5 MULT18X18D for Icarus and
/// Verilator, for the subset [`ecp5_verilog`] instantiates: A, B, SIGNEDA,
/// SIGNEDB, CLK0, CE0, RST0 and P, each register either absent (`"NONE"`)
/// or on CLK0 / CE0 / RST0 with a synchronous reset, as Lattice's sysDSP
/// usage guide (TN1267) describes them: input registers on A and B, a
/// pipeline register after the multiplier array, an output register on P.
/// Any other setting stops the simulation. It sits inside `` `ifndef
/// SYNTHESIS `` so that Yosys, which defines `SYNTHESIS`, takes the primitive
/// from its own cell library.
pub const ECP5_MULT18X18D_MODEL: &str = r#"`ifndef SYNTHESIS
/* verilator lint_off UNUSED */
/* verilator lint_off DECLFILENAME */
module MULT18X18D #(
    parameter REG_INPUTA_CLK = "NONE",
    parameter REG_INPUTA_CE = "CE0",
    parameter REG_INPUTA_RST = "RST0",
    parameter REG_INPUTB_CLK = "NONE",
    parameter REG_INPUTB_CE = "CE0",
    parameter REG_INPUTB_RST = "RST0",
    parameter REG_PIPELINE_CLK = "NONE",
    parameter REG_PIPELINE_CE = "CE0",
    parameter REG_PIPELINE_RST = "RST0",
    parameter REG_OUTPUT_CLK = "NONE",
    parameter REG_OUTPUT_CE = "CE0",
    parameter REG_OUTPUT_RST = "RST0",
    parameter GSR = "ENABLED",
    parameter RESETMODE = "SYNC"
) (
    input  wire A0, A1, A2, A3, A4, A5, A6, A7, A8, A9, A10, A11, A12, A13, A14, A15, A16, A17,
    input  wire B0, B1, B2, B3, B4, B5, B6, B7, B8, B9, B10, B11, B12, B13, B14, B15, B16, B17,
    input  wire C0, C1, C2, C3, C4, C5, C6, C7, C8, C9, C10, C11, C12, C13, C14, C15, C16, C17,
    input  wire SIGNEDA, SIGNEDB, SOURCEA, SOURCEB, CLK0, CE0, RST0,
    output wire P0, P1, P2, P3, P4, P5, P6, P7, P8, P9, P10, P11, P12, P13, P14, P15, P16, P17,
    output wire P18, P19, P20, P21, P22, P23, P24, P25, P26, P27, P28, P29, P30, P31, P32, P33, P34, P35
);
    wire [17:0] a = {A17, A16, A15, A14, A13, A12, A11, A10, A9, A8, A7, A6, A5, A4, A3, A2, A1, A0};
    wire [17:0] b = {B17, B16, B15, B14, B13, B12, B11, B10, B9, B8, B7, B6, B5, B4, B3, B2, B1, B0};
    initial begin
        if ((REG_INPUTA_CLK != "NONE" && (REG_INPUTA_CLK != "CLK0" || REG_INPUTA_CE != "CE0" || REG_INPUTA_RST != "RST0"))
            || (REG_INPUTB_CLK != "NONE" && (REG_INPUTB_CLK != "CLK0" || REG_INPUTB_CE != "CE0" || REG_INPUTB_RST != "RST0"))
            || (REG_PIPELINE_CLK != "NONE" && (REG_PIPELINE_CLK != "CLK0" || REG_PIPELINE_CE != "CE0" || REG_PIPELINE_RST != "RST0"))
            || (REG_OUTPUT_CLK != "NONE" && (REG_OUTPUT_CLK != "CLK0" || REG_OUTPUT_CE != "CE0" || REG_OUTPUT_RST != "RST0"))
            || RESETMODE != "SYNC") begin
            $display("MULT18X18D model: only registers on CLK0 / CE0 / RST0 with RESETMODE SYNC are modelled");
            $finish;
        end
    end
    reg [17:0] a_q = 18'd0;
    reg [17:0] b_q = 18'd0;
    reg signa_q = 1'b0;
    reg signb_q = 1'b0;
    always @(posedge CLK0) begin
        if (RST0) begin
            a_q <= 18'd0;
            b_q <= 18'd0;
            signa_q <= 1'b0;
            signb_q <= 1'b0;
        end else if (CE0) begin
            a_q <= a;
            b_q <= b;
            signa_q <= SIGNEDA;
            signb_q <= SIGNEDB;
        end
    end
    wire [17:0] a_in = REG_INPUTA_CLK == "NONE" ? a : a_q;
    wire [17:0] b_in = REG_INPUTB_CLK == "NONE" ? b : b_q;
    wire signa_in = REG_INPUTA_CLK == "NONE" ? SIGNEDA : signa_q;
    wire signb_in = REG_INPUTB_CLK == "NONE" ? SIGNEDB : signb_q;
    wire [35:0] a_36 = {{18{signa_in & a_in[17]}}, a_in};
    wire [35:0] b_36 = {{18{signb_in & b_in[17]}}, b_in};
    wire [35:0] m = a_36 * b_36;
    reg [35:0] m_q = 36'd0;
    always @(posedge CLK0) begin
        if (RST0) m_q <= 36'd0;
        else if (CE0) m_q <= m;
    end
    wire [35:0] m_out = REG_PIPELINE_CLK == "NONE" ? m : m_q;
    reg [35:0] p_q = 36'd0;
    always @(posedge CLK0) begin
        if (RST0) p_q <= 36'd0;
        else if (CE0) p_q <= m_out;
    end
    wire [35:0] p = REG_OUTPUT_CLK == "NONE" ? m_out : p_q;
    assign {P35, P34, P33, P32, P31, P30, P29, P28, P27, P26, P25, P24, P23, P22, P21, P20, P19, P18} = p[35:18];
    assign {P17, P16, P15, P14, P13, P12, P11, P10, P9, P8, P7, P6, P5, P4, P3, P2, P1, P0} = p[17:0];
endmodule
/* verilator lint_on DECLFILENAME */
/* verilator lint_on UNUSED */
`endif
"#;

#[cfg(test)]
mod tests {
    use crate::arith::convert::{from_i128, to_i128};
    use crate::arith::multiplier::{Multiplier, MULTIPLIER_LATENCY};
    use crate::arith::unit_vectors::tuples;
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;

    #[test]
    fn multiplier_is_the_exact_product() {
        let mut uut = Multiplier::<25, 49, 74>::default();
        uut.connect_all();
        uut.advance.next = true;
        let a = tuples::<1>(1, 25);
        let b = tuples::<1>(2, 49);
        let pairs: Vec<(i128, i128)> = a.iter().zip(&b).map(|(a, b)| (a[0], b[0])).collect();
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &pairs,
            MULTIPLIER_LATENCY,
            |u, (a, b)| {
                u.a.next = from_i128(*a);
                u.b.next = from_i128(*b);
            },
            |u| to_i128(u.product.val()),
            |(a, b)| a * b,
        );
    }
}
