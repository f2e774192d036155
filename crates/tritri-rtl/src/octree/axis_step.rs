//! One test function of the octree engine's triangle classifier, for one
//! entry (a triangle in a cell): the value at the cell's low corner, moved
//! into a child when the controller descends, and the mask of the cell's
//! eight children whose ranges meet the triangle's interval.
//!
//! The software model is `tritri_geom::octree::triangle_cell`: for
//! `f(p) = g · p` over a cell of level `l`, child `o` (bit `k`: upper half
//! along axis `k`) has its low-corner value at `at_lo + S_o` with
//! `q_k = g_k << (l - 1)` and `S_o = Σ_{k in o} q_k`, and its range is that
//! value plus `[Σ min(0, q_k), Σ max(0, q_k)]`. The range meets
//! `[low, high]` iff `ε <= S_o <= δ` with
//! `δ = high - at_lo - Σ min(0, q_k)` and `ε = low - at_lo - Σ max(0, q_k)`:
//! two subtractions per entry, then eight pairs of comparisons against the
//! eight subset sums of the same three `q_k`. Only adds, shifts and
//! compares; the multiplications were done once, for the root.
//!
//! Descending into child `o` of the previous cell (level `l + 1`) first
//! adds `Σ_{k in o} 2 q_k` to the value: the same interpolation.
//!
//! Stages: shifts (1); descent, subset sums and range ends (2); `δ`, `ε`
//! (3); comparisons (4). Two's complement at the step's width `bits`
//! (at most the ports' `V`), modulo `2^bits`: exact while every value of
//! its function fits `bits` signed bits. [`super::value_bits`] guarantees
//! that at `V` for any function of the grid; a function with small
//! gradients (an axis, an edge) fits fewer, and a step built for it
//! ([`AxisStep::with_bits`]) reads the low `bits` bits of its inputs and
//! is that much smaller.
//!
//! A custom-Verilog primitive with an exact i128 model evaluated only at
//! clock edges, like [`crate::arith::multiplier::Multiplier`].

use crate::arith::convert::{from_i128, to_i128, wrap_i128};
use rust_hdl::prelude::*;

/// Clock edges from an entry to its child mask.
pub const AXIS_STEP_LATENCY: usize = 4;

#[derive(LogicBlock)]
pub struct AxisStep<const V: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// Level of the cell whose children are classified (>= 1).
    pub level: Signal<In, Bits<6>>,
    /// The entry moves into child `octant` of the cell it was in.
    pub descend: Signal<In, Bit>,
    pub octant: Signal<In, Bits<3>>,
    /// `f` at the low corner of the entry's cell (before any descent).
    pub at_lo: Signal<In, Bits<V>>,
    pub gradient_x: Signal<In, Bits<V>>,
    pub gradient_y: Signal<In, Bits<V>>,
    pub gradient_z: Signal<In, Bits<V>>,
    /// The triangle's interval along `g`.
    pub low: Signal<In, Bits<V>>,
    pub high: Signal<In, Bits<V>>,
    /// `f` at the low corner of the classified cell.
    pub value: Signal<Out, Bits<V>>,
    /// Bit `o`: child `o`'s range meets `[low, high]`.
    pub mask: Signal<Out, Bits<8>>,
    _s1: Stage1,
    _s2: Stage2,
    _s3: Stage3,
    /// The width the step computes at (see the module's doc).
    _bits: usize,
    /// Bits of the shift `level - 1` (modulo `2^shift_bits`): 6, or as
    /// many as the largest level a caller gives needs, each bit one stage
    /// of the three barrel shifters.
    _shift_bits: usize,
}

impl<const V: usize> crate::unit::Unit for AxisStep<V> {
    const LATENCY: Option<usize> = Some(AXIS_STEP_LATENCY);
    fn settings(&self) -> Vec<(&'static str, String)> {
        vec![
            ("bits", self._bits.to_string()),
            ("shift_bits", self._shift_bits.to_string()),
        ]
    }
}

#[derive(Clone, Copy, Default)]
struct Stage1 {
    q: [i128; 3],
    step: u8,
    at_lo: i128,
    low: i128,
    high: i128,
}

#[derive(Clone, Copy, Default)]
struct Stage2 {
    sums: [i128; 8],
    value: i128,
    negative: i128,
    positive: i128,
    low: i128,
    high: i128,
}

#[derive(Clone, Copy, Default)]
struct Stage3 {
    sums: [i128; 8],
    value: i128,
    delta: i128,
    epsilon: i128,
}

impl<const V: usize> Default for AxisStep<V> {
    fn default() -> Self {
        Self::with_bits(V, 6)
    }
}

