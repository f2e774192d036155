//! The segment-triangle case's third determinant, without multipliers.
//!
//! A degenerate triangle spans the segment `[a, b]`; against a proper
//! triangle `p q r` the test needs the signs of `[a, b, p, q]`,
//! `[a, b, q, r]` and `[a, b, r, p]` (`segment_triangle` in
//! devillers_guigue.rs), where `[a, b, c, d] = (b - a) · ((c - a) × (d - a))`.
//! The three cross products `(c - a) × (d - a)` over the triangle's edges
//! sum to `p × q + q × r + r × p` (the terms in `a` cancel), which is the
//! triangle's normal `N = (q - p) × (r - p)`. So the three determinants sum
//! to `(b - a) · N = orient3d(p, q, r, b) - orient3d(p, q, r, a)`: the
//! difference of the segment ends' plane-side values, which the plane side
//! computes for every pair anyway. Hence
//!
//! ```text
//! [a, b, r, p] = (s_b - s_a) - [a, b, p, q] - [a, b, q, r]
//! ```
//!
//! from orient3d units 0 and 1: two subtractions where a third orient3d
//! unit took nine multipliers. `s_b - s_a` is a sum of three orient3d
//! values and may pass `O` bits, but the result is one orient3d value and
//! fits them, so arithmetic modulo `2^O` (residues only) gives it exactly.
//!
//! [`EndsDifference`] forms `s_b - s_a` beside the plane side (2 stages:
//! the two ends' values, then their difference; in one stage the 6:1
//! choice and the subtraction were the W = 8 pipeline's critical path on
//! ECP5, 108 MHz, 13 logic levels);
//! [`ThirdDeterminant`] the determinant and its sign beside units 0 and
//! 1's sign stage (3 stages: `(s_b - s_a) - [a, b, p, q]`, then the sign
//! of that less `[a, b, q, r]`, then the sign again). With both subtractions in one stage,
//! their two carry chains in series into the value's register were 6 of
//! the 15 register inputs short of 150 MHz (W = 16, the rare cases shared,
//! ECP5, 138.0 MHz). The stage costs no latency of its own: units 0 and
//! 1's certificates come as late (`crate::arith::certificate::CertainSign`).
//!
//! The second subtraction gives only the sign and whether its operands are
//! equal, in parts (`RegisteredDifferenceSign`); the third stage registers
//! the sign again and the AND of the parts, on their way to the decision.
//! (From the value's register, the OR of its O bits into the sign's stage
//! was 7.40 ns, W = 16, the rare cases shared, ECP5, seed 1; the
//! operands' equality in one piece, 6.79 ns.)

use crate::arith::adder::{RegisteredDifference, RegisteredDifferenceSign, ADDER_LATENCY};
use crate::arith::sign::SIGN_LATENCY;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from the plane-side values to `s_b - s_a`.
pub const ENDS_DIFFERENCE_LATENCY: usize = 1 + ADDER_LATENCY;
/// Clock edges from the two determinants to the third's sign.
pub const THIRD_DETERMINANT_LATENCY: usize = 2 * ADDER_LATENCY + SIGN_LATENCY;

/// `s_b - s_a` for the degenerate triangle's segment ends `a = low`, `b =
/// high` (T1's when T1 is degenerate, else T2's), from the plane-side
/// values of each triangle's vertices against the other's plane.
#[derive(LogicBlock, Default)]
pub struct EndsDifference<const O: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// T1's vertices against T2's plane, and T2's against T1's.
    pub t1_distance: [Signal<In, Bits<O>>; 3],
    pub t2_distance: [Signal<In, Bits<O>>; 3],
    pub t1_degenerate: Signal<In, Bit>,
    pub t1_segment_low: Signal<In, Bits<2>>,
    pub t1_segment_high: Signal<In, Bits<2>>,
    pub t2_segment_low: Signal<In, Bits<2>>,
    pub t2_segment_high: Signal<In, Bits<2>>,
    /// `s_b - s_a` modulo `2^O`, `ENDS_DIFFERENCE_LATENCY` edges later.
    pub difference: Signal<Out, Bits<O>>,
    low_q: DFF<Bits<O>>,
    high_q: DFF<Bits<O>>,
    subtract: RegisteredDifference<O>,
}

impl<const O: usize> crate::unit::Unit for EndsDifference<O> {
    const LATENCY: Option<usize> = Some(ENDS_DIFFERENCE_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, low_q, high_q, subtract);
    }
}

