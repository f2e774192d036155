//! Cross product `u × v` of two (W+1)-bit difference vectors, exact in
//! 2W+1 bits per component.
//!
//! Thesis, chapter 3, figure 3.10 (the cross-product unit of the normal
//! unit); `tritri_geom::fixed_point::cross` is the software model. Six
//! registered multipliers `(W+1) x (W+1) -> 2W+1` (each product is at most
//! `(2^W - 1)^2 < 2^(2W)` in magnitude, so it fits) and one registered
//! subtraction per component (two in [`TwoWayCrossProduct`], one each
//! way), modulo `2^(2W+1)`, exact because every component is at most
//! `M^2` in magnitude (`tritri_geom::widths`).

use super::adder::{RegisteredDifference, ADDER_LATENCY};
use super::multiplier::{Multiplier, MULTIPLIER_LATENCY};
use rust_hdl::prelude::*;

/// Clock edges from operands to cross product.
pub const CROSS_PRODUCT_LATENCY: usize = MULTIPLIER_LATENCY + ADDER_LATENCY;

/// The six products of `u × v`, `u1 v2, u2 v1, u2 v0, u0 v2, u0 v1, u1 v0`:
/// component `k` is `term[2k] - term[2k + 1]`. One place for the
/// multipliers' wiring, shared by [`CrossProduct`] and
/// [`TwoWayCrossProduct`].
#[derive(LogicBlock, Default)]
pub struct CrossTerms<const D: usize, const C: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub u: [Signal<In, Bits<D>>; 3],
    pub v: [Signal<In, Bits<D>>; 3],
    /// `MULTIPLIER_LATENCY` enabled edges later.
    pub term: [Signal<Out, Bits<C>>; 6],
    multiplier: [Multiplier<D, D, C>; 6],
}

impl<const D: usize, const C: usize> crate::unit::Unit for CrossTerms<D, C> {
    const LATENCY: Option<usize> = Some(MULTIPLIER_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, multiplier);
    }
}

impl<const D: usize, const C: usize> Logic for CrossTerms<D, C> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..6 {
            self.multiplier[i].clock.next = self.clock.val();
            self.multiplier[i].advance.next = self.advance.val();
            self.term[i].next = self.multiplier[i].product.val();
        }
        self.multiplier[0].a.next = self.u[1].val();
        self.multiplier[0].b.next = self.v[2].val();
        self.multiplier[1].a.next = self.u[2].val();
        self.multiplier[1].b.next = self.v[1].val();
        self.multiplier[2].a.next = self.u[2].val();
        self.multiplier[2].b.next = self.v[0].val();
        self.multiplier[3].a.next = self.u[0].val();
        self.multiplier[3].b.next = self.v[2].val();
        self.multiplier[4].a.next = self.u[0].val();
        self.multiplier[4].b.next = self.v[1].val();
        self.multiplier[5].a.next = self.u[1].val();
        self.multiplier[5].b.next = self.v[0].val();
    }
}

fn assert_cross_width(d: usize, c: usize) {
    assert_eq!(
        c,
        2 * d - 1,
        "a cross product of {d}-bit differences has {} bits",
        2 * d - 1
    );
}

#[derive(LogicBlock)]
pub struct CrossProduct<const D: usize, const C: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub u: [Signal<In, Bits<D>>; 3],
    pub v: [Signal<In, Bits<D>>; 3],
    /// `u × v`, `CROSS_PRODUCT_LATENCY` enabled edges later.
    pub product: [Signal<Out, Bits<C>>; 3],
    terms: CrossTerms<D, C>,
    component: [RegisteredDifference<C>; 3],
}

impl<const D: usize, const C: usize> crate::unit::Unit for CrossProduct<D, C> {
    const LATENCY: Option<usize> = Some(CROSS_PRODUCT_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, terms, component);
    }
}

