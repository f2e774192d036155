//! The certificate of an orientation sign (`tritri_geom::certificate`):
//! is `|P|` at least the threshold `T` of every admissible move of its
//! entries,
//!
//! ```text
//! T = X + (X >> 19) + Y + (Y >> 19) + 4 Sw + 2^(ke + 2) + 16,
//! X = sum |n_k| - [n_k < 0], Sw = |w|_1, ke = bitlen(|e1|_1 + |e2|_1),
//! Y = 2^(bitlen Sw + ke)?
//! ```
//!
//! Four blocks, none with a multiplier:
//!
//! * [`EdgesBitLength`] (five register stages): `ke` of a triangle's two
//!   edges, once per triangle (with its normal) or per determinant.
//! * [`NormalPart`] (three register stages): `X + (X >> 19)` of a normal,
//!   once for every threshold on it.
//! * [`CertificateThreshold`] (six register stages, beside the dot
//!   product): `T` from `|w_k|`, `ke` and the normal's part.
//! * [`CertainSign`] (one register stage for the sign, like
//!   [`super::sign::SignOf`], three for the certificate): the sign of `P`
//!   and whether its ones' complement magnitude `P ^ (P >> top)` (`|P|` or
//!   `|P| - 1`) is at least `T`, compared as `P >= T` or `P <= !T` by the
//!   sign, each in parts.
//!
//! A bit length is read from the leading one of `2 v + 1`, so that the one
//! sits at bit `bitlen v`, found over two stages from groups of four bits
//! (`two_stage_leading_one_verilog`); each bit of its index is an OR of
//! the one-hot through a constant mask. The first three blocks are
//! primitives with custom Verilog and an exact model of each register,
//! evaluated at clock edges, like the adders (`super::adder`): rust-hdl
//! simulates values wider than 32 bits as bit arrays. They compute in the
//! widths the values need at W-bit coordinates (`D = W + 1`, `C = 2W + 1`,
//! `O = 3W + 2`): `Sw` in `D + 1` bits, `X` in `C + 1`, `T` in `C + 6`.
//!
//! (The earlier certificate compared `P` with `2^(2m + 5)` for the largest
//! entry `2^m`: OR-trees and wiring only, but at W = 24 it sent 0.17 to
//! 0.26 % of a real scene's pairs back to the host.)

use super::convert::{from_i128, to_i128};
use rust_hdl::prelude::*;
use tritri_geom::certificate::{bit_length, ones_complement_magnitude};

/// Clock edges from value and threshold to sign and certificate.
pub const CERTAIN_SIGN_LATENCY: usize = 1;

/// Clock edges from two edges to their `ke`.
pub const EDGES_BIT_LENGTH_LATENCY: usize = 5;

/// Clock edges from `w`, `n` and `ke` to the threshold.
pub const CERTIFICATE_THRESHOLD_LATENCY: usize = 6;

/// The magnitudes `|v_k|` of D-bit two's complement values as the
/// hardware takes them: `negated_k` (`-v_k` modulo `2^D`, unsigned) where
/// `v_k` is negative, else `v_k`.
fn magnitudes_of<const D: usize>(
    v: &[Signal<In, Bits<D>>; 3],
    negated: &[Signal<In, Bits<D>>; 3],
) -> [u128; 3] {
    std::array::from_fn(|k| {
        if to_i128(v[k].val()) < 0 {
            to_i128(negated[k].val()) as u128 & ((1u128 << D) - 1)
        } else {
            to_i128(v[k].val()) as u128
        }
    })
}

/// Verilog: `{name}` = `|v|` of the `bits`-bit two's complement array port
/// element `v` (rust-hdl names the elements `{prefix}$k`, which the
/// emitter renames), chosen by its sign from `v` and the element `negated`
/// (`-v`), `bits` bits wide: `|-2^(bits-1)|` is `2^(bits-1)` unsigned.
fn magnitude_verilog(name: &str, v: &str, negated: &str, bits: usize) -> String {
    let top = bits - 1;
    format!("wire [{top}:0] {name} = {v}[{top}] ? {negated} : {v};\n")
}

/// Verilog: `|v| - [v < 0]` of the `bits`-bit element `v`, `v ^ {bits{v[top]}}`
/// (no carry chain), zero-extended to `width` bits.
fn ones_complement_verilog(v: &str, bits: usize, width: usize) -> String {
    format!(
        "{{{}'d0, {v} ^ {{{bits}{{{v}[{}]}}}}}}",
        width - bits,
        bits - 1
    )
}

/// Verilog: `t0 + t1 + t2` of unsigned terms, each widened by a zero bit
/// (three magnitudes of at most `2^(n-1)` sum below `2^(n+1)`).
fn widened_sum_verilog(terms: [String; 3]) -> String {
    terms.map(|t| format!("{{1'b0, {t}}}")).join(" + ")
}

/// Bits of a group of the two-stage leading one.
const LEAD_GROUP_BITS: usize = 4;

