//! Vector subtractor: `a - b` for two points of W-bit signed coordinates,
//! giving an exact (W+1)-bit difference vector, registered.
//!
//! Thesis, chapter 3, figure 3.11 (the vector subtraction unit: "24 bit
//! minus 24 bit gives 25 bit"). Used by every unit that forms edge vectors:
//! the normal (step 1/3), the plane side (step 2/4), orient3d (step 7) and
//! the 2D tests.
//!
//! Implemented on offset binary: `x + 2^(W-1) = x ^ 2^(W-1)` as an unsigned
//! W-bit number, so `a - b = (a ^ s) - (b ^ s)` with both zero-extended to
//! W+1 bits, computed modulo `2^(W+1)`; the true difference lies in
//! `[-(2^W - 1), 2^W - 1]` and fits, so the result is exact without any sign
//! extension.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from operands to difference.
pub const SUBTRACTOR_LATENCY: usize = 1;

#[derive(LogicBlock)]
pub struct VectorSubtractor<const W: usize, const D: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: [Signal<In, Bits<W>>; 3],
    pub b: [Signal<In, Bits<W>>; 3],
    /// `a - b`, exact, `SUBTRACTOR_LATENCY` enabled edges later.
    pub difference: [Signal<Out, Bits<D>>; 3],
    sign_flip: Constant<Bits<W>>,
    difference_0: DFF<Bits<D>>,
    difference_1: DFF<Bits<D>>,
    difference_2: DFF<Bits<D>>,
}

impl<const W: usize, const D: usize> crate::unit::Unit for VectorSubtractor<W, D> {
    const LATENCY: Option<usize> = Some(SUBTRACTOR_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, difference_0, difference_1, difference_2);
    }
}

impl<const W: usize, const D: usize> Default for VectorSubtractor<W, D> {
    fn default() -> Self {
        assert_eq!(
            D,
            tritri_geom::widths::difference_bits(W),
            "a difference of {W}-bit values has {} bits",
            W + 1
        );
        Self {
            clock: Default::default(),
            advance: Default::default(),
            a: Default::default(),
            b: Default::default(),
            difference: Default::default(),
            sign_flip: Constant::new(Bits::<W>::from(1u64 << (W - 1))),
            difference_0: Default::default(),
            difference_1: Default::default(),
            difference_2: Default::default(),
        }
    }
}

impl<const W: usize, const D: usize> Logic for VectorSubtractor<W, D> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, difference_0, difference_1, difference_2);
        if self.advance.val() {
            self.difference_0.d.next = bit_cast::<D, W>(self.a[0].val() ^ self.sign_flip.val())
                - bit_cast::<D, W>(self.b[0].val() ^ self.sign_flip.val());
            self.difference_1.d.next = bit_cast::<D, W>(self.a[1].val() ^ self.sign_flip.val())
                - bit_cast::<D, W>(self.b[1].val() ^ self.sign_flip.val());
            self.difference_2.d.next = bit_cast::<D, W>(self.a[2].val() ^ self.sign_flip.val())
                - bit_cast::<D, W>(self.b[2].val() ^ self.sign_flip.val());
        }
        self.difference[0].next = self.difference_0.q.val();
        self.difference[1].next = self.difference_1.q.val();
        self.difference[2].next = self.difference_2.q.val();
    }
}

/// Scalar form of [`VectorSubtractor`]: `a - b` of two W-bit signed values,
/// exact in W+1 bits, registered. The 2D tests use it on projected
/// coordinates.
#[derive(LogicBlock)]
pub struct Subtractor<const W: usize, const D: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: Signal<In, Bits<W>>,
    pub b: Signal<In, Bits<W>>,
    pub difference: Signal<Out, Bits<D>>,
    sign_flip: Constant<Bits<W>>,
    difference_q: DFF<Bits<D>>,
}

impl<const W: usize, const D: usize> crate::unit::Unit for Subtractor<W, D> {
    const LATENCY: Option<usize> = Some(SUBTRACTOR_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, difference_q);
    }
}

impl<const W: usize, const D: usize> Default for Subtractor<W, D> {
    fn default() -> Self {
        assert_eq!(
            D,
            tritri_geom::widths::difference_bits(W),
            "a difference of {W}-bit values has {} bits",
            W + 1
        );
        Self {
            clock: Default::default(),
            advance: Default::default(),
            a: Default::default(),
            b: Default::default(),
            difference: Default::default(),
            sign_flip: Constant::new(Bits::<W>::from(1u64 << (W - 1))),
            difference_q: Default::default(),
        }
    }
}

