//! One test function of the classifier for an entry at its cell's own
//! corner: the mask of the cell's eight children whose ranges meet the
//! triangle's interval, when the setup took the cell's low corner as its
//! root (the binning lanes, [`crate::broad_phase::classify_lane`]), so the
//! function is zero there and nothing descends.
//!
//! [`super::axis_step`] decides child `o` of a cell of level `l` by
//! `ε ≤ S_o ≤ δ`, with `S_o = 2^(l-1) T_o` (`T_o` the sum of the gradient's
//! components in `o`), `δ = high - 2^(l-1) N` and `ε = low - 2^(l-1) P`
//! (`N`, `P` the sums of its negative and positive components). Dividing by
//! `2^(l-1)`, that is `⌈low / 2^(l-1)⌉ - P ≤ T_o ≤ ⌊high / 2^(l-1)⌋ - N`, exact
//! in integers: two arithmetic shifts of the interval's ends instead of
//! three of the gradient, and the sixteen comparisons at the gradient's
//! width `t` rather than the values' (about `G + 3` bits for an edge where
//! the axis step takes `2G + 5`). The two ends are saturated to `t + 1`
//! bits first, which keeps every comparison's answer: `T_o` lies strictly
//! inside that range.
//!
//! Stages: the shifted ends and the gradient at `t` bits (1); the subset
//! sums, `P` and `N` (2); the ends less `P`, `N`, saturated (3); the
//! comparisons (4). [`CORNER_STEP_LATENCY`] equals the axis step's, so a
//! lane keeps its timing.
//!
//! A custom-Verilog primitive with an exact i128 model evaluated only at
//! clock edges, like [`super::axis_step::AxisStep`].

use super::axis_step::{level_shift, level_shift_verilog, narrow_ports_verilog};
use crate::arith::convert::{to_i128, wrap_i128};
use rust_hdl::prelude::*;

/// Clock edges from an entry to its child mask.
pub const CORNER_STEP_LATENCY: usize = super::axis_step::AXIS_STEP_LATENCY;

#[derive(LogicBlock)]
pub struct CornerStep<const V: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// Level of the cell whose children are classified (>= 1).
    pub level: Signal<In, Bits<6>>,
    pub gradient_x: Signal<In, Bits<V>>,
    pub gradient_y: Signal<In, Bits<V>>,
    pub gradient_z: Signal<In, Bits<V>>,
    /// The triangle's interval along `g`, relative to the cell's corner.
    pub low: Signal<In, Bits<V>>,
    pub high: Signal<In, Bits<V>>,
    /// Bit `o`: child `o`'s range meets `[low, high]`.
    pub mask: Signal<Out, Bits<8>>,
    _s1: Stage1,
    _s2: Stage2,
    _s3: Stage3,
    /// The width of the interval's ends (the axis step's `bits`).
    _bits: usize,
    /// The width of the gradient's sums: every `T_o`, `P`, `N` fits
    /// `gradient_bits` signed bits.
    _gradient_bits: usize,
    /// Bits of the shift `level - 1`, as the axis step's.
    _shift_bits: usize,
}

impl<const V: usize> crate::unit::Unit for CornerStep<V> {
    const LATENCY: Option<usize> = Some(CORNER_STEP_LATENCY);
    fn settings(&self) -> Vec<(&'static str, String)> {
        vec![
            ("bits", self._bits.to_string()),
            ("gradient_bits", self._gradient_bits.to_string()),
            ("shift_bits", self._shift_bits.to_string()),
        ]
    }
}

#[derive(Clone, Copy, Default)]
struct Stage1 {
    g: [i128; 3],
    low: i128,
    high: i128,
}

#[derive(Clone, Copy, Default)]
struct Stage2 {
    sums: [i128; 8],
    negative: i128,
    positive: i128,
    low: i128,
    high: i128,
}

#[derive(Clone, Copy, Default)]
struct Stage3 {
    sums: [i128; 8],
    delta: i128,
    epsilon: i128,
}