/// Verilog of a leading one over two register stages:
/// `{name}_t_q`, the `width + 1` bits of `2 v + 1`, and `{name}_any_q[g]`,
/// the OR of its group `g` of [`LEAD_GROUP_BITS`] bits (from bit 0; the
/// lowest group's is never needed), are registered; then `{name}_lead`,
/// the one-hot at bit `bitlen v`, takes each bit from its group's higher
/// bits and the higher groups' ORs: at most eight inputs, two LUT levels.
/// The first stage holds the sum that forms `v` and one LUT level.
///
/// Written in one stage, each bit a wide OR of all the bits above, it took
/// three LUT levels behind the sum (the whole W = 16 shared pipeline's
/// critical path at 127.6 MHz, the threshold's `offset_lead_q`; and at
/// 138.7 MHz, timing weight 30, `ke`'s `lead_q`); as a smear (`t | t >> 1`,
/// `>> 2`, ...), a chain of six (117.1 MHz). Returns the declarations and
/// the first stage's statements.
fn two_stage_leading_one_verilog(name: &str, v: &str, width: usize) -> (String, String) {
    let l = width + 1;
    let groups = l.div_ceil(LEAD_GROUP_BITS);
    let top = |g: usize| ((g + 1) * LEAD_GROUP_BITS).min(l) - 1;
    let mut decl = format!(
        "wire [{top}:0] {name}_t = {{{v}, 1'b1}};\nreg [{top}:0] {name}_t_q;\nreg [{}:1] {name}_any_q;\n",
        groups - 1,
        top = l - 1
    );
    let bits: Vec<String> = (0..l)
        .rev()
        .map(|i| {
            let g = i / LEAD_GROUP_BITS;
            let mut terms = vec![format!("{name}_t_q[{i}]")];
            if i < top(g) {
                terms.push(format!("~|{name}_t_q[{}:{}]", top(g), i + 1));
            }
            if g + 1 < groups {
                terms.push(format!("~|{name}_any_q[{}:{}]", groups - 1, g + 1));
            }
            terms.join(" & ")
        })
        .collect();
    decl += &format!(
        "wire [{}:0] {name}_lead = {{\n    {}\n}};\n",
        l - 1,
        bits.join(",\n    ")
    );
    let any: Vec<String> = (1..groups)
        .rev()
        .map(|g| format!("|{name}_t[{}:{}]", top(g), g * LEAD_GROUP_BITS))
        .collect();
    let stage = format!(
        "{name}_t_q <= {name}_t;\n        {name}_any_q <= {{{}}};\n",
        any.join(", ")
    );
    (decl, stage)
}

/// Verilog: the 8-bit index of the `width`-bit one-hot `lead`.
fn index_verilog(lead: &str, width: usize) -> String {
    let bits: Vec<String> = (0..8)
        .rev()
        .filter(|j| width > 1 << j)
        .map(|j| {
            let mask = (0..width)
                .filter(|i| (i >> j) & 1 == 1)
                .fold(0u128, |m, i| m | 1 << i);
            format!("|({lead} & {width}'h{mask:x})")
        })
        .collect();
    let pad = 8 - bits.len();
    format!("{{{pad}'d0, {}}}", bits.join(", "))
}

/// `ke = bitlen(|a|_1 + |b|_1)` of two edges of D-bit differences, in five
/// register stages, each at most one carry chain: the six magnitudes (each
/// a choice between the edge and its negation, which the edge's
/// subtractor forms on a chain of its own,
/// `super::subtractor::TwoWaySubtractor`); the two sums of magnitudes;
/// their sum; `2 sum + 1` and the ORs of its groups of four bits; the
/// leading one and its index.
#[derive(LogicBlock)]
pub struct EdgesBitLength<const D: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: [Signal<In, Bits<D>>; 3],
    /// `-a`, modulo `2^D`.
    pub a_negated: [Signal<In, Bits<D>>; 3],
    pub b: [Signal<In, Bits<D>>; 3],
    /// `-b`, modulo `2^D`.
    pub b_negated: [Signal<In, Bits<D>>; 3],
    /// `ke`, `EDGES_BIT_LENGTH_LATENCY` enabled edges later.
    pub bits: Signal<Out, Bits<8>>,
    // Simulation model state (the Verilog's registers; the leading one as
    // its index).
    _abs_a: [u128; 3],
    _abs_b: [u128; 3],
    _l1_a: u128,
    _l1_b: u128,
    _sum: u128,
    _bits: u128,
}

impl<const D: usize> crate::unit::Unit for EdgesBitLength<D> {
    const LATENCY: Option<usize> = Some(EDGES_BIT_LENGTH_LATENCY);
}

impl<const D: usize> Default for EdgesBitLength<D> {
    fn default() -> Self {
        assert!((2..=64).contains(&D));
        Self {
            clock: Default::default(),
            advance: Default::default(),
            a: Default::default(),
            a_negated: Default::default(),
            b: Default::default(),
            b_negated: Default::default(),
            bits: Default::default(),
            _abs_a: [0; 3],
            _abs_b: [0; 3],
            _l1_a: 0,
            _l1_b: 0,
            _sum: 0,
            _bits: 0,
        }
    }
}