impl<const O: usize> Logic for EndsDifference<O> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, subtract);
        dff_setup!(self, clock, low_q, high_q);
        self.subtract.advance.next = self.advance.val();
        // Stage 1: the ends' values.
        if self.advance.val() {
            if self.t1_degenerate.val() {
                self.low_q.d.next = self.t1_distance[0].val();
                if self.t1_segment_low.val() == 1 {
                    self.low_q.d.next = self.t1_distance[1].val();
                } else if self.t1_segment_low.val() == 2 {
                    self.low_q.d.next = self.t1_distance[2].val();
                }
                self.high_q.d.next = self.t1_distance[0].val();
                if self.t1_segment_high.val() == 1 {
                    self.high_q.d.next = self.t1_distance[1].val();
                } else if self.t1_segment_high.val() == 2 {
                    self.high_q.d.next = self.t1_distance[2].val();
                }
            } else {
                self.low_q.d.next = self.t2_distance[0].val();
                if self.t2_segment_low.val() == 1 {
                    self.low_q.d.next = self.t2_distance[1].val();
                } else if self.t2_segment_low.val() == 2 {
                    self.low_q.d.next = self.t2_distance[2].val();
                }
                self.high_q.d.next = self.t2_distance[0].val();
                if self.t2_segment_high.val() == 1 {
                    self.high_q.d.next = self.t2_distance[1].val();
                } else if self.t2_segment_high.val() == 2 {
                    self.high_q.d.next = self.t2_distance[2].val();
                }
            }
        }
        // Stage 2: their difference.
        self.subtract.a.next = self.high_q.q.val();
        self.subtract.b.next = self.low_q.q.val();
        self.difference.next = self.subtract.difference.val();
    }
}

/// The segment-triangle case's third orientation sign without multipliers:
/// `[a, b, r, p] = (s_b - s_a) - [a, b, p, q] - [a, b, q, r]`.
#[derive(LogicBlock, Default)]
pub struct ThirdDeterminant<const O: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// `s_b - s_a`, from [`EndsDifference`].
    pub ends_difference: Signal<In, Bits<O>>,
    /// The values of orient3d units 0 and 1.
    pub first: Signal<In, Bits<O>>,
    pub second: Signal<In, Bits<O>>,
    /// `[a, b, r, p] < 0`, `THIRD_DETERMINANT_LATENCY` edges later.
    pub negative: Signal<Out, Bit>,
    /// `[a, b, r, p] == 0`.
    pub zero: Signal<Out, Bit>,
    /// `(s_b - s_a) - [a, b, p, q]`, and `[a, b, q, r]` beside it.
    subtract_first: RegisteredDifference<O>,
    second_q: DFF<Bits<O>>,
    subtract_second: RegisteredDifferenceSign<O>,
    negative_q: DFF<Bit>,
    zero_q: DFF<Bit>,
}

impl<const O: usize> crate::unit::Unit for ThirdDeterminant<O> {
    const LATENCY: Option<usize> = Some(THIRD_DETERMINANT_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            subtract_first,
            second_q,
            subtract_second,
            negative_q,
            zero_q
        );
    }
}