impl<const W: usize, const D: usize> Logic for Subtractor<W, D> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, difference_q);
        if self.advance.val() {
            self.difference_q.d.next = bit_cast::<D, W>(self.a.val() ^ self.sign_flip.val())
                - bit_cast::<D, W>(self.b.val() ^ self.sign_flip.val());
        }
        self.difference.next = self.difference_q.q.val();
    }
}

/// [`VectorSubtractor`] in both directions: `a - b` and `b - a`, each on
/// its own carry chain, registered. A magnitude `|a - b|` is then a choice
/// between two registers by the first's sign, one LUT, rather than a
/// negation (`~v + 1`, a second chain) behind the difference register.
/// [`MagnitudeSubtractor`] is its first stage; the edges of the normal and
/// of the certified orient3d feed their `ke`
/// (`super::certificate::EdgesBitLength`) this way. (That negation behind
/// the edge register, which also feeds the cross product's multipliers,
/// was the W = 16 pipeline's critical path at 153.1 MHz on ECP5.)
#[derive(LogicBlock, Default)]
pub struct TwoWaySubtractor<const W: usize, const D: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: [Signal<In, Bits<W>>; 3],
    pub b: [Signal<In, Bits<W>>; 3],
    /// `a - b`, exact, `SUBTRACTOR_LATENCY` enabled edges later.
    pub difference: [Signal<Out, Bits<D>>; 3],
    /// `b - a`, with it.
    pub negated: [Signal<Out, Bits<D>>; 3],
    forward: VectorSubtractor<W, D>,
    backward: VectorSubtractor<W, D>,
}

impl<const W: usize, const D: usize> crate::unit::Unit for TwoWaySubtractor<W, D> {
    const LATENCY: Option<usize> = Some(SUBTRACTOR_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, forward, backward);
    }
}

impl<const W: usize, const D: usize> Logic for TwoWaySubtractor<W, D> {
    #[hdl_gen]
    fn update(&mut self) {
        self.forward.clock.next = self.clock.val();
        self.backward.clock.next = self.clock.val();
        self.forward.advance.next = self.advance.val();
        self.backward.advance.next = self.advance.val();
        for k in 0..3 {
            self.forward.a[k].next = self.a[k].val();
            self.forward.b[k].next = self.b[k].val();
            self.backward.a[k].next = self.b[k].val();
            self.backward.b[k].next = self.a[k].val();
            self.difference[k].next = self.forward.difference[k].val();
            self.negated[k].next = self.backward.difference[k].val();
        }
    }
}

/// Clock edges from inputs to [`MagnitudeSubtractor`]'s outputs.
pub const MAGNITUDE_SUBTRACTOR_LATENCY: usize = SUBTRACTOR_LATENCY + 1;

/// [`VectorSubtractor`] that also gives each component's magnitude
/// `|a_k - b_k|` (at most `2^W - 1`, in D bits, the top one zero): both
/// differences on their own carry chains ([`TwoWaySubtractor`]), then a
/// choice by the first's sign, registered with the difference
/// ([`MAGNITUDE_SUBTRACTOR_LATENCY`]). The certificate's threshold
/// (`super::certificate::CertificateThreshold`) takes the magnitudes of an
/// offset where the offset has no clock to spare before it (the plane
/// side's `v - p`). (In one stage, the inputs' wires across the chip, a
/// chain, the sign out to 17 choices and on to the register were the
/// critical path of the W = 16 pipeline with the rare cases shared, 7.4
/// ns, 134.5 MHz.)
#[derive(LogicBlock)]
pub struct MagnitudeSubtractor<const W: usize, const D: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: [Signal<In, Bits<W>>; 3],
    pub b: [Signal<In, Bits<W>>; 3],
    /// `a - b`, exact, `MAGNITUDE_SUBTRACTOR_LATENCY` enabled edges later.
    pub difference: [Signal<Out, Bits<D>>; 3],
    /// `|a - b|`, with the difference.
    pub magnitude: [Signal<Out, Bits<D>>; 3],
    top_bit: Constant<Bits<8>>,
    /// Stage 1: `a - b` and `b - a`.
    both: TwoWaySubtractor<W, D>,
    /// Stage 2.
    difference_q: [DFF<Bits<D>>; 3],
    magnitude_q: [DFF<Bits<D>>; 3],
}