impl<const D: usize> Logic for EdgesBitLength<D> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            self.bits.next = Bits::from(self._bits as u64);
            self._bits = bit_length(self._sum) as u128;
            self._sum = self._l1_a + self._l1_b;
            self._l1_a = self._abs_a.iter().sum();
            self._l1_b = self._abs_b.iter().sum();
            self._abs_a = magnitudes_of(&self.a, &self.a_negated);
            self._abs_b = magnitudes_of(&self.b, &self.b_negated);
        }
    }

    fn connect(&mut self) {
        self.bits.connect();
    }

    fn hdl(&self) -> Verilog {
        // |a_k| <= 2^(D-1) fits D bits; |a|_1 < 3 2^(D-1), D + 1; their sum
        // D + 2.
        let (l1_bits, sum_bits) = (D + 1, D + 2);
        let mut magnitudes = String::new();
        let mut registers = String::new();
        let mut initial = String::new();
        let mut updates = String::new();
        for v in ["a", "b"] {
            for k in 0..3 {
                magnitudes += &magnitude_verilog(
                    &format!("abs_{v}{k}"),
                    &format!("{v}${k}"),
                    &format!("{v}_negated${k}"),
                    D,
                );
                registers += &format!("reg [{}:0] abs_{v}{k}_q;\n", D - 1);
                initial += &format!("    abs_{v}{k}_q = {D}'d0;\n");
                updates += &format!("        abs_{v}{k}_q <= abs_{v}{k};\n");
            }
        }
        let l1 = |v: &str| widened_sum_verilog(std::array::from_fn(|k| format!("abs_{v}{k}_q")));
        let lead = two_stage_leading_one_verilog("sum", "sum_q", sum_bits);
        Verilog::Custom(format!(
            "\
// ke = bitlen(|a|_1 + |b|_1) of two edges (tritri_geom::certificate), in five
// register stages.
{magnitudes}{registers}reg [{l1m}:0] l1_a_q;
reg [{l1m}:0] l1_b_q;
reg [{s1}:0] sum_q;
{lead}initial begin
{initial}    l1_a_q = {l1_bits}'d0;
    l1_b_q = {l1_bits}'d0;
    sum_q = {sum_bits}'d0;
    sum_t_q = {sum_bits_p}'d0;
    sum_any_q = {groups}'d0;
    bits = 8'd0;
end
always @(posedge clock) begin
    if (advance) begin
{updates}        l1_a_q <= {l1_a};
        l1_b_q <= {l1_b};
        sum_q <= {{1'b0, l1_a_q}} + {{1'b0, l1_b_q}};
        {lead_stage}        bits <= {index};
    end
end
",
            l1_a = l1("a"),
            l1_b = l1("b"),
            lead = lead.0,
            lead_stage = lead.1,
            groups = (sum_bits + 1).div_ceil(LEAD_GROUP_BITS) - 1,
            index = index_verilog("sum_lead", sum_bits + 1),
            l1m = l1_bits - 1,
            s1 = sum_bits - 1,
            sum_bits_p = sum_bits + 1,
        ))
    }
}

/// `X + (X >> 19)` of the module docs from a normal `n = e1 × e2` (C-bit),
/// in three register stages, each one carry chain: the ones' complement
/// magnitudes of `n`, the first two summed; `X`
/// (`tritri_geom::certificate::normal_l1`); `X + (X >> 19)`.
///
/// Once per normal, for every threshold on it: a plane side's three
/// thresholds share their plane's. (Each threshold summed the normal
/// itself, three times the same stages, from one register placed by the
/// multipliers or from a copy of its own, and its later stages spread
/// out: the W = 16, P = 1 shared system on ECP5 routed at 144.1 MHz with
/// 8 of its 11 short register inputs in those stages, `normal_part_q` to
/// `partial_q`, 5.3 ns of routing.)
#[derive(LogicBlock)]
pub struct NormalPart<const C: usize, const O: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub normal: [Signal<In, Bits<C>>; 3],
    /// `X + (X >> 19)`, below `2^(C + 2)`, zero-extended to O bits (the
    /// threshold's input, [`CertificateThreshold::normal_part`]),
    /// `NORMAL_PART_LATENCY` enabled edges later.
    pub part: Signal<Out, Bits<O>>,
    // Simulation model state (the Verilog's registers by stage).
    _normal_01: u128,
    _normal_2: u128,
    _normal_l1: u128,
}

/// Clock edges from a normal to its part of the threshold.
pub const NORMAL_PART_LATENCY: usize = 3;

impl<const C: usize, const O: usize> crate::unit::Unit for NormalPart<C, O> {
    const LATENCY: Option<usize> = Some(NORMAL_PART_LATENCY);
}

impl<const C: usize, const O: usize> Default for NormalPart<C, O> {
    fn default() -> Self {
        // X + (X >> 19) < 2^(C + 2) fits the threshold's O bits.
        assert!(C + 2 <= O && O <= 120);
        Self {
            clock: Default::default(),
            advance: Default::default(),
            normal: Default::default(),
            part: Default::default(),
            _normal_01: 0,
            _normal_2: 0,
            _normal_l1: 0,
        }
    }
}

