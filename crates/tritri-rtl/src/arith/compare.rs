//! Registered comparison of two W-bit signed coordinates: `a < b` and
//! `a == b`. Used for the lexicographic segment ends of a degenerate
//! triangle (`shape` in devillers_guigue.rs) and for the collinear cases of
//! the 2D segment tests (`on_segment_2d`).
//!
//! Signed order is the unsigned order of offset binary (`x ^ 2^(W-1)`), so
//! no sign extension is needed.

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
    sign_flip: Constant<Bits<W>>,
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
            sign_flip: Constant::new(Bits::<W>::from(1u64 << (W - 1))),
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
            self.less_q.d.next =
                (self.a.val() ^ self.sign_flip.val()) < (self.b.val() ^ self.sign_flip.val());
            self.equal_q.d.next = self.a.val() == self.b.val();
        }
        self.less.next = self.less_q.q.val();
        self.equal.next = self.equal_q.q.val();
    }
}