impl<const V: usize> AxisStep<V> {
    /// A step computing at `bits` of its `V`-bit ports: for a function
    /// whose every value (at a corner, its interval's ends, `δ`, `ε`, the
    /// sums) fits `bits` signed bits, so its inputs' higher bits are only
    /// their sign; its `value` is sign-extended back to `V`. It shifts by
    /// `level - 1` modulo `2^shift_bits`, for callers whose levels are at
    /// most `2^shift_bits`.
    pub fn with_bits(bits: usize, shift_bits: usize) -> Self {
        assert!(
            (8..=127).contains(&V) && (8..=V).contains(&bits) && (1..=6).contains(&shift_bits),
            "axis step of {bits} bits in {V}, {shift_bits}-bit shifts, is not supported"
        );
        Self {
            clock: Default::default(),
            advance: Default::default(),
            level: Default::default(),
            descend: Default::default(),
            octant: Default::default(),
            at_lo: Default::default(),
            gradient_x: Default::default(),
            gradient_y: Default::default(),
            gradient_z: Default::default(),
            low: Default::default(),
            high: Default::default(),
            value: Default::default(),
            mask: Default::default(),
            _s1: Stage1::default(),
            _s2: Stage2::default(),
            _s3: Stage3::default(),
            _bits: bits,
            _shift_bits: shift_bits,
        }
    }
}

/// The shift `level - 1` in `shift_bits` bits (Verilog's wrap), as the
/// steps' model computes it.
pub(super) fn level_shift(level: Bits<6>, shift_bits: usize) -> u32 {
    (level.index() as u32).wrapping_sub(1) & ((1u32 << shift_bits) - 1)
}

/// The steps' Verilog wire `shift`, `level - 1` in `shift_bits` bits; the
/// level's bits above the shift's are not read (their names tell
/// Verilator's lint so).
pub(super) fn level_shift_verilog(shift_bits: usize) -> String {
    if shift_bits == 6 {
        "wire [5:0] shift = level - 6'd1;\n".to_string()
    } else {
        format!(
            "wire [{sb1}:0] shift = level[{sb1}:0] - {shift_bits}'d1;\n\
             wire unused_level = ^level[5:{shift_bits}];\n",
            sb1 = shift_bits - 1
        )
    }
}

/// The steps' wires `<port>_w`, each `V`-bit input port at its own width:
/// its low bits (the rest is its sign). The higher bits fold into a wire
/// whose name tells Verilator's lint they are unread on purpose.
pub(super) fn narrow_ports_verilog(ports: &[(&str, usize)], v: usize) -> String {
    let mut narrow = String::new();
    let mut unread = Vec::new();
    for &(port, width) in ports {
        if width == v {
            narrow.push_str(&format!("wire [{}:0] {port}_w = {port};\n", width - 1));
        } else {
            narrow.push_str(&format!(
                "wire [{}:0] {port}_w = {port}[{}:0];\n",
                width - 1,
                width - 1
            ));
            unread.push(format!("{port}[{}:{width}]", v - 1));
        }
    }
    if !unread.is_empty() {
        narrow.push_str(&format!(
            "wire unused_signs = ^{{{}}};\n",
            unread.join(", ")
        ));
    }
    narrow
}

/// `S_o` for the eight octants: the subset sums of `q`.
fn subset_sums(q: [i128; 3], bits: usize) -> [i128; 8] {
    let mut sums = [0i128; 8];
    for (o, s) in sums.iter_mut().enumerate() {
        *s = wrap_i128((0..3).filter(|k| o >> k & 1 == 1).map(|k| q[k]).sum(), bits);
    }
    sums
}

impl<const V: usize> Logic for AxisStep<V> {
    fn update(&mut self) {
        if !(self.clock.pos_edge() && self.advance.val()) {
            return;
        }
        let bits = self._bits;
        // Stage 4: comparisons.
        let s3 = self._s3;
        let mask = (0..8)
            .filter(|&o| s3.epsilon <= s3.sums[o] && s3.sums[o] <= s3.delta)
            .fold(0u64, |m, o| m | 1 << o);
        self.mask.next = Bits::from(mask);
        self.value.next = from_i128::<V>(s3.value);
        // Stage 3: the two differences.
        let s2 = self._s2;
        self._s3 = Stage3 {
            sums: s2.sums,
            value: s2.value,
            delta: wrap_i128(s2.high - s2.value - s2.negative, bits),
            epsilon: wrap_i128(s2.low - s2.value - s2.positive, bits),
        };
        // Stage 2: descent, subset sums, range ends.
        let s1 = self._s1;
        let descent: i128 = (0..3)
            .filter(|k| s1.step >> k & 1 == 1)
            .map(|k| s1.q[k] << 1)
            .sum();
        self._s2 = Stage2 {
            sums: subset_sums(s1.q, bits),
            value: wrap_i128(s1.at_lo + descent, bits),
            negative: wrap_i128(s1.q.iter().filter(|q| **q < 0).sum(), bits),
            positive: wrap_i128(s1.q.iter().filter(|q| **q > 0).sum(), bits),
            low: s1.low,
            high: s1.high,
        };
        // Stage 1: shifts (Verilog's `<<` by `level - 1` in `shift_bits`
        // bits, modulo 2^bits), of the inputs' low `bits` bits.
        let shift = level_shift(self.level.val(), self._shift_bits);
        let octant = self.octant.val().index() as u8;
        let gradient = [
            self.gradient_x.val(),
            self.gradient_y.val(),
            self.gradient_z.val(),
        ];
        self._s1 = Stage1 {
            q: gradient.map(|g| {
                if shift >= bits as u32 {
                    0
                } else {
                    wrap_i128(to_i128(g) << shift, bits)
                }
            }),
            step: if self.descend.val() { octant } else { 0 },
            at_lo: wrap_i128(to_i128(self.at_lo.val()), bits),
            low: wrap_i128(to_i128(self.low.val()), bits),
            high: wrap_i128(to_i128(self.high.val()), bits),
        };
    }