impl<const V: usize> CornerStep<V> {
    /// A step for a function whose interval ends fit `bits` signed bits
    /// and whose gradient's sums of up to three components fit
    /// `gradient_bits`, at levels up to `2^shift_bits`.
    pub fn new(bits: usize, gradient_bits: usize, shift_bits: usize) -> Self {
        assert!(
            (8..=127).contains(&V)
                && (8..=V).contains(&bits)
                && (2..bits).contains(&gradient_bits)
                && (1..=6).contains(&shift_bits),
            "corner step of {bits} bits in {V}, sums of {gradient_bits}, {shift_bits}-bit shifts, is not supported"
        );
        Self {
            clock: Default::default(),
            advance: Default::default(),
            level: Default::default(),
            gradient_x: Default::default(),
            gradient_y: Default::default(),
            gradient_z: Default::default(),
            low: Default::default(),
            high: Default::default(),
            mask: Default::default(),
            _s1: Stage1::default(),
            _s2: Stage2::default(),
            _s3: Stage3::default(),
            _bits: bits,
            _gradient_bits: gradient_bits,
            _shift_bits: shift_bits,
        }
    }
}

/// `x` clamped to `bits` signed bits.
fn saturate(x: i128, bits: usize) -> i128 {
    let max = (1i128 << (bits - 1)) - 1;
    x.clamp(-max - 1, max)
}

impl<const V: usize> Logic for CornerStep<V> {
    fn update(&mut self) {
        if !(self.clock.pos_edge() && self.advance.val()) {
            return;
        }
        let (w, t) = (self._bits, self._gradient_bits);
        // Stage 4: comparisons.
        let s3 = self._s3;
        let mask = (0..8)
            .filter(|&o| s3.epsilon <= s3.sums[o] && s3.sums[o] <= s3.delta)
            .fold(0u64, |m, o| m | 1 << o);
        self.mask.next = Bits::from(mask);
        // Stage 3: the ends less P and N, at `w` bits, saturated to `t + 1`.
        let s2 = self._s2;
        self._s3 = Stage3 {
            sums: s2.sums,
            delta: saturate(wrap_i128(s2.high - s2.negative, w), t + 1),
            epsilon: saturate(wrap_i128(s2.low - s2.positive, w), t + 1),
        };
        // Stage 2: subset sums, P, N (each within `t` bits).
        let g = self._s1.g;
        let sum =
            |f: &dyn Fn(usize) -> bool| wrap_i128((0..3).filter(|&k| f(k)).map(|k| g[k]).sum(), t);
        self._s2 = Stage2 {
            sums: std::array::from_fn(|o| sum(&|k| o >> k & 1 == 1)),
            negative: sum(&|k| g[k] < 0),
            positive: sum(&|k| g[k] > 0),
            low: self._s1.low,
            high: self._s1.high,
        };
        // Stage 1: ⌈low / 2^s⌉ = -(-low >> s) and ⌊high / 2^s⌋ = high >> s
        // (arithmetic shifts by `level - 1` in `shift_bits` bits, of the
        // inputs' low `w` bits); the gradient's low `t` bits.
        let shift = level_shift(self.level.val(), self._shift_bits);
        let low = wrap_i128(to_i128(self.low.val()), w);
        let high = wrap_i128(to_i128(self.high.val()), w);
        self._s1 = Stage1 {
            g: [
                self.gradient_x.val(),
                self.gradient_y.val(),
                self.gradient_z.val(),
            ]
            .map(|x| wrap_i128(to_i128(x), t)),
            low: wrap_i128(-(wrap_i128(-low, w) >> shift), w),
            high: high >> shift,
        };
    }

    fn connect(&mut self) {
        self.mask.connect();
    }