impl<const C: usize, const O: usize> Logic for NormalPart<C, O> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            // Each stage from the one before, last first.
            let l1 = self._normal_l1;
            self.part.next = from_i128::<O>((l1 + (l1 >> 19)) as i128);
            self._normal_l1 = self._normal_01 + self._normal_2;
            // X (normal_l1) as the Verilog sums it.
            let n: [u128; 3] =
                std::array::from_fn(|k| ones_complement_magnitude(to_i128(self.normal[k].val())));
            self._normal_01 = n[0] + n[1];
            self._normal_2 = n[2];
        }
    }

    fn connect(&mut self) {
        self.part.connect();
    }

    fn hdl(&self) -> Verilog {
        // X < 3 2^(C-1) fits C + 1 bits; X + (X >> 19) C + 2.
        let x = C + 1;
        Verilog::Custom(format!(
            "\
// The normal's part of the certificate's threshold: X + (X >> 19),
// X = sum (|n_k| - [n_k < 0]), in three register stages.
reg [{x1}:0] normal_01_q;
reg [{x1}:0] normal_2_q;
reg [{x1}:0] normal_l1_q;
initial begin
    normal_01_q = {x}'d0;
    normal_2_q = {x}'d0;
    normal_l1_q = {x}'d0;
    part = {o}'d0;
end
always @(posedge clock) begin
    if (advance) begin
        normal_01_q <= {n0} + {n1};
        normal_2_q <= {n2};
        normal_l1_q <= normal_01_q + normal_2_q;
        part <= {{{pad}'d0, {normal_part}}};
    end
end
",
            n0 = ones_complement_verilog("normal$0", C, x),
            n1 = ones_complement_verilog("normal$1", C, x),
            n2 = ones_complement_verilog("normal$2", C, x),
            x1 = x - 1,
            o = O,
            pad = O - (x + 1),
            // X >> 19 is zero below 20 bits.
            normal_part = if x > 19 {
                format!(
                    "{{1'b0, normal_l1_q}} + {{20'd0, normal_l1_q[{}:19]}}",
                    x - 1
                )
            } else {
                "{1'b0, normal_l1_q}".to_string()
            },
        ))
    }
}

/// `T` of the module docs from the magnitudes of the offset `w` (`|w_k|`,
/// D bits unsigned) and `ke` (in the same clock), and the normal's part
/// `X + (X >> 19)` ([`NormalPart`]) three clocks later, as the fourth
/// stage takes it, in six register stages, each at most one carry chain or
/// one LUT tree:
///
/// 1. `Sw = |w|_1`; `2^(ke + 2) + 16`;
/// 2. `2 Sw + 1` and the ORs of its groups of four bits;
///    `4 Sw + 2^(ke + 2) + 16`;
/// 3. `bitlen Sw`, the index of the leading one of `2 Sw + 1` (two LUT
///    levels each);
/// 4. the exponent `bitlen Sw + ke`; the two parts' sum (the normal's
///    straight from the input: a register beside this unit forms it);
/// 5. `Y + (Y >> 19)`, a one shifted by the exponent;
/// 6. `T`.
///
/// (A first version took `w` itself and summed its magnitudes in the
/// stage that formed them, two carry chains in series: the W = 8
/// pipeline's critical path on ECP5. The offsets' units now form the
/// magnitudes beside the differences, `super::subtractor::MagnitudeSubtractor`.
/// Stage 3 registered the leading one and stage 4 took its index before
/// the exponent's carry chain: 5 of the 9 register inputs short of 150 MHz
/// on the whole W = 16 shared pipeline, timing weight 30.)
#[derive(LogicBlock)]
pub struct CertificateThreshold<const D: usize, const C: usize, const O: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// `|w_k|` of the offset `w = d - a`, at most `2^(D-1)`.
    pub offset_magnitude: [Signal<In, Bits<D>>; 3],
    /// `ke` of `b - a`, `c - a` ([`EdgesBitLength`]).
    pub edges_bits: Signal<In, Bits<8>>,
    /// `X + (X >> 19)` of `n = (b - a) × (c - a)` ([`NormalPart`]),
    /// `NORMAL_PART_DELAY` enabled edges after the offset.
    pub normal_part: Signal<In, Bits<O>>,
    /// `T`, `CERTIFICATE_THRESHOLD_LATENCY` enabled edges after the offset.
    pub threshold: Signal<Out, Bits<O>>,
    // Simulation model state (the Verilog's registers by stage; the
    // leading one as its index).
    _offset_l1: u128,
    _edge_term: u128,
    _edges_bits: u128,
    _offset_t: u128,
    _small_part: u128,
    _edges_bits_2: u128,
    _bits_w: u128,
    _small_part_2: u128,
    _edges_bits_3: u128,
    _exponent: u128,
    _partial: u128,
    _y: u128,
    _partial_2: u128,
}

/// Clock edges from the offset to the normal's part at the threshold's
/// input (its fourth stage adds it): a normal taken with the offset goes
/// through [`NormalPart`] first.
pub const NORMAL_PART_DELAY: usize = 3;

impl<const D: usize, const C: usize, const O: usize> crate::unit::Unit
    for CertificateThreshold<D, C, O>
{
    const LATENCY: Option<usize> = Some(CERTIFICATE_THRESHOLD_LATENCY);
}

impl<const D: usize, const C: usize, const O: usize> Default for CertificateThreshold<D, C, O> {
    fn default() -> Self {
        // The pipeline's widths: C = 2D - 1, O = 3D - 1; T < 2^(C + 6) <= 2^O.
        assert!(D >= 7 && C == 2 * D - 1 && O == 3 * D - 1 && O <= 120);
        Self {
            clock: Default::default(),
            advance: Default::default(),
            offset_magnitude: Default::default(),
            edges_bits: Default::default(),
            normal_part: Default::default(),
            threshold: Default::default(),
            _offset_l1: 0,
            _edge_term: 0,
            _edges_bits: 0,
            _offset_t: 0,
            _small_part: 0,
            _edges_bits_2: 0,
            _bits_w: 0,
            _small_part_2: 0,
            _edges_bits_3: 0,
            _exponent: 0,
            _partial: 0,
            _y: 0,
            _partial_2: 0,
        }
    }
}