impl<const O: usize> Logic for ThirdDeterminant<O> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, subtract_first, subtract_second);
        dff_setup!(self, clock, second_q, negative_q, zero_q);
        self.subtract_first.advance.next = self.advance.val();
        self.subtract_second.advance.next = self.advance.val();
        // Stage 1: less the first determinant; the second waits beside it.
        self.subtract_first.a.next = self.ends_difference.val();
        self.subtract_first.b.next = self.first.val();
        if self.advance.val() {
            self.second_q.d.next = self.second.val();
        }
        // Stage 2: the sign of the value less the second; stage 3: the
        // sign again, and whether it is 0 from the parts' equalities.
        self.subtract_second.a.next = self.subtract_first.difference.val();
        self.subtract_second.b.next = self.second_q.q.val();
        if self.advance.val() {
            self.negative_q.d.next = self.subtract_second.negative.val();
            self.zero_q.d.next = self.subtract_second.equal_parts.val().all();
        }
        self.negative.next = self.negative_q.q.val();
        self.zero.next = self.zero_q.q.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::arith::convert::{from_i128, to_i128, wrap_i128};
    use crate::pipeline::third_determinant::{
        EndsDifference, ThirdDeterminant, ENDS_DIFFERENCE_LATENCY, THIRD_DETERMINANT_LATENCY,
    };
    use crate::pipeline::unit_vectors::{point, VECTORS};
    use crate::sim_drive::assert_stream_matches;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rust_hdl::prelude::*;
    use tritri_geom::fixed_point::{orient3d_value, FixedPoint3, FixedTriangle};

    /// The segment-triangle case's third determinant: `s_b - s_a` of the
    /// degenerate triangle's chosen ends, then `[a, b, r, p]`'s sign from it and
    /// `[a, b, p, q]`, `[a, b, q, r]` (the identity in
    /// `pipeline::third_determinant`), at W = 24's extremes where the 74-bit
    /// arithmetic wraps.
    #[test]
    fn third_determinant_is_the_models_sign() {
        let mut rng = ChaCha8Rng::seed_from_u64(8);
        // [p, q, r, a, b], and the pair's other triangle's vertices.
        let points: Vec<([FixedPoint3; 5], FixedTriangle)> = (0..VECTORS)
            .map(|k| {
                let pts: [FixedPoint3; 5] = std::array::from_fn(|_| point(&mut rng, k));
                (pts, std::array::from_fn(|_| point(&mut rng, k + 1)))
            })
            .collect();
        let vectors: Vec<_> = points
            .iter()
            .enumerate()
            .map(|(k, &([p, q, r, a, b], other))| {
                // The segment [a, b] among T1's or T2's vertices, its ends at
                // random indices; the other triangle's values are decoys.
                let t1_degenerate = k % 2 == 0;
                let (low, high) = (rng.gen_range(0..3usize), rng.gen_range(0..3usize));
                let mut segment = other;
                segment[low] = a;
                segment[high] = b;
                let side = |t: FixedTriangle| t.map(|v| orient3d_value(p, q, r, v));
                let ends = side(segment);
                let (t1, t2) = if t1_degenerate {
                    (ends, side(other))
                } else {
                    (side(other), ends)
                };
                // s_b - s_a may pass 74 bits (it is a sum of three orient3d
                // values); its residue is what the unit keeps.
                (
                    t1_degenerate,
                    low,
                    high,
                    t1,
                    t2,
                    wrap_i128(ends[high] - ends[low], 74),
                )
            })
            .collect();
        let mut ends = EndsDifference::<74>::default();
        ends.connect_all();
        ends.advance.next = true;
        assert_stream_matches(
            &mut ends,
            |u| &mut u.clock,
            &vectors,
            ENDS_DIFFERENCE_LATENCY,
            |u, (t1_degenerate, low, high, t1, t2, _)| {
                u.t1_degenerate.next = *t1_degenerate;
                for (segment_low, segment_high) in [
                    (&mut u.t1_segment_low, &mut u.t1_segment_high),
                    (&mut u.t2_segment_low, &mut u.t2_segment_high),
                ] {
                    segment_low.next = (*low as u64).into();
                    segment_high.next = (*high as u64).into();
                }
                for v in 0..3 {
                    u.t1_distance[v].next = from_i128(t1[v]);
                    u.t2_distance[v].next = from_i128(t2[v]);
                }
            },
            |u| to_i128(u.difference.val()),
            |(.., difference)| *difference,
        );
        let determinants: Vec<[i128; 4]> = points
            .iter()
            .map(|&([p, q, r, a, b], _)| {
                [
                    wrap_i128(orient3d_value(p, q, r, b) - orient3d_value(p, q, r, a), 74),
                    orient3d_value(a, b, p, q),
                    orient3d_value(a, b, q, r),
                    orient3d_value(a, b, r, p),
                ]
            })
            .collect();
        // Zero determinants too: the unit finds them from its operands.
        assert!(determinants.iter().any(|d| d[3] == 0));
        assert!(determinants.iter().any(|d| d[3] != 0));
        let mut third = ThirdDeterminant::<74>::default();
        third.connect_all();
        third.advance.next = true;
        assert_stream_matches(
            &mut third,
            |u| &mut u.clock,
            &determinants,
            THIRD_DETERMINANT_LATENCY,
            |u, [ends_difference, first, second, _]| {
                u.ends_difference.next = from_i128(*ends_difference);
                u.first.next = from_i128(*first);
                u.second.next = from_i128(*second);
            },
            |u| (u.negative.val(), u.zero.val()),
            |[.., third]| (*third < 0, *third == 0),
        );
    }
}