impl<const W: usize, const D: usize> crate::unit::Unit for MagnitudeSubtractor<W, D> {
    const LATENCY: Option<usize> = Some(MAGNITUDE_SUBTRACTOR_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, both, difference_q, magnitude_q);
    }
}

impl<const W: usize, const D: usize> Default for MagnitudeSubtractor<W, D> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            advance: Default::default(),
            a: Default::default(),
            b: Default::default(),
            difference: Default::default(),
            magnitude: Default::default(),
            top_bit: Constant::new(Bits::<8>::from((D - 1) as u64)),
            both: Default::default(),
            difference_q: Default::default(),
            magnitude_q: Default::default(),
        }
    }
}

impl<const W: usize, const D: usize> Logic for MagnitudeSubtractor<W, D> {
    #[hdl_gen]
    fn update(&mut self) {
        self.both.clock.next = self.clock.val();
        self.both.advance.next = self.advance.val();
        for k in 0..3 {
            self.both.a[k].next = self.a[k].val();
            self.both.b[k].next = self.b[k].val();
            self.difference_q[k].clock.next = self.clock.val();
            self.magnitude_q[k].clock.next = self.clock.val();
            self.difference_q[k].d.next = self.difference_q[k].q.val();
            self.magnitude_q[k].d.next = self.magnitude_q[k].q.val();
            self.difference[k].next = self.difference_q[k].q.val();
            self.magnitude[k].next = self.magnitude_q[k].q.val();
            if self.advance.val() {
                self.difference_q[k].d.next = self.both.difference[k].val();
                if self.both.difference[k]
                    .val()
                    .get_bit(self.top_bit.val().index())
                {
                    self.magnitude_q[k].d.next = self.both.negated[k].val();
                } else {
                    self.magnitude_q[k].d.next = self.both.difference[k].val();
                }
            }
        }
    }
}

/// `v` and its magnitudes `|v_k|` (D bits, at most `2^(D-1)`), registered
/// together: one carry chain and a choice, from a register near by. Where
/// an offset has clocks to spare before its threshold
/// (`crate::pipeline::certified_orient3d`'s `d - a` waits for the cross
/// product), its last wait is this stage, and the subtraction stays a
/// single chain ([`MagnitudeSubtractor`]'s second chain and choice made
/// that pipeline's ECP5 critical path from the operand registers).
#[derive(LogicBlock)]
pub struct VectorMagnitude<const D: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub v: [Signal<In, Bits<D>>; 3],
    /// `v`, `SUBTRACTOR_LATENCY` enabled edges later.
    pub value: [Signal<Out, Bits<D>>; 3],
    /// `|v|`, with it.
    pub magnitude: [Signal<Out, Bits<D>>; 3],
    top_bit: Constant<Bits<8>>,
    zero: Constant<Bits<D>>,
    value_q0: DFF<Bits<D>>,
    value_q1: DFF<Bits<D>>,
    value_q2: DFF<Bits<D>>,
    magnitude_q0: DFF<Bits<D>>,
    magnitude_q1: DFF<Bits<D>>,
    magnitude_q2: DFF<Bits<D>>,
}

impl<const D: usize> crate::unit::Unit for VectorMagnitude<D> {
    const LATENCY: Option<usize> = Some(SUBTRACTOR_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            value_q0,
            value_q1,
            value_q2,
            magnitude_q0,
            magnitude_q1,
            magnitude_q2
        );
    }
}

impl<const D: usize> Default for VectorMagnitude<D> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            advance: Default::default(),
            v: Default::default(),
            value: Default::default(),
            magnitude: Default::default(),
            top_bit: Constant::new(Bits::<8>::from((D - 1) as u64)),
            zero: Constant::new(Bits::<D>::from(0u64)),
            value_q0: Default::default(),
            value_q1: Default::default(),
            value_q2: Default::default(),
            magnitude_q0: Default::default(),
            magnitude_q1: Default::default(),
            magnitude_q2: Default::default(),
        }
    }
}

