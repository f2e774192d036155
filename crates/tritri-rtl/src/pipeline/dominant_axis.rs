//! The axis of the largest |component| of a normal, ties to the lowest axis:
//! the projection used by the coplanar test drops it, so the projection is
//! one-to-one on the triangle's plane.
//!
//! Software model: `FixedPoint::dominant_normal_axis` and
//! `tritri_geom::fixed_point::dominant_axis` (used by `coplanar_triangles`
//! and `segment_triangle` in devillers_guigue.rs). Three stages:
//! magnitudes, the three comparisons, the axis. (Comparisons and axis in
//! one stage were a 2W + 1-bit carry chain into a select, 137 MHz on ECP5.)
//! The magnitudes are selected from the normal and its negation, both
//! registered by the cross product: negating here was a 2W + 1-bit carry
//! chain behind 4.5 ns of routing from the cross product's registers, the
//! W = 16 pipeline's worst path on ECP5 (137.7 MHz, seed 3). A component's
//! magnitude is at most `M^2 < 2^(2W)`, so the negation never overflows.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from normal to axis.
pub const DOMINANT_AXIS_LATENCY: usize = 3;

#[derive(LogicBlock)]
pub struct DominantAxis<const C: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub normal: [Signal<In, Bits<C>>; 3],
    /// `-normal`.
    pub negated: [Signal<In, Bits<C>>; 3],
    /// 0, 1 or 2.
    pub axis: Signal<Out, Bits<2>>,
    top_bit: Constant<Bits<8>>,
    magnitude: [DFF<Bits<C>>; 3],
    /// |n0| >= |n1|, |n0| >= |n2|, |n1| >= |n2|.
    at_least_q: [DFF<Bit>; 3],
    axis_q: DFF<Bits<2>>,
}

impl<const C: usize> crate::unit::Unit for DominantAxis<C> {
    const LATENCY: Option<usize> = Some(DOMINANT_AXIS_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, magnitude, at_least_q, axis_q);
    }
}

impl<const C: usize> Default for DominantAxis<C> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            advance: Default::default(),
            normal: Default::default(),
            negated: Default::default(),
            axis: Default::default(),
            top_bit: Constant::new(Bits::<8>::from((C - 1) as u64)),
            magnitude: Default::default(),
            at_least_q: Default::default(),
            axis_q: Default::default(),
        }
    }
}

impl<const C: usize> Logic for DominantAxis<C> {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..3 {
            self.magnitude[k].clock.next = self.clock.val();
            self.magnitude[k].d.next = self.magnitude[k].q.val();
            if self.advance.val() {
                if self.normal[k].val().get_bit(self.top_bit.val().index()) {
                    self.magnitude[k].d.next = self.negated[k].val();
                } else {
                    self.magnitude[k].d.next = self.normal[k].val();
                }
            }
        }
        for k in 0..3 {
            self.at_least_q[k].clock.next = self.clock.val();
            self.at_least_q[k].d.next = self.at_least_q[k].q.val();
        }
        if self.advance.val() {
            self.at_least_q[0].d.next = self.magnitude[0].q.val() >= self.magnitude[1].q.val();
            self.at_least_q[1].d.next = self.magnitude[0].q.val() >= self.magnitude[2].q.val();
            self.at_least_q[2].d.next = self.magnitude[1].q.val() >= self.magnitude[2].q.val();
        }
        dff_setup!(self, clock, axis_q);
        if self.advance.val() {
            if self.at_least_q[0].q.val() && self.at_least_q[1].q.val() {
                self.axis_q.d.next = 0.into();
            } else if self.at_least_q[2].q.val() {
                self.axis_q.d.next = 1.into();
            } else {
                self.axis_q.d.next = 2.into();
            }
        }
        self.axis.next = self.axis_q.q.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::arith::convert::from_i128;
    use crate::pipeline::dominant_axis::{DominantAxis, DOMINANT_AXIS_LATENCY};
    use crate::pipeline::unit_vectors::{normal, triangles};
    use crate::sim_drive::assert_stream_matches;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rust_hdl::prelude::*;
    use tritri_geom::fixed_point::dominant_axis;

    #[test]
    fn dominant_axis_is_the_largest_component_ties_low() {
        // Normals of random triangles, and ties: equal magnitudes of either sign.
        let mut normals: Vec<[i128; 3]> = triangles(2).iter().map(normal).collect();
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..100 {
            let m: i128 = rng.gen_range(0..1 << 40);
            let s = |rng: &mut ChaCha8Rng| if rng.gen_bool(0.5) { m } else { -m };
            normals.push([s(&mut rng), s(&mut rng), rng.gen_range(-m..=m)]);
            normals.push([rng.gen_range(-m..=m), s(&mut rng), s(&mut rng)]);
        }
        let mut uut = DominantAxis::<49>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &normals,
            DOMINANT_AXIS_LATENCY,
            |u, n| {
                for k in 0..3 {
                    u.normal[k].next = from_i128(n[k]);
                    u.negated[k].next = from_i128(-n[k]);
                }
            },
            |u| u.axis.val().to_u64() as usize,
            |n| dominant_axis(n.map(|c| c.unsigned_abs())),
        );
    }
}