impl<const D: usize, const C: usize> Default for CrossProduct<D, C> {
    fn default() -> Self {
        assert_cross_width(D, C);
        Self {
            clock: Default::default(),
            advance: Default::default(),
            u: Default::default(),
            v: Default::default(),
            product: Default::default(),
            terms: Default::default(),
            component: Default::default(),
        }
    }
}

impl<const D: usize, const C: usize> Logic for CrossProduct<D, C> {
    #[hdl_gen]
    fn update(&mut self) {
        self.terms.clock.next = self.clock.val();
        self.terms.advance.next = self.advance.val();
        for k in 0..3 {
            self.terms.u[k].next = self.u[k].val();
            self.terms.v[k].next = self.v[k].val();
            self.component[k].clock.next = self.clock.val();
            self.component[k].advance.next = self.advance.val();
            self.component[k].a.next = self.terms.term[2 * k].val();
            self.component[k].b.next = self.terms.term[2 * k + 1].val();
            self.product[k].next = self.component[k].difference.val();
        }
    }
}

/// `u × v` and `v × u = -(u × v)`, both from the same products in the same
/// stage, as [`super::subtractor::TwoWaySubtractor`] gives an edge both ways:
/// a reader that wants a component's magnitude then selects one of two
/// registers by the sign instead of negating behind the multipliers (the
/// triangle's dominant axis; a 2W + 1-bit negation there, behind 4.5 ns of
/// routing from the products, was the W = 16 pipeline's worst path on ECP5).
#[derive(LogicBlock)]
pub struct TwoWayCrossProduct<const D: usize, const C: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub u: [Signal<In, Bits<D>>; 3],
    pub v: [Signal<In, Bits<D>>; 3],
    /// `u × v`, `CROSS_PRODUCT_LATENCY` enabled edges later.
    pub product: [Signal<Out, Bits<C>>; 3],
    /// `v × u`, with it.
    pub negated: [Signal<Out, Bits<C>>; 3],
    terms: CrossTerms<D, C>,
    component: [RegisteredDifference<C>; 3],
    negated_component: [RegisteredDifference<C>; 3],
}

impl<const D: usize, const C: usize> crate::unit::Unit for TwoWayCrossProduct<D, C> {
    const LATENCY: Option<usize> = Some(CROSS_PRODUCT_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, terms, component, negated_component);
    }
}

impl<const D: usize, const C: usize> Default for TwoWayCrossProduct<D, C> {
    fn default() -> Self {
        assert_cross_width(D, C);
        Self {
            clock: Default::default(),
            advance: Default::default(),
            u: Default::default(),
            v: Default::default(),
            product: Default::default(),
            negated: Default::default(),
            terms: Default::default(),
            component: Default::default(),
            negated_component: Default::default(),
        }
    }
}

impl<const D: usize, const C: usize> Logic for TwoWayCrossProduct<D, C> {
    #[hdl_gen]
    fn update(&mut self) {
        self.terms.clock.next = self.clock.val();
        self.terms.advance.next = self.advance.val();
        for k in 0..3 {
            self.terms.u[k].next = self.u[k].val();
            self.terms.v[k].next = self.v[k].val();
            self.component[k].clock.next = self.clock.val();
            self.component[k].advance.next = self.advance.val();
            self.component[k].a.next = self.terms.term[2 * k].val();
            self.component[k].b.next = self.terms.term[2 * k + 1].val();
            self.product[k].next = self.component[k].difference.val();
            self.negated_component[k].clock.next = self.clock.val();
            self.negated_component[k].advance.next = self.advance.val();
            self.negated_component[k].a.next = self.terms.term[2 * k + 1].val();
            self.negated_component[k].b.next = self.terms.term[2 * k].val();
            self.negated[k].next = self.negated_component[k].difference.val();
        }
    }
}