impl<const D: usize> Logic for VectorMagnitude<D> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            value_q0,
            value_q1,
            value_q2,
            magnitude_q0,
            magnitude_q1,
            magnitude_q2
        );
        if self.advance.val() {
            self.value_q0.d.next = self.v[0].val();
            self.value_q1.d.next = self.v[1].val();
            self.value_q2.d.next = self.v[2].val();
            if self.v[0].val().get_bit(self.top_bit.val().index()) {
                self.magnitude_q0.d.next = self.zero.val() - self.v[0].val();
            } else {
                self.magnitude_q0.d.next = self.v[0].val();
            }
            if self.v[1].val().get_bit(self.top_bit.val().index()) {
                self.magnitude_q1.d.next = self.zero.val() - self.v[1].val();
            } else {
                self.magnitude_q1.d.next = self.v[1].val();
            }
            if self.v[2].val().get_bit(self.top_bit.val().index()) {
                self.magnitude_q2.d.next = self.zero.val() - self.v[2].val();
            } else {
                self.magnitude_q2.d.next = self.v[2].val();
            }
        }
        self.value[0].next = self.value_q0.q.val();
        self.value[1].next = self.value_q1.q.val();
        self.value[2].next = self.value_q2.q.val();
        self.magnitude[0].next = self.magnitude_q0.q.val();
        self.magnitude[1].next = self.magnitude_q1.q.val();
        self.magnitude[2].next = self.magnitude_q2.q.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::convert::to_i128;
    use crate::sim_drive::clock_cycle;

    /// Difference and magnitude of every pair of extreme and middle values
    /// of 8-bit coordinates, one pair a clock: each comes out
    /// `MAGNITUDE_SUBTRACTOR_LATENCY` edges after it went in.
    #[test]
    fn magnitude_subtractor_is_exact() {
        let values = [-128i64, -127, -1, 0, 1, 5, 126, 127];
        let pairs: Vec<[(i64, i64); 3]> = values
            .iter()
            .flat_map(|&a| values.iter().map(move |&b| (a, b)))
            .map(|(a, b)| std::array::from_fn(|k| ((a + 7 * k as i64).clamp(-128, 127), b)))
            .collect();
        let mut unit = MagnitudeSubtractor::<8, 9>::default();
        unit.connect_all();
        unit.advance.next = true;
        for (i, pair) in pairs.iter().enumerate() {
            for (k, &(a, b)) in pair.iter().enumerate() {
                unit.a[k].next = Bits::from(a as u64 & 0xff);
                unit.b[k].next = Bits::from(b as u64 & 0xff);
            }
            clock_cycle(&mut unit, |u| &mut u.clock);
            let Some(out) = (i + 1).checked_sub(MAGNITUDE_SUBTRACTOR_LATENCY) else {
                continue;
            };
            for (k, &(a, b)) in pairs[out].iter().enumerate() {
                assert_eq!(
                    to_i128(unit.difference[k].val()),
                    (a - b) as i128,
                    "pair {out}"
                );
                assert_eq!(unit.magnitude[k].val().to_u64(), (a - b).unsigned_abs());
            }
        }
    }

    /// Value and magnitude of 9-bit values across their range, the most
    /// negative included.
    #[test]
    fn vector_magnitude_is_exact() {
        let mut unit = VectorMagnitude::<9>::default();
        unit.connect_all();
        for x in [-256i64, -255, -128, -1, 0, 1, 100, 255] {
            for k in 0..3 {
                unit.v[k].next = Bits::from((x >> k) as u64 & 0x1ff);
            }
            unit.advance.next = true;
            clock_cycle(&mut unit, |u| &mut u.clock);
            for k in 0..3 {
                assert_eq!(to_i128(unit.value[k].val()), (x >> k) as i128);
                assert_eq!(unit.magnitude[k].val().to_u64(), (x >> k).unsigned_abs());
            }
        }
    }
}

#[cfg(test)]
mod random_vectors {
    use crate::arith::convert::{from_i128, to_i128};
    use crate::arith::subtractor::{Subtractor, VectorSubtractor, SUBTRACTOR_LATENCY};
    use crate::arith::unit_vectors::tuples;
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;

    #[test]
    fn subtractors_are_exact() {
        let mut uut = Subtractor::<24, 25>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &tuples::<2>(3, 24),
            SUBTRACTOR_LATENCY,
            |u, [a, b]| {
                u.a.next = from_i128(*a);
                u.b.next = from_i128(*b);
            },
            |u| to_i128(u.difference.val()),
            |[a, b]| a - b,
        );
        let mut uut = VectorSubtractor::<24, 25>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &tuples::<6>(4, 24),
            SUBTRACTOR_LATENCY,
            |u, v| {
                for k in 0..3 {
                    u.a[k].next = from_i128(v[k]);
                    u.b[k].next = from_i128(v[3 + k]);
                }
            },
            |u| u.difference.each_ref().map(|d| to_i128(d.val())),
            |v| std::array::from_fn(|k| v[k] - v[3 + k]),
        );
    }
}