    fn connect(&mut self) {
        self.value.connect();
        self.mask.connect();
    }

    fn hdl(&self) -> Verilog {
        let w = self._bits;
        let w1 = w - 1;
        let shift = level_shift_verilog(self._shift_bits);
        // The inputs at the step's width, and the value back at the ports'.
        let narrow = narrow_ports_verilog(
            &[
                "gradient_x",
                "gradient_y",
                "gradient_z",
                "at_lo",
                "low",
                "high",
            ]
            .map(|p| (p, w)),
            V,
        );
        let widen = if w == V {
            "value_3".to_string()
        } else {
            format!("{{{{{}{{value_3[{w1}]}}}}, value_3}}", V - w)
        };
        let text = format!(
            "\
// The step computes at {w} of the ports' {V} bits.
{narrow}\
// Stage 1: the increments of the children, q_k = g_k << (level - 1).
reg [{w1}:0] q0_1, q1_1, q2_1, at_lo_1, low_1, high_1;
reg [2:0] step_1;
// Stage 2: descent, subset sums S_o, range ends.
reg [{w1}:0] s_2 [0:7];
reg [{w1}:0] value_2, negative_2, positive_2, low_2, high_2;
// Stage 3: delta = high - value - negative, epsilon = low - value - positive.
reg [{w1}:0] s_3 [0:7];
reg [{w1}:0] value_3, delta_3, epsilon_3;
{shift}\
integer i;
initial begin
    q0_1 = {w}'d0; q1_1 = {w}'d0; q2_1 = {w}'d0; at_lo_1 = {w}'d0; low_1 = {w}'d0; high_1 = {w}'d0; step_1 = 3'd0;
    value_2 = {w}'d0; negative_2 = {w}'d0; positive_2 = {w}'d0; low_2 = {w}'d0; high_2 = {w}'d0;
    value_3 = {w}'d0; delta_3 = {w}'d0; epsilon_3 = {w}'d0;
    for (i = 0; i < 8; i = i + 1) begin
        s_2[i] = {w}'d0;
        s_3[i] = {w}'d0;
    end
    value = {V}'d0;
    mask = 8'd0;
end
always @(posedge clock) begin
    if (advance) begin
        q0_1 <= gradient_x_w << shift;
        q1_1 <= gradient_y_w << shift;
        q2_1 <= gradient_z_w << shift;
        at_lo_1 <= at_lo_w;
        low_1 <= low_w;
        high_1 <= high_w;
        step_1 <= descend ? octant : 3'd0;

        value_2 <= at_lo_1 + (step_1[0] ? {{q0_1[{w2}:0], 1'b0}} : {w}'d0)
                           + (step_1[1] ? {{q1_1[{w2}:0], 1'b0}} : {w}'d0)
                           + (step_1[2] ? {{q2_1[{w2}:0], 1'b0}} : {w}'d0);
        negative_2 <= (q0_1[{w1}] ? q0_1 : {w}'d0) + (q1_1[{w1}] ? q1_1 : {w}'d0) + (q2_1[{w1}] ? q2_1 : {w}'d0);
        positive_2 <= (q0_1[{w1}] ? {w}'d0 : q0_1) + (q1_1[{w1}] ? {w}'d0 : q1_1) + (q2_1[{w1}] ? {w}'d0 : q2_1);
        s_2[0] <= {w}'d0;
        s_2[1] <= q0_1;
        s_2[2] <= q1_1;
        s_2[3] <= q0_1 + q1_1;
        s_2[4] <= q2_1;
        s_2[5] <= q0_1 + q2_1;
        s_2[6] <= q1_1 + q2_1;
        s_2[7] <= q0_1 + q1_1 + q2_1;
        low_2 <= low_1;
        high_2 <= high_1;

        value_3 <= value_2;
        delta_3 <= high_2 - value_2 - negative_2;
        epsilon_3 <= low_2 - value_2 - positive_2;
        for (i = 0; i < 8; i = i + 1) begin
            s_3[i] <= s_2[i];
        end

        value <= {widen};
        for (i = 0; i < 8; i = i + 1) begin
            mask[i] <= $signed(epsilon_3) <= $signed(s_3[i]) && $signed(s_3[i]) <= $signed(delta_3);
        end
    end
end
",
            w2 = w - 2,
        );
        Verilog::Custom(text)
    }
}
