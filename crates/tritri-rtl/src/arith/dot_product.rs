//! Dot product `u · v` of a (W+1)-bit difference vector and a (2W+1)-bit
//! cross product, in 3W+2 bits: an orient3d value.
//!
//! Thesis, chapter 3, figure 3.9 (the dot-product unit, 78 bits there; 74
//! here, the tight bound of `tritri_geom::widths`). Three registered
//! multipliers `(W+1) x (2W+1) -> 3W+2` and a three-input sum in two
//! register stages.
//! The sum is computed modulo `2^(3W+2)`: partial sums may wrap, but the
//! final value of an orient3d is at most `2 M^3` in magnitude and fits, so
//! the wrapped result is the exact one (docs/ARCHITECTURE.md, conventions).

use super::adder::{RegisteredSum3, SUM3_LATENCY};
use super::multiplier::{Multiplier, MULTIPLIER_LATENCY};
use rust_hdl::prelude::*;

/// Clock edges from operands to dot product.
pub const DOT_PRODUCT_LATENCY: usize = MULTIPLIER_LATENCY + SUM3_LATENCY;

#[derive(LogicBlock)]
pub struct DotProduct<const D: usize, const C: usize, const O: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub u: [Signal<In, Bits<D>>; 3],
    pub v: [Signal<In, Bits<C>>; 3],
    /// `u · v` modulo `2^O`, `DOT_PRODUCT_LATENCY` enabled edges later.
    pub product: Signal<Out, Bits<O>>,
    /// All 1 when `product == 0`, in the same clock
    /// ([`RegisteredSum3::zero_parts`]).
    pub zero_parts: Signal<Out, Bits<O>>,
    multiplier: [Multiplier<D, C, O>; 3],
    sum: RegisteredSum3<O>,
}

impl<const D: usize, const C: usize, const O: usize> crate::unit::Unit for DotProduct<D, C, O> {
    const LATENCY: Option<usize> = Some(DOT_PRODUCT_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, multiplier, sum);
    }
}

impl<const D: usize, const C: usize, const O: usize> Default for DotProduct<D, C, O> {
    fn default() -> Self {
        assert!(
            O <= D + C,
            "a dot product of {D}-bit by {C}-bit vectors has at most {} bits",
            D + C
        );
        Self {
            clock: Default::default(),
            advance: Default::default(),
            u: Default::default(),
            v: Default::default(),
            product: Default::default(),
            zero_parts: Default::default(),
            multiplier: Default::default(),
            sum: Default::default(),
        }
    }
}

impl<const D: usize, const C: usize, const O: usize> Logic for DotProduct<D, C, O> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..3 {
            self.multiplier[i].clock.next = self.clock.val();
            self.multiplier[i].advance.next = self.advance.val();
            self.multiplier[i].a.next = self.u[i].val();
            self.multiplier[i].b.next = self.v[i].val();
        }
        self.sum.clock.next = self.clock.val();
        self.sum.advance.next = self.advance.val();
        self.sum.a.next = self.multiplier[0].product.val();
        self.sum.b.next = self.multiplier[1].product.val();
        self.sum.c.next = self.multiplier[2].product.val();
        self.product.next = self.sum.sum.val();
        self.zero_parts.next = self.sum.zero_parts.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::arith::convert::{from_i128, to_i128};
    use crate::arith::dot_product::{DotProduct, DOT_PRODUCT_LATENCY};
    use crate::arith::unit_vectors::{edge_vectors, narrow};
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;
    use tritri_geom::fixed_point::cross;

    #[test]
    fn dot_product_is_exact() {
        let mut uut = DotProduct::<25, 49, 74>::default();
        uut.connect_all();
        uut.advance.next = true;
        let vectors: Vec<([i128; 3], [i128; 3])> = edge_vectors(7)
            .into_iter()
            .map(|[e1, e2, e3]| (e3, cross(narrow(e1), narrow(e2))))
            .collect();
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &vectors,
            DOT_PRODUCT_LATENCY,
            |uut, (u, v)| {
                for k in 0..3 {
                    uut.u[k].next = from_i128(u[k]);
                    uut.v[k].next = from_i128(v[k]);
                }
            },
            |uut| to_i128(uut.product.val()),
            |(u, v)| (0..3).map(|k| u[k] * v[k]).sum(),
        );
    }
}
