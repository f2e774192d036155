//! The certificate of an orientation sign (`tritri_geom::certificate`):
//! is `|P|` clear of `2^(2m + 5)`, where every entry of the determinant's
//! rows is at most `2^m` in magnitude?
//!
//! Two blocks, neither with an adder or a multiplier:
//!
//! * [`MagnitudeThermometer`] (two register stages): `2^m - 1` for three
//!   differences, the OR of their ones' complement magnitudes
//!   (`x ^ (x >> top)`), then that smeared downwards, with bit 0 forced
//!   (`m >= 1`). Thermometers of several rows combine by OR. In one
//!   combinational stage it was the W = 8 pipeline's critical path on ECP5
//!   (119.6 MHz: five LUT levels and 4.6 ns of routing from a difference
//!   register next to the multipliers).
//! * [`CertainSign`] (one register stage, like [`super::sign::SignOf`]):
//!   the sign of `P` and whether `(P ^ (P >> top)) & !mask` is not zero,
//!   where `mask = 2^(2m + 5) - 1` is the thermometer with every bit doubled
//!   (a Morton expansion: constant shifts and masks, wiring after
//!   synthesis), shifted up five places, low five bits set.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from value to sign and certificate.
pub const CERTAIN_SIGN_LATENCY: usize = 1;

/// Clock edges from the differences to their thermometer.
pub const MAGNITUDE_THERMOMETER_LATENCY: usize = 2;

#[derive(LogicBlock)]
pub struct MagnitudeThermometer<const D: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// Three D-bit two's complement differences.
    pub value: [Signal<In, Bits<D>>; 3],
    /// `2^m - 1`: every `|value| <= 2^m`, `m >= 1`
    /// (`MAGNITUDE_THERMOMETER_LATENCY` enabled edges later).
    pub thermometer: Signal<Out, Bits<D>>,
    top_bit: Constant<Bits<8>>,
    one: Constant<Bits<D>>,
    /// Each value's ones' complement magnitude.
    magnitude: [Signal<Local, Bits<D>>; 3],
    /// Stage 1: their OR.
    magnitudes_q: DFF<Bits<D>>,
    /// After each smear step (by 1, 2, 4, 8, 16, 32 places: enough for
    /// D <= 64).
    smear: [Signal<Local, Bits<D>>; 7],
    /// Stage 2: the thermometer.
    thermometer_q: DFF<Bits<D>>,
}

impl<const D: usize> crate::unit::Unit for MagnitudeThermometer<D> {
    const LATENCY: Option<usize> = Some(MAGNITUDE_THERMOMETER_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, magnitudes_q, thermometer_q);
    }
}

impl<const D: usize> Default for MagnitudeThermometer<D> {
    fn default() -> Self {
        assert!((2..=64).contains(&D));
        Self {
            clock: Default::default(),
            advance: Default::default(),
            value: Default::default(),
            thermometer: Default::default(),
            top_bit: Constant::new(Bits::<8>::from((D - 1) as u64)),
            one: Constant::new(Bits::<D>::from(1)),
            magnitude: Default::default(),
            magnitudes_q: Default::default(),
            smear: Default::default(),
            thermometer_q: Default::default(),
        }
    }
}

impl<const D: usize> Logic for MagnitudeThermometer<D> {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..3 {
            if self.value[k].val().get_bit(self.top_bit.val().index()) {
                self.magnitude[k].next = !self.value[k].val();
            } else {
                self.magnitude[k].next = self.value[k].val();
            }
        }
        dff_setup!(self, clock, magnitudes_q, thermometer_q);
        if self.advance.val() {
            self.magnitudes_q.d.next =
                self.magnitude[0].val() | self.magnitude[1].val() | self.magnitude[2].val();
        }
        self.smear[0].next = self.magnitudes_q.q.val();
        self.smear[1].next = self.smear[0].val() | (self.smear[0].val() >> 1);
        self.smear[2].next = self.smear[1].val() | (self.smear[1].val() >> 2);
        self.smear[3].next = self.smear[2].val() | (self.smear[2].val() >> 4);
        self.smear[4].next = self.smear[3].val() | (self.smear[3].val() >> 8);
        self.smear[5].next = self.smear[4].val() | (self.smear[4].val() >> 16);
        self.smear[6].next = self.smear[5].val() | (self.smear[5].val() >> 32);
        if self.advance.val() {
            self.thermometer_q.d.next = self.smear[6].val() | self.one.val();
        }
        self.thermometer.next = self.thermometer_q.q.val();
    }
}

/// The sign of a determinant and its certificate, registered.
#[derive(LogicBlock)]
pub struct CertainSign<const O: usize, const D: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// The determinant `P`, O-bit two's complement.
    pub value: Signal<In, Bits<O>>,
    /// `2^m - 1` of the determinant's entries.
    pub thermometer: Signal<In, Bits<D>>,
    /// `P < 0`, `CERTAIN_SIGN_LATENCY` enabled edges later.
    pub negative: Signal<Out, Bit>,
    /// `P == 0`.
    pub zero: Signal<Out, Bit>,
    /// `|P| > 2^(2m + 5)`: the sign holds for every admissible move.
    pub certain: Signal<Out, Bit>,
    top_bit: Constant<Bits<8>>,
    /// The Morton expansion's masks, widest step first.
    spread_mask: [Constant<Bits<O>>; 6],
    low_five: Constant<Bits<O>>,
    /// The thermometer widened, then after each expansion step.
    spread: [Signal<Local, Bits<O>>; 7],
    /// `2^(2m + 5) - 1`.
    mask: Signal<Local, Bits<O>>,
    /// `|P|` or `|P| - 1`.
    magnitude: Signal<Local, Bits<O>>,
    negative_q: DFF<Bit>,
    zero_q: DFF<Bit>,
    certain_q: DFF<Bit>,
}

