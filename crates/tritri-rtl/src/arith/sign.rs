//! Sign of a two's-complement predicate value, registered: the only thing
//! the decisions look at (docs/ARCHITECTURE.md, conventions: decide on signs, never on products of
//! predicate values). Thesis, chapter 3: "the sign is in the top bit".

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from value to sign.
pub const SIGN_LATENCY: usize = 1;

#[derive(LogicBlock)]
pub struct SignOf<const N: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub value: Signal<In, Bits<N>>,
    /// The value is `< 0`.
    pub negative: Signal<Out, Bit>,
    /// The value is `== 0`.
    pub zero: Signal<Out, Bit>,
    top_bit: Constant<Bits<8>>,
    negative_q: DFF<Bit>,
    zero_q: DFF<Bit>,
}

impl<const N: usize> crate::unit::Unit for SignOf<N> {
    const LATENCY: Option<usize> = Some(SIGN_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, negative_q, zero_q);
    }
}

impl<const N: usize> Default for SignOf<N> {
    fn default() -> Self {
        assert!((2..256).contains(&N));
        Self {
            clock: Default::default(),
            advance: Default::default(),
            value: Default::default(),
            negative: Default::default(),
            zero: Default::default(),
            top_bit: Constant::new(Bits::<8>::from((N - 1) as u64)),
            negative_q: Default::default(),
            zero_q: Default::default(),
        }
    }
}

impl<const N: usize> Logic for SignOf<N> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, negative_q, zero_q);
        if self.advance.val() {
            self.negative_q.d.next = self.value.val().get_bit(self.top_bit.val().index());
            self.zero_q.d.next = !self.value.val().any();
        }
        self.negative.next = self.negative_q.q.val();
        self.zero.next = self.zero_q.q.val();
    }
}