/// One component of a cross product, `u.x w.y - u.y w.x`: the orient2d
/// value of a projected triangle (`tritri_geom::fixed_point::orient2d_value`)
/// from its two edge vectors. Exact in 2W+1 bits, same reasoning as
/// [`CrossProduct`].
#[derive(LogicBlock)]
pub struct CrossProduct2d<const D: usize, const C: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub u_x: Signal<In, Bits<D>>,
    pub u_y: Signal<In, Bits<D>>,
    pub w_x: Signal<In, Bits<D>>,
    pub w_y: Signal<In, Bits<D>>,
    /// `u.x w.y - u.y w.x`, `CROSS_PRODUCT_LATENCY` enabled edges later.
    pub product: Signal<Out, Bits<C>>,
    multiplier: [Multiplier<D, D, C>; 2],
    difference: RegisteredDifference<C>,
}

impl<const D: usize, const C: usize> crate::unit::Unit for CrossProduct2d<D, C> {
    const LATENCY: Option<usize> = Some(CROSS_PRODUCT_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, multiplier, difference);
    }
}

impl<const D: usize, const C: usize> Default for CrossProduct2d<D, C> {
    fn default() -> Self {
        assert_cross_width(D, C);
        Self {
            clock: Default::default(),
            advance: Default::default(),
            u_x: Default::default(),
            u_y: Default::default(),
            w_x: Default::default(),
            w_y: Default::default(),
            product: Default::default(),
            multiplier: Default::default(),
            difference: Default::default(),
        }
    }
}

impl<const D: usize, const C: usize> Logic for CrossProduct2d<D, C> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..2 {
            self.multiplier[i].clock.next = self.clock.val();
            self.multiplier[i].advance.next = self.advance.val();
        }
        self.multiplier[0].a.next = self.u_x.val();
        self.multiplier[0].b.next = self.w_y.val();
        self.multiplier[1].a.next = self.u_y.val();
        self.multiplier[1].b.next = self.w_x.val();
        self.difference.clock.next = self.clock.val();
        self.difference.advance.next = self.advance.val();
        self.difference.a.next = self.multiplier[0].product.val();
        self.difference.b.next = self.multiplier[1].product.val();
        self.product.next = self.difference.difference.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::arith::convert::{from_i128, to_i128};
    use crate::arith::cross_product::{
        CrossProduct, CrossProduct2d, TwoWayCrossProduct, CROSS_PRODUCT_LATENCY,
    };
    use crate::arith::unit_vectors::{edge_vectors, narrow};
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;
    use tritri_geom::fixed_point::cross;

    #[test]
    fn cross_products_are_exact() {
        let mut uut = CrossProduct::<25, 49>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &edge_vectors(5),
            CROSS_PRODUCT_LATENCY,
            |u, [e1, e2, _]| {
                for k in 0..3 {
                    u.u[k].next = from_i128(e1[k]);
                    u.v[k].next = from_i128(e2[k]);
                }
            },
            |u| u.product.each_ref().map(|p| to_i128(p.val())),
            |[e1, e2, _]| cross(narrow(*e1), narrow(*e2)),
        );
        // Both ways: the product and its negation from the same stage.
        let mut uut = TwoWayCrossProduct::<25, 49>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &edge_vectors(8),
            CROSS_PRODUCT_LATENCY,
            |u, [e1, e2, _]| {
                for k in 0..3 {
                    u.u[k].next = from_i128(e1[k]);
                    u.v[k].next = from_i128(e2[k]);
                }
            },
            |u| {
                (
                    u.product.each_ref().map(|p| to_i128(p.val())),
                    u.negated.each_ref().map(|p| to_i128(p.val())),
                )
            },
            |[e1, e2, _]| {
                let n = cross(narrow(*e1), narrow(*e2));
                (n, n.map(|c| -c))
            },
        );
        let mut uut = CrossProduct2d::<25, 49>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &edge_vectors(6),
            CROSS_PRODUCT_LATENCY,
            |u, [e1, e2, _]| {
                u.u_x.next = from_i128(e1[0]);
                u.u_y.next = from_i128(e1[1]);
                u.w_x.next = from_i128(e2[0]);
                u.w_y.next = from_i128(e2[1]);
            },
            |u| to_i128(u.product.val()),
            |[e1, e2, _]| e1[0] * e2[1] - e1[1] * e2[0],
        );
    }
}