    fn hdl(&self) -> Verilog {
        let (w, t, sb) = (self._bits, self._gradient_bits, self._shift_bits);
        let (w1, t1, c) = (w - 1, t - 1, t + 1);
        let c1 = c - 1;
        let shift = level_shift_verilog(sb);
        // The inputs at their widths (the gradient's at its sums').
        let narrow = narrow_ports_verilog(
            &[
                ("gradient_x", t),
                ("gradient_y", t),
                ("gradient_z", t),
                ("low", w),
                ("high", w),
            ],
            V,
        );
        let text = format!(
            "\
// The ends at {w} bits, the gradient's sums at {t}, compared at {c}.
{narrow}\
{shift}\
wire [{w1}:0] minus_low = -low_w;
// Stage 1: the ends divided by 2^(level - 1), rounded inwards.
reg [{t1}:0] g0_1, g1_1, g2_1;
reg [{w1}:0] low_1, high_1;
// Stage 2: the subset sums T_o, and P, N.
reg [{t1}:0] s_2 [0:7];
reg [{t1}:0] negative_2, positive_2;
reg [{w1}:0] low_2, high_2;
// Stage 3: delta = high - N, epsilon = low - P, saturated to {c} bits.
reg [{t1}:0] s_3 [0:7];
reg [{c1}:0] delta_3, epsilon_3;
wire [{w1}:0] delta_w = high_2 - {{{{{wt}{{negative_2[{t1}]}}}}, negative_2}};
wire [{w1}:0] epsilon_w = low_2 - {{{{{wt}{{positive_2[{t1}]}}}}, positive_2}};
// A value fits {c} bits when its bits above them are copies of its sign.
wire delta_fits = delta_w[{w1}:{c1}] == {{{wc}{{delta_w[{w1}]}}}};
wire epsilon_fits = epsilon_w[{w1}:{c1}] == {{{wc}{{epsilon_w[{w1}]}}}};
wire [{c1}:0] delta_sat = delta_fits ? delta_w[{c1}:0] : {{delta_w[{w1}], {{{c1}{{~delta_w[{w1}]}}}}}};
wire [{c1}:0] epsilon_sat = epsilon_fits ? epsilon_w[{c1}:0] : {{epsilon_w[{w1}], {{{c1}{{~epsilon_w[{w1}]}}}}}};
integer i;
initial begin
    g0_1 = {t}'d0; g1_1 = {t}'d0; g2_1 = {t}'d0; low_1 = {w}'d0; high_1 = {w}'d0;
    negative_2 = {t}'d0; positive_2 = {t}'d0; low_2 = {w}'d0; high_2 = {w}'d0;
    delta_3 = {c}'d0; epsilon_3 = {c}'d0;
    for (i = 0; i < 8; i = i + 1) begin
        s_2[i] = {t}'d0;
        s_3[i] = {t}'d0;
    end
    mask = 8'd0;
end
always @(posedge clock) begin
    if (advance) begin
        g0_1 <= gradient_x_w;
        g1_1 <= gradient_y_w;
        g2_1 <= gradient_z_w;
        low_1 <= $unsigned(-($signed(minus_low) >>> shift));
        high_1 <= $unsigned($signed(high_w) >>> shift);

        negative_2 <= (g0_1[{t1}] ? g0_1 : {t}'d0) + (g1_1[{t1}] ? g1_1 : {t}'d0) + (g2_1[{t1}] ? g2_1 : {t}'d0);
        positive_2 <= (g0_1[{t1}] ? {t}'d0 : g0_1) + (g1_1[{t1}] ? {t}'d0 : g1_1) + (g2_1[{t1}] ? {t}'d0 : g2_1);
        s_2[0] <= {t}'d0;
        s_2[1] <= g0_1;
        s_2[2] <= g1_1;
        s_2[3] <= g0_1 + g1_1;
        s_2[4] <= g2_1;
        s_2[5] <= g0_1 + g2_1;
        s_2[6] <= g1_1 + g2_1;
        s_2[7] <= g0_1 + g1_1 + g2_1;
        low_2 <= low_1;
        high_2 <= high_1;

        delta_3 <= delta_sat;
        epsilon_3 <= epsilon_sat;
        for (i = 0; i < 8; i = i + 1) begin
            s_3[i] <= s_2[i];
        end

        for (i = 0; i < 8; i = i + 1) begin
            mask[i] <= $signed(epsilon_3) <= $signed({{s_3[i][{t1}], s_3[i]}}) && $signed({{s_3[i][{t1}], s_3[i]}}) <= $signed(delta_3);
        end
    end
end
",
            wt = w - t,
            wc = w - c + 1,
        );
        Verilog::Custom(text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::convert::from_i128;
    use crate::sim_drive::clock_cycle;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The axis step's test, `ε ≤ 2^(l-1) T_o ≤ δ`, at full width.
    fn reference(g: [i128; 3], low: i128, high: i128, level: u32) -> u8 {
        let q = g.map(|x| x << (level - 1));
        let negative: i128 = q.iter().filter(|x| **x < 0).sum();
        let positive: i128 = q.iter().filter(|x| **x > 0).sum();
        (0..8u8)
            .filter(|&o| {
                let s: i128 = (0..3).filter(|k| o >> k & 1 == 1).map(|k| q[k]).sum();
                low - positive <= s && s <= high - negative
            })
            .fold(0, |m, o| m | 1 << o)
    }

    /// The edge step of a 16-bit grid (ends at 37 bits, sums at 19) and the
    /// plane's (54, 36) decide as the full-width test on random gradients
    /// at their bounds' edges, intervals around the children's ranges and
    /// beyond the comparisons' width (saturation), ends beside the
    /// children's boundaries (rounding), at every level.
    #[test]
    fn decides_as_the_full_width_test() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for (bits, sums, bound) in [(37usize, 19usize, 1i128 << 16), (54, 36, 1i128 << 33)] {
            let mut step = CornerStep::<54>::new(bits, sums, 4);
            step.connect_all();
            step.advance.next = true;
            let (mut met, mut missed) = (0, 0);
            for case in 0..4000 {
                let level = rng.gen_range(1..=16u32);
                let mut g = [0; 3].map(|_| rng.gen_range(-bound + 1..bound));
                if case % 3 == 0 {
                    g[rng.gen_range(0..3usize)] = 0;
                }
                if case % 7 == 0 {
                    g = g.map(|x| if x < 0 { -bound + 1 } else { bound - 1 });
                }
                // Intervals near the children's ranges, or anywhere in the
                // ends' width.
                let reach: i128 = g.iter().map(|x| x.abs()).sum::<i128>() << level;
                let limit = (1i128 << (bits - 2)) - 1;
                // Small gradients with ends a step either side of a
                // multiple of 2^(level - 1): where rounding the ends decides.
                if case % 4 == 1 {
                    g = [0; 3].map(|_| rng.gen_range(-3..=3));
                }
                let near = |rng: &mut ChaCha8Rng| {
                    (rng.gen_range(-12i128..=12) << (level - 1)) + rng.gen_range(-1..=1)
                };
                let (low, high) = if case % 4 == 1 {
                    let (a, b) = (near(&mut rng), near(&mut rng));
                    (a.min(b), a.max(b))
                } else if case % 4 == 0 {
                    let a = rng.gen_range(-limit..=limit);
                    let b = rng.gen_range(-limit..=limit);
                    (a.min(b), a.max(b))
                } else {
                    let a = rng.gen_range(-2 * reach - 2..=2 * reach + 2);
                    let b = a + rng.gen_range(0..=reach + 1);
                    (a.clamp(-limit, limit), b.clamp(-limit, limit))
                };
                step.level.next = (level as u64).into();
                step.gradient_x.next = from_i128::<54>(g[0]);
                step.gradient_y.next = from_i128::<54>(g[1]);
                step.gradient_z.next = from_i128::<54>(g[2]);
                step.low.next = from_i128::<54>(low);
                step.high.next = from_i128::<54>(high);
                for _ in 0..CORNER_STEP_LATENCY {
                    clock_cycle(&mut step, |s| &mut s.clock);
                }
                let mask = step.mask.val().index() as u8;
                assert_eq!(
                    mask,
                    reference(g, low, high, level),
                    "g {g:?}, [{low}, {high}], level {level}, {bits} / {sums} bits"
                );
                met += mask.count_ones();
                missed += 8 - mask.count_ones();
            }
            assert!(
                met > 4000 && missed > 4000,
                "{met} children met, {missed} missed"
            );
        }
    }
}