impl<const D: usize, const C: usize, const O: usize> Logic for CertificateThreshold<D, C, O> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            let t_mask = (1u128 << (C + 6)) - 1;
            let small_mask = (1u128 << (D + 6)) - 1;
            // Each stage from the one before, last first.
            self.threshold.next = from_i128::<O>(((self._partial_2 + self._y) & t_mask) as i128);
            let one = if self._exponent < (C + 6) as u128 {
                1u128 << self._exponent
            } else {
                0
            };
            self._y = one | (one >> 19);
            self._partial_2 = self._partial;
            self._exponent = (self._bits_w + self._edges_bits_3) & 0xff;
            // The part's bits above the sum's are zero.
            let normal_part = to_i128(self.normal_part.val()) as u128 & t_mask;
            self._partial = (normal_part + self._small_part_2) & t_mask;
            self._bits_w = bit_length(self._offset_t) as u128;
            self._small_part_2 = self._small_part;
            self._edges_bits_3 = self._edges_bits_2;
            self._offset_t = self._offset_l1;
            self._small_part = (4 * self._offset_l1 + self._edge_term) & small_mask;
            self._edges_bits_2 = self._edges_bits;
            self._offset_l1 = self
                .offset_magnitude
                .iter()
                .map(|m| m.val().to_u128())
                .sum();
            let ke = self.edges_bits.val().to_u64() as u128;
            let edge_term = if ke + 2 < (D + 6) as u128 {
                4u128 << ke
            } else {
                0
            };
            self._edge_term = (edge_term + 16) & small_mask;
            self._edges_bits = ke;
        }
    }

    fn connect(&mut self) {
        self.threshold.connect();
    }

    fn hdl(&self) -> Verilog {
        // Sw <= 3 2^(D-1) fits D + 1 bits; X + (X >> 19) C + 2; 4 Sw +
        // 2^(ke + 2) + 16 (ke <= D + 2) D + 6; T C + 6.
        let (sw, small, t) = (D + 1, D + 6, C + 6);
        let part = C + 2;
        let lead = two_stage_leading_one_verilog("offset", "offset_l1_q", sw);
        Verilog::Custom(format!(
            "\
// The certificate's threshold (tritri_geom::certificate::threshold):
// T = X + (X >> 19) + Y + (Y >> 19) + 4 Sw + 2^(ke + 2) + 16,
// Sw = |w|_1, Y = 2^(bitlen Sw + ke), with X + (X >> 19) from the normal's
// own unit (NormalPart), in six register stages, each at most one carry
// chain or one LUT tree.
reg [{sw1}:0] offset_l1_q;
reg [{small1}:0] edge_term_q;
reg [7:0] edges_bits_q;
{lead}reg [{small1}:0] small_part_q;
reg [7:0] edges_bits_q2;
reg [7:0] offset_bits_q;
reg [{small1}:0] small_part_q2;
reg [7:0] edges_bits_q3;
reg [7:0] exponent_q;
reg [{t1}:0] partial_q;
reg [{t1}:0] y_q;
reg [{t1}:0] partial_q2;
wire [7:0] offset_bits = {index};
wire [{t1}:0] y_one = {t}'d1 << exponent_q;
// The normal's part is below 2^(C + 2): its higher bits are zero (a
// wire named unused, which Verilator's lint leaves alone).
wire unused_normal_part_bits = |normal_part[{o1}:{part}];
initial begin
    offset_l1_q = {sw}'d0;
    edge_term_q = {small}'d0;
    edges_bits_q = 8'd0;
    offset_t_q = {sw_p}'d0;
    offset_any_q = {groups}'d0;
    small_part_q = {small}'d0;
    edges_bits_q2 = 8'd0;
    offset_bits_q = 8'd0;
    small_part_q2 = {small}'d0;
    edges_bits_q3 = 8'd0;
    exponent_q = 8'd0;
    partial_q = {t}'d0;
    y_q = {t}'d0;
    partial_q2 = {t}'d0;
    threshold = {o}'d0;
end
always @(posedge clock) begin
    if (advance) begin
        offset_l1_q <= {offset_l1};
        edge_term_q <= ({small}'d4 << edges_bits) + {small}'d16;
        edges_bits_q <= edges_bits;
        {lead_stage}        small_part_q <= {{3'd0, offset_l1_q, 2'd0}} + edge_term_q;
        edges_bits_q2 <= edges_bits_q;
        offset_bits_q <= offset_bits;
        small_part_q2 <= small_part_q;
        edges_bits_q3 <= edges_bits_q2;
        exponent_q <= offset_bits_q + edges_bits_q3;
        partial_q <= {{{pad_part}'d0, normal_part[{part1}:0]}} + {{{pad_small}'d0, small_part_q2}};
        y_q <= y_one | (y_one >> 19);
        partial_q2 <= partial_q;
        threshold <= {{{pad_t}'d0, partial_q2 + y_q}};
    end
end
",
            offset_l1 =
                widened_sum_verilog(std::array::from_fn(|k| format!("offset_magnitude${k}"))),
            lead = lead.0,
            lead_stage = lead.1,
            groups = (sw + 1).div_ceil(LEAD_GROUP_BITS) - 1,
            index = index_verilog("offset_lead", sw + 1),
            sw1 = sw - 1,
            small1 = small - 1,
            part1 = part - 1,
            t1 = t - 1,
            o1 = O - 1,
            sw_p = sw + 1,
            pad_part = t - part,
            pad_small = t - small,
            pad_t = O - t,
            o = O,
        ))
    }
}

/// The sign of a determinant, registered, and its certificate two clocks
/// later.
///
/// `P >= T` and `P <= !T`, compared as unsigned O-bit values (for `P >= 0`,
/// `|P| >= T`; for `P < 0`, both in the upper half, `!P >= T`), each in
/// parts of at most [`COMPARE_PART_BITS`] bits. `P` and `T` are first
/// registered beside the comparisons (`value_q`, `threshold_q`, in the
/// sign's stage); every part's `>=` and `<=` (the lowest part's `>=` or
/// `<=` alone) are registered from those copies, and the next stage
/// combines them from the top, `P >= T` being `hi >= & (!(hi <=) | rest)`.
/// A part's `x <= y` is written `{y, 1} > {x, 0}`: written as `>=` and
/// `<=` on the same operands, Yosys made the two one carry chain and took
/// `<=` from it through an equality's LUTs, two levels and 3.5 ns of
/// routing more (W = 16 shared pipeline, ECP5, router1: orient3d's
/// `threshold_q` to `above_le_q1`, the critical path at 141.2 MHz with
/// seed 1; a plane side's, 138.3 MHz with seed 3, 8 of the 13 register
/// inputs short of 150 MHz in such parts).
/// In one stage the comparison was a carry chain over all O bits behind
/// a register placed apart, the clock of the W = 16 plane side on ECP5
/// (121.7 MHz, 53 logic levels, the 50-bit chain's cells) and of the
/// W = 8 pipeline (132.6 MHz). In two halves:
/// 148.7 MHz at W = 8; at W = 16 a 25-bit half's chain behind the value's
/// register was the path again (plane side 136.7, orient3d 141.1 MHz,
/// 26 and 27 logic levels). In parts read straight from `P`, a part's
/// chain behind the value's register, placed by the dot product that
/// computes it, was 7 of the 15 register inputs short of 150 MHz (W = 16,
/// the rare cases shared, 138.0 MHz). The plane sides' signs wait for the
/// decision in delay lines; orient3d's wait for the third determinant's
/// sign, which takes as long as the certificate
/// (`crate::pipeline::third_determinant`).
///
/// Whether `P` is 0 comes with it, in parts, from the sum that computes
/// it ([`super::adder::RegisteredSum3::zero_parts`]); here their AND is
/// registered.
///
/// Custom Verilog with an exact model of its registers, like the
/// threshold's.
#[derive(LogicBlock)]
pub struct CertainSign<const O: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// The determinant `P`, O-bit two's complement.
    pub value: Signal<In, Bits<O>>,
    /// All 1 exactly when `P == 0`, in the same clock as `value`.
    pub value_zero_parts: Signal<In, Bits<O>>,
    /// `T` of the determinant's entries.
    pub threshold: Signal<In, Bits<O>>,
    /// `P < 0`, `CERTAIN_SIGN_LATENCY` enabled edges later.
    pub negative: Signal<Out, Bit>,
    /// `P == 0`.
    pub zero: Signal<Out, Bit>,
    /// `|P| >= T`: the sign holds for every admissible move,
    /// `CERTIFICATE_LATENCY` enabled edges after the value.
    pub certain: Signal<Out, Bit>,
    // Model state: the certificates of the values one and two clocks
    // before, the older first.
    _certain: [bool; 2],
}

/// Clock edges from value and threshold to the certificate.
pub const CERTIFICATE_LATENCY: usize = CERTAIN_SIGN_LATENCY + 2;

/// The widest part [`CertainSign`] compares in one carry chain: two halves
/// at W = 8 (O = 26), four parts at W = 16, six at W = 24. (At 10 bits, three
/// parts at W = 8, that pipeline routed at 141.5 MHz instead of 148.7 on
/// ECP5, its path elsewhere; the W = 16 units as with 13.)
pub const COMPARE_PART_BITS: usize = 13;

/// `[low, high]` bit ranges of O bits in parts of at most
/// [`COMPARE_PART_BITS`], as even as they come, lowest first.
fn compare_parts(o: usize) -> Vec<(usize, usize)> {
    let count = o.div_ceil(COMPARE_PART_BITS);
    let mut parts = Vec::with_capacity(count);
    let mut low = 0;
    for i in 0..count {
        let bits = o / count + usize::from(i < o % count);
        parts.push((low, low + bits - 1));
        low += bits;
    }
    parts
}

/// Verilog: `a >= b` over parts combined from the top, given each part's
/// `{ge}{i}` and `{le}{i}` registers (the lowest part's `{last}` alone):
/// `ge & (~le | rest)` for `>=`; with `ge`, `le` swapped, `<=`.
fn combined_compare_verilog(ge: &str, le: &str, last: &str, parts: usize) -> String {
    let mut text = last.to_string();
    for i in 1..parts {
        // Parenthesised below the top: `&` within `|` draws a lint warning.
        let rest = if i == 1 { text } else { format!("({text})") };
        text = format!("{ge}{i} & (~{le}{i} | {rest})");
    }
    text
}

impl<const O: usize> crate::unit::Unit for CertainSign<O> {
    const LATENCY: Option<usize> = Some(CERTAIN_SIGN_LATENCY);
}

impl<const O: usize> Default for CertainSign<O> {
    fn default() -> Self {
        assert!((4..128).contains(&O));
        Self {
            clock: Default::default(),
            advance: Default::default(),
            value: Default::default(),
            value_zero_parts: Default::default(),
            threshold: Default::default(),
            negative: Default::default(),
            zero: Default::default(),
            certain: Default::default(),
            _certain: [false; 2],
        }
    }
}

impl<const O: usize> Logic for CertainSign<O> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            let mask = (1u128 << O) - 1;
            let p = to_i128(self.value.val());
            let t = to_i128(self.threshold.val()) as u128 & mask;
            self.certain.next = self._certain[0];
            self._certain[0] = self._certain[1];
            // As the Verilog compares: P >= T, or P <= !T, unsigned.
            let unsigned = p as u128 & mask;
            self._certain[1] = if p < 0 {
                unsigned <= !t & mask
            } else {
                unsigned >= t
            };
            self.negative.next = p < 0;
            self.zero.next = self.value_zero_parts.val().all();
        }
    }

    fn connect(&mut self) {
        self.negative.connect();
        self.zero.connect();
        self.certain.connect();
    }

    fn hdl(&self) -> Verilog {
        let parts = compare_parts(O);
        let mut regs = String::new();
        let mut inits = String::new();
        let mut compares = String::new();
        for (i, &(low, high)) in parts.iter().enumerate() {
            let range = format!("[{high}:{low}]");
            // The lowest part needs one comparison per sign. `x <= y` is
            // written `{y, 1} > {x, 0}`: on the same operands as `x >= y`,
            // synthesis would share one carry chain (class doc).
            let names: &[(&str, bool, &str)] = if i == 0 {
                &[
                    ("above_ge_q", true, "threshold_q"),
                    ("below_le_q", false, "limit"),
                ]
            } else {
                &[
                    ("above_ge_q", true, "threshold_q"),
                    ("above_le_q", false, "threshold_q"),
                    ("below_ge_q", true, "limit"),
                    ("below_le_q", false, "limit"),
                ]
            };
            for &(name, at_least, bound) in names {
                regs += &format!("reg {name}{i};\n");
                inits += &format!("    {name}{i} = 1'b0;\n");
                compares += &if at_least {
                    format!("        {name}{i} <= value_q{range} >= {bound}{range};\n")
                } else {
                    format!(
                        "        {name}{i} <= {{{bound}{range}, 1'b1}} > {{value_q{range}, 1'b0}};\n"
                    )
                };
            }
        }
        let above =
            combined_compare_verilog("above_ge_q", "above_le_q", "above_ge_q0", parts.len());
        let below =
            combined_compare_verilog("below_le_q", "below_ge_q", "below_le_q0", parts.len());
        Verilog::Custom(format!(
            "\
// The sign of P, registered, and its certificate |P| >= T two clocks
// later: P and T registered beside the comparisons, then P >= T (P >= 0)
// or P <= ~T (P < 0) as unsigned values, each compared in {count} parts
// whose results are registered, then combined from the top. x <= y is
// written {{y, 1}} > {{x, 0}}, so that synthesis gives it a carry chain of
// its own rather than x >= y's chain and an equality.
reg [{top}:0] value_q;
reg [{top}:0] threshold_q;
wire [{top}:0] limit = ~threshold_q;
// The sign of P registered with the parts' comparisons.
reg compared_negative_q;
{regs}initial begin
    value_q = {o}'d0;
    threshold_q = {o}'d0;
    compared_negative_q = 1'b0;
{inits}    negative = 1'b0;
    zero = 1'b0;
    certain = 1'b0;
end
always @(posedge clock) begin
    if (advance) begin
        negative <= value[{top}];
        zero <= &value_zero_parts;
        value_q <= value;
        threshold_q <= threshold;
        compared_negative_q <= value_q[{top}];
{compares}        certain <= compared_negative_q
            ? {below}
            : {above};
    end
end
",
            count = parts.len(),
            top = O - 1,
            o = O,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::convert::{from_i128, to_i128};
    use tritri_geom::certificate::{bit_length, clears_threshold, normal_l1, threshold};

    fn set_vector<const N: usize>(v: &mut [Signal<In, Bits<N>>; 3], x: [i128; 3]) {
        for k in 0..3 {
            v[k].next = from_i128::<N>(x[k]);
        }
    }

    /// `ke` is the model's bit length of `|a|_1 + |b|_1`, at the extremes
    /// of 9-bit differences (W = 8) and for every bit length of 33-bit ones
    /// (W = 32).
    #[test]
    fn edges_bit_length_is_the_models() {
        let mut uut = EdgesBitLength::<9>::default();
        uut.clock.connect();
        uut.advance.connect();
        uut.a
            .iter_mut()
            .chain(uut.a_negated.iter_mut())
            .chain(uut.b.iter_mut())
            .chain(uut.b_negated.iter_mut())
            .for_each(|s| s.connect());
        uut.connect_all();
        uut.advance.next = true;
        let mut cases: Vec<([i128; 3], [i128; 3])> = Vec::new();
        for x in [-256i128, -255, -1, 0, 1, 2, 3, 127, 128, 255] {
            for y in [0i128, -1, 5, -256, 255] {
                cases.push(([x, y, -x], [y, x, 0]));
            }
        }
        let expect = |(a, b): &([i128; 3], [i128; 3])| {
            let l1 = |v: &[i128; 3]| v.iter().map(|x| x.unsigned_abs()).sum::<u128>();
            bit_length(l1(a) + l1(b)) as u64
        };
        for case in &cases {
            set_vector(&mut uut.a, case.0);
            set_vector(&mut uut.a_negated, case.0.map(|x| -x));
            set_vector(&mut uut.b, case.1);
            set_vector(&mut uut.b_negated, case.1.map(|x| -x));
            for _ in 0..EDGES_BIT_LENGTH_LATENCY {
                crate::sim_drive::clock_cycle(&mut uut, |u| &mut u.clock);
            }
            assert_eq!(uut.bits.val().to_u64(), expect(case), "{case:?}");
        }
        let mut uut = EdgesBitLength::<33>::default();
        uut.clock.connect();
        uut.advance.connect();
        uut.a
            .iter_mut()
            .chain(uut.a_negated.iter_mut())
            .chain(uut.b.iter_mut())
            .chain(uut.b_negated.iter_mut())
            .for_each(|s| s.connect());
        uut.connect_all();
        uut.advance.next = true;
        for bits in 0..33 {
            let x = (1i128 << bits) >> 1;
            let case = ([x, -x, x], [-(1i128 << 32), 0, x]);
            set_vector(&mut uut.a, case.0);
            set_vector(&mut uut.a_negated, case.0.map(|x| -x));
            set_vector(&mut uut.b, case.1);
            set_vector(&mut uut.b_negated, case.1.map(|x| -x));
            for _ in 0..EDGES_BIT_LENGTH_LATENCY {
                crate::sim_drive::clock_cycle(&mut uut, |u| &mut u.clock);
            }
            assert_eq!(uut.bits.val().to_u64(), expect(&case), "{case:?}");
        }
    }

    /// The threshold is `tritri_geom::certificate::threshold` of the same
    /// `w`, `n` and `ke`, for offsets of every bit length, normals around
    /// the `>> 19` and `ke` across its range, at W = 8 (D = 9) and W = 32
    /// (D = 33), the pipeline's inputs streaming a clock apart: the normal
    /// goes through a `NormalPart` taken with the offset, whose part the
    /// threshold reads as it comes.
    #[test]
    fn threshold_is_the_models() {
        check_threshold::<9, 17, 26>();
        check_threshold::<33, 65, 98>();
    }

    fn check_threshold<const D: usize, const C: usize, const O: usize>() {
        const _: () = assert!(NORMAL_PART_LATENCY == NORMAL_PART_DELAY);
        let mut uut = CertificateThreshold::<D, C, O>::default();
        uut.clock.connect();
        uut.advance.connect();
        uut.offset_magnitude.iter_mut().for_each(|s| s.connect());
        uut.normal_part.connect();
        uut.edges_bits.connect();
        uut.connect_all();
        uut.advance.next = true;
        let mut part = NormalPart::<C, O>::default();
        part.clock.connect();
        part.advance.connect();
        part.normal.iter_mut().for_each(|s| s.connect());
        part.connect_all();
        part.advance.next = true;
        let w_top = (1i128 << (D - 1)) - 1;
        let n_top = (1i128 << (C - 1)) - 1;
        let mut cases = Vec::new();
        for bits in 0..D {
            let w = [(1i128 << bits) >> 1, -w_top.min(3), 0];
            for n in [
                [0i128, 0, 0],
                [((1 << 19) - 1).min(n_top), 0, 1],
                [-(1 << 20).min(n_top), 7, 0],
                [n_top, -n_top, n_top],
            ] {
                for ke in [0u32, 1, 7, (D + 2) as u32] {
                    cases.push((w, n, ke));
                }
            }
        }
        cases.push((
            [-w_top - 1, -w_top - 1, -w_top - 1],
            [-n_top - 1; 3],
            (D + 2) as u32,
        ));
        let expect = |(w, n, ke): &([i128; 3], [i128; 3], u32)| {
            let l1 = |v: &[i128; 3]| v.iter().map(|x| x.unsigned_abs()).sum::<u128>();
            threshold(normal_l1(*n), l1(w), *ke)
        };
        // One case a clock: the output then is the case CERTIFICATE_THRESHOLD_LATENCY before.
        for (i, case) in cases.iter().enumerate() {
            for k in 0..3 {
                uut.offset_magnitude[k].next = Bits::from(case.0[k].unsigned_abs() as u64);
            }
            set_vector(&mut part.normal, case.1);
            uut.edges_bits.next = Bits::from(case.2 as u64);
            // The part before this edge, as a wire between the two gives it.
            uut.normal_part.next = part.part.val();
            crate::sim_drive::clock_cycle(&mut uut, |u| &mut u.clock);
            crate::sim_drive::clock_cycle(&mut part, |u| &mut u.clock);
            if i + 1 >= CERTIFICATE_THRESHOLD_LATENCY {
                let earlier = &cases[i + 1 - CERTIFICATE_THRESHOLD_LATENCY];
                let t = to_i128(uut.threshold.val()) as u128;
                assert_eq!(t, expect(earlier), "{earlier:?}");
            }
        }
    }

    /// The certificate is `tritri_geom::certificate::clears_threshold`
    /// around each threshold, two clocks after the sign, at W = 8 and W = 32.
    #[test]
    fn certain_is_the_models_threshold() {
        check_certain::<26>();
        check_certain::<98>();
    }

    fn check_certain<const O: usize>() {
        let mut uut = CertainSign::<O>::default();
        uut.clock.connect();
        uut.advance.connect();
        uut.value.connect();
        uut.threshold.connect();
        uut.connect_all();
        uut.advance.next = true;
        let (lo, hi) = (-(1i128 << (O - 1)), (1i128 << (O - 1)) - 1);
        // The certificate shown is that of the case two before.
        assert_eq!(CERTIFICATE_LATENCY, CERTAIN_SIGN_LATENCY + 2);
        let mut earlier: std::collections::VecDeque<(i128, i128)> = Default::default();
        for bits in 4..(O as u32 - 2) {
            let t = (1i128 << bits) + 3;
            for p in [
                0,
                1,
                -1,
                t - 1,
                t,
                t + 1,
                -t + 1,
                -t,
                -t - 1,
                2 * t,
                -2 * t,
                lo,
                hi,
            ] {
                let p = p.clamp(lo, hi);
                uut.value.next = from_i128::<O>(p);
                // Parts as a sum gives them: here all but one (the
                // part count at O = 26 is 7), or all when P is 0.
                uut.value_zero_parts.next = if p == 0 {
                    from_i128::<O>(-1)
                } else {
                    from_i128::<O>(!(1 << (p.unsigned_abs() % 7)))
                };
                uut.threshold.next = from_i128::<O>(t);
                crate::sim_drive::clock_cycle(&mut uut, |u| &mut u.clock);
                if earlier.len() == 2 {
                    let (p, t) = earlier.pop_front().unwrap();
                    assert_eq!(
                        uut.certain.val(),
                        clears_threshold(p, t as u128),
                        "T {t} P {p}"
                    );
                }
                assert_eq!(uut.negative.val(), p < 0);
                assert_eq!(uut.zero.val(), p == 0);
                earlier.push_back((p, t));
            }
        }
    }
}
