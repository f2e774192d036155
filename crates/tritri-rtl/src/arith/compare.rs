//! Registered comparison of two W-bit signed coordinates: `a < b` and
//! `a == b`. Used for the lexicographic segment ends of a degenerate
//! triangle (`shape` in devillers_guigue.rs) and for the collinear cases of
//! the 2D segment tests (`on_segment_2d`).
//!
//! Signed order is the unsigned order of offset binary (`x ^ 2^(W-1)`), so
//! no sign extension is needed. The comparison is written on the
//! complements, `a < b` as `~(b ^ 2^(W-1)) < ~(a ^ 2^(W-1))`, which is the
//! same order reversed: a subtractor of the same operands
//! ([`super::subtractor`], in offset binary too) would otherwise share its
//! carry chain with the comparison (Yosys' `alumacc` takes `a < b` from the
//! borrow of an `a - b` it finds). That chain sits by the multiplier the
//! difference feeds; on ECP5 the comparison's result register then sat
//! across the chip from it, the W = 8 pipeline's critical path (128.5 MHz,
//! 5.9 of 7.8 ns routing). Its own chain costs a few LUTs and lets the
//! placer keep the comparison by its register.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from operands to result.
pub const COMPARE_LATENCY: usize = 1;

#[derive(LogicBlock)]
pub struct CoordinateCompare<const W: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: Signal<In, Bits<W>>,
    pub b: Signal<In, Bits<W>>,
    /// `a < b` (signed).
    pub less: Signal<Out, Bit>,
    /// `a == b`.
    pub equal: Signal<Out, Bit>,
    /// `!2^(W-1)`: offset binary, complemented.
    reversed_order: Constant<Bits<W>>,
    less_q: DFF<Bit>,
    equal_q: DFF<Bit>,
}

impl<const W: usize> crate::unit::Unit for CoordinateCompare<W> {
    const LATENCY: Option<usize> = Some(COMPARE_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, less_q, equal_q);
    }
}

impl<const W: usize> Default for CoordinateCompare<W> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            advance: Default::default(),
            a: Default::default(),
            b: Default::default(),
            less: Default::default(),
            equal: Default::default(),
            reversed_order: Constant::new(Bits::<W>::from((1u64 << (W - 1)) - 1)),
            less_q: Default::default(),
            equal_q: Default::default(),
        }
    }
}

impl<const W: usize> Logic for CoordinateCompare<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, less_q, equal_q);
        if self.advance.val() {
            self.less_q.d.next = (self.b.val() ^ self.reversed_order.val())
                < (self.a.val() ^ self.reversed_order.val());
            // As a wide NOR of the differing bits: written `a == b`, Yosys'
            // `alumacc` took it from the carry chain of `a < b` and then
            // through three LUTs (W = 16 shared pipeline, timing weight
            // 30: the critical path, 141.9 MHz, 5.1 of 7.1 ns routing).
            self.equal_q.d.next = !(self.a.val() ^ self.b.val()).any();
        }
        self.less.next = self.less_q.q.val();
        self.equal.next = self.equal_q.q.val();
    }
}

/// Clock edges from operands to [`SplitCompare`]'s result.
pub const SPLIT_COMPARE_LATENCY: usize = 2;

/// [`CoordinateCompare`] in two register stages, for a place with a clock
/// to spare: the high and low halves are compared apart (`<` and `==` of
/// each, two carry chains and two NORs of half the width), then combined,
/// `a < b = less_high | equal_high & less_low`. The shared rare-case unit
/// forms its 27 comparisons once per job from one register of points; in
/// one stage, a 17-bit chain and the LUTs after it were the W = 16 shared
/// system's critical path on every seed routed (ECP5, 128.6 to 152.7 MHz).
/// The halves are taken by constant shifts, which Yosys folds into wiring
/// and zeros before it sizes the comparisons: both chains are half as
/// long. (A mask leaves the low half's chain at the full width.)
#[derive(LogicBlock)]
pub struct SplitCompare<const W: usize> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub b: Signal<In, Bits<W>>,
    /// `a < b` (signed), `SPLIT_COMPARE_LATENCY` edges later.
    pub less: Signal<Out, Bit>,
    /// `a == b`, with it.
    pub equal: Signal<Out, Bit>,
    /// As [`CoordinateCompare`]'s: the keys `x ^ reversed_order` are in the
    /// reverse of the signed order, and so is each half of them.
    reversed_order: Constant<Bits<W>>,
    /// The low half's width, `W / 2`, the high half's, and the mask of
    /// the low half (for its `==`).
    low_bits: Constant<Bits<8>>,
    high_bits: Constant<Bits<8>>,
    low_mask: Constant<Bits<W>>,
    /// Stage 1: each half.
    less_high_q: DFF<Bit>,
    equal_high_q: DFF<Bit>,
    less_low_q: DFF<Bit>,
    equal_low_q: DFF<Bit>,
    /// Stage 2.
    less_q: DFF<Bit>,
    equal_q: DFF<Bit>,
}

impl<const W: usize> crate::unit::Unit for SplitCompare<W> {
    const LATENCY: Option<usize> = Some(SPLIT_COMPARE_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            less_high_q,
            equal_high_q,
            less_low_q,
            equal_low_q,
            less_q,
            equal_q
        );
    }
}