impl<const O: usize, const D: usize> crate::unit::Unit for CertainSign<O, D> {
    const LATENCY: Option<usize> = Some(CERTAIN_SIGN_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, negative_q, zero_q, certain_q);
    }
}

/// Bits `i` with `i mod 2s < s`: where the expansion step by `s` keeps bits.
fn spread_mask<const O: usize>(step: u64) -> Bits<O> {
    (0..O)
        .filter(|i| (*i as u64) % (2 * step) < step)
        .fold(Bits::<O>::default(), |m, i| m.replace_bit(i, true))
}

impl<const O: usize, const D: usize> Default for CertainSign<O, D> {
    fn default() -> Self {
        // The mask reaches bit 2D + 5 (the determinant has more: O = 3W + 2).
        assert!(2 * D + 5 <= O && O < 256);
        Self {
            clock: Default::default(),
            advance: Default::default(),
            value: Default::default(),
            thermometer: Default::default(),
            negative: Default::default(),
            zero: Default::default(),
            certain: Default::default(),
            top_bit: Constant::new(Bits::<8>::from((O - 1) as u64)),
            spread_mask: [32, 16, 8, 4, 2, 1].map(|s| Constant::new(spread_mask::<O>(s))),
            low_five: Constant::new(Bits::<O>::from(0x1f)),
            spread: Default::default(),
            mask: Default::default(),
            magnitude: Default::default(),
            negative_q: Default::default(),
            zero_q: Default::default(),
            certain_q: Default::default(),
        }
    }
}

impl<const O: usize, const D: usize> Logic for CertainSign<O, D> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, negative_q, zero_q, certain_q);
        // Bit i of the thermometer to bit 2i (Morton expansion), then to
        // bits 2i and 2i + 1, then five places up.
        self.spread[0].next = bit_cast::<O, D>(self.thermometer.val());
        self.spread[1].next =
            (self.spread[0].val() | (self.spread[0].val() << 32)) & self.spread_mask[0].val();
        self.spread[2].next =
            (self.spread[1].val() | (self.spread[1].val() << 16)) & self.spread_mask[1].val();
        self.spread[3].next =
            (self.spread[2].val() | (self.spread[2].val() << 8)) & self.spread_mask[2].val();
        self.spread[4].next =
            (self.spread[3].val() | (self.spread[3].val() << 4)) & self.spread_mask[3].val();
        self.spread[5].next =
            (self.spread[4].val() | (self.spread[4].val() << 2)) & self.spread_mask[4].val();
        self.spread[6].next =
            (self.spread[5].val() | (self.spread[5].val() << 1)) & self.spread_mask[5].val();
        self.mask.next =
            ((self.spread[6].val() | (self.spread[6].val() << 1)) << 5) | self.low_five.val();
        if self.value.val().get_bit(self.top_bit.val().index()) {
            self.magnitude.next = !self.value.val();
        } else {
            self.magnitude.next = self.value.val();
        }
        if self.advance.val() {
            self.negative_q.d.next = self.value.val().get_bit(self.top_bit.val().index());
            self.zero_q.d.next = !self.value.val().any();
            self.certain_q.d.next = (self.magnitude.val() & !self.mask.val()).any();
        }
        self.negative.next = self.negative_q.q.val();
        self.zero.next = self.zero_q.q.val();
        self.certain.next = self.certain_q.q.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::convert::from_i128;
    use tritri_geom::certificate::{clears_threshold, entry_bits};

    /// The thermometer is `2^m - 1` of `tritri_geom::certificate::entry_bits`.
    #[test]
    fn thermometer_is_the_models_bit_count() {
        let mut uut = MagnitudeThermometer::<9>::default();
        uut.clock.connect();
        uut.advance.connect();
        for v in &mut uut.value {
            v.connect();
        }
        uut.connect_all();
        uut.advance.next = true;
        for x in -256i64..=255 {
            for y in [0i64, -1, 3, -100, 255] {
                uut.value[0].next = from_i128::<9>(x as i128);
                uut.value[1].next = from_i128::<9>(y as i128);
                uut.value[2].next = from_i128::<9>(-2);
                for _ in 0..MAGNITUDE_THERMOMETER_LATENCY {
                    crate::sim_drive::clock_cycle(&mut uut, |u| &mut u.clock);
                }
                let m = entry_bits(&[x, y, -2]);
                assert_eq!(uut.thermometer.val().to_u64(), (1 << m) - 1, "{x} {y}");
            }
        }
    }

    /// The certificate is `tritri_geom::certificate::clears_threshold` for
    /// every m and values around each threshold, at W = 8 and W = 32.
    #[test]
    fn certain_is_the_models_threshold() {
        check_certain::<26, 9>();
        check_certain::<98, 33>();
    }

    fn check_certain<const O: usize, const D: usize>() {
        let mut uut = CertainSign::<O, D>::default();
        uut.clock.connect();
        uut.advance.connect();
        uut.value.connect();
        uut.thermometer.connect();
        uut.connect_all();
        uut.advance.next = true;
        let (lo, hi) = (-(1i128 << (O - 1)), (1i128 << (O - 1)) - 1);
        for m in 1..=D as u32 {
            let t = 2i128 << (2 * m + 4);
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
                uut.thermometer.next = Bits::from((1u64 << m) - 1);
                crate::sim_drive::clock_cycle(&mut uut, |u| &mut u.clock);
                assert_eq!(uut.certain.val(), clears_threshold(p, m), "m {m} P {p}");
                assert_eq!(uut.negative.val(), p < 0);
                assert_eq!(uut.zero.val(), p == 0);
            }
        }
    }
}