impl<const W: usize> Default for SplitCompare<W> {
    fn default() -> Self {
        assert!((2..=64).contains(&W), "{W}-bit coordinates");
        let low_bits = W / 2;
        Self {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            less: Default::default(),
            equal: Default::default(),
            reversed_order: Constant::new(Bits::<W>::from((1u64 << (W - 1)) - 1)),
            low_bits: Constant::new(Bits::<8>::from(low_bits as u64)),
            high_bits: Constant::new(Bits::<8>::from((W - low_bits) as u64)),
            low_mask: Constant::new(Bits::<W>::from((1u64 << low_bits) - 1)),
            less_high_q: Default::default(),
            equal_high_q: Default::default(),
            less_low_q: Default::default(),
            equal_low_q: Default::default(),
            less_q: Default::default(),
            equal_q: Default::default(),
        }
    }
}

impl<const W: usize> Logic for SplitCompare<W> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            less_high_q,
            equal_high_q,
            less_low_q,
            equal_low_q,
            less_q,
            equal_q
        );
        self.less_high_q.d.next = ((self.b.val() ^ self.reversed_order.val())
            >> self.low_bits.val())
            < ((self.a.val() ^ self.reversed_order.val()) >> self.low_bits.val());
        self.equal_high_q.d.next = !((self.a.val() ^ self.b.val()) >> self.low_bits.val()).any();
        self.less_low_q.d.next = (((self.b.val() ^ self.reversed_order.val())
            << self.high_bits.val())
            >> self.high_bits.val())
            < (((self.a.val() ^ self.reversed_order.val()) << self.high_bits.val())
                >> self.high_bits.val());
        self.equal_low_q.d.next = !((self.a.val() ^ self.b.val()) & self.low_mask.val()).any();
        self.less_q.d.next =
            self.less_high_q.q.val() | (self.equal_high_q.q.val() & self.less_low_q.q.val());
        self.equal_q.d.next = self.equal_high_q.q.val() & self.equal_low_q.q.val();
        self.less.next = self.less_q.q.val();
        self.equal.next = self.equal_q.q.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim_drive::clock_cycle;

    /// Every pair of 8-bit values, the extremes included: the order on
    /// complemented offset binary is the signed order.
    #[test]
    fn comparison_is_signed_order() {
        let mut unit = CoordinateCompare::<8>::default();
        unit.connect_all();
        for a in -128i64..128 {
            for b in -128i64..128 {
                unit.a.next = Bits::from(a as u64 & 0xff);
                unit.b.next = Bits::from(b as u64 & 0xff);
                unit.advance.next = true;
                clock_cycle(&mut unit, |u| &mut u.clock);
                assert_eq!(
                    (unit.less.val(), unit.equal.val()),
                    (a < b, a == b),
                    "{a} vs {b}"
                );
            }
        }
    }

    /// The same for the split comparison, a pair a clock: its verdicts
    /// leave `SPLIT_COMPARE_LATENCY` clocks after their operands.
    #[test]
    fn split_comparison_is_signed_order() {
        let mut unit = SplitCompare::<8>::default();
        unit.connect_all();
        let pairs: Vec<(i64, i64)> = (-128i64..128)
            .flat_map(|a| (-128i64..128).map(move |b| (a, b)))
            .collect();
        for (t, &(a, b)) in pairs.iter().enumerate() {
            unit.a.next = Bits::from(a as u64 & 0xff);
            unit.b.next = Bits::from(b as u64 & 0xff);
            clock_cycle(&mut unit, |u| &mut u.clock);
            if let Some(&(a, b)) = (t + 1)
                .checked_sub(SPLIT_COMPARE_LATENCY)
                .map(|i| &pairs[i])
            {
                assert_eq!(
                    (unit.less.val(), unit.equal.val()),
                    (a < b, a == b),
                    "{a} vs {b}"
                );
            }
        }
    }
}

#[cfg(test)]
mod random_vectors {
    use crate::arith::compare::{
        CoordinateCompare, SplitCompare, COMPARE_LATENCY, SPLIT_COMPARE_LATENCY,
    };
    use crate::arith::convert::from_i128;
    use crate::arith::sign::{SignOf, SIGN_LATENCY};
    use crate::arith::unit_vectors::tuples;
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;

    #[test]
    fn sign_and_comparison() {
        let mut uut = SignOf::<74>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &tuples::<1>(9, 74),
            SIGN_LATENCY,
            |u, [v]| u.value.next = from_i128(*v),
            |u| (u.negative.val(), u.zero.val()),
            |[v]| (*v < 0, *v == 0),
        );
        let mut uut = CoordinateCompare::<24>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &tuples::<2>(10, 24),
            COMPARE_LATENCY,
            |u, [a, b]| {
                u.a.next = from_i128(*a);
                u.b.next = from_i128(*b);
            },
            |u| (u.less.val(), u.equal.val()),
            |[a, b]| (a < b, a == b),
        );
        // Odd widths split unevenly: 11 bits as 6 + 5.
        let mut uut = SplitCompare::<24>::default();
        uut.connect_all();
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &tuples::<2>(10, 24),
            SPLIT_COMPARE_LATENCY,
            |u, [a, b]| {
                u.a.next = from_i128(*a);
                u.b.next = from_i128(*b);
            },
            |u| (u.less.val(), u.equal.val()),
            |[a, b]| (a < b, a == b),
        );
        let mut uut = SplitCompare::<11>::default();
        uut.connect_all();
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &tuples::<2>(11, 11),
            SPLIT_COMPARE_LATENCY,
            |u, [a, b]| {
                u.a.next = from_i128(*a);
                u.b.next = from_i128(*b);
            },
            |u| (u.less.val(), u.equal.val()),
            |[a, b]| (a < b, a == b),
        );
    }
}
