//! Step (5): align T1. Rotate T1 so that its vertex alone on its side of
//! T2's plane comes first (and lies on the positive side or on the plane),
//! and swap T2's orientation (q2 <-> r2) when that vertex is below.
//!
//! Thesis, figure 3.6 and 3.16 (the T1 vertex-alignment unit: the signs of
//! DV0..DV2 select the multiplexers). Software model: `align_t1` in
//! devillers_guigue.rs, whose sign table [`AlignmentTable`] reproduces arm
//! by arm; step (6) (`align_t2`) uses the same table. Decided on signs only.
//!
//! Here the unit does not move coordinates: it outputs the rotation of T1
//! and the swap of T2 (the vertex multiplexers come later, see
//! `orient3d_operands`), plus T2's signs permuted by the swap for step (6).

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from signs to alignment.
pub const ALIGN_T1_LATENCY: usize = 1;

/// The sign table shared by steps (5) and (6), combinational. For signs
/// `(s0, s1, s2)` of a triangle's vertices against the other plane it gives
/// the rotation `k` (the aligned triangle is `[v_k, v_k+1, v_k+2]`) and
/// whether the other triangle's last two vertices trade places.
/// The all-zero row is unreachable (coplanar pairs never get here).
#[derive(LogicBlock, Default)]
pub struct AlignmentTable {
    pub negative: [Signal<In, Bit>; 3],
    pub zero: [Signal<In, Bit>; 3],
    pub rotation: Signal<Out, Bits<2>>,
    pub swap: Signal<Out, Bit>,
}

impl crate::unit::Unit for AlignmentTable {}

impl Logic for AlignmentTable {
    #[hdl_gen]
    fn update(&mut self) {
        // Arms in the order of the reference code (positive = neither
        // negative nor zero).
        if !self.negative[0].val() && !self.zero[0].val() {
            if !self.negative[1].val() && !self.zero[1].val() {
                // (+, +, _): [r, p, q], swap
                self.rotation.next = 2.into();
                self.swap.next = true;
            } else if !self.negative[2].val() && !self.zero[2].val() {
                // (+, _, +): [q, r, p], swap
                self.rotation.next = 1.into();
                self.swap.next = true;
            } else {
                // (+, _, _): [p, q, r], keep
                self.rotation.next = 0.into();
                self.swap.next = false;
            }
        } else if self.negative[0].val() {
            if self.negative[1].val() {
                // (-, -, _): [r, p, q], keep
                self.rotation.next = 2.into();
                self.swap.next = false;
            } else if self.negative[2].val() {
                // (-, _, -): [q, r, p], keep
                self.rotation.next = 1.into();
                self.swap.next = false;
            } else {
                // (-, _, _): [p, q, r], swap
                self.rotation.next = 0.into();
                self.swap.next = true;
            }
        } else if self.negative[1].val() {
            if self.negative[2].val() {
                // (0, -, -): [p, q, r], keep
                self.rotation.next = 0.into();
                self.swap.next = false;
            } else {
                // (0, -, + or 0): [q, r, p], swap
                self.rotation.next = 1.into();
                self.swap.next = true;
            }
        } else if !self.zero[1].val() {
            if !self.negative[2].val() && !self.zero[2].val() {
                // (0, +, +): [p, q, r], swap
                self.rotation.next = 0.into();
                self.swap.next = true;
            } else {
                // (0, +, - or 0): [q, r, p], keep
                self.rotation.next = 1.into();
                self.swap.next = false;
            }
        } else if !self.negative[2].val() && !self.zero[2].val() {
            // (0, 0, +): [r, p, q], keep
            self.rotation.next = 2.into();
            self.swap.next = false;
        } else {
            // (0, 0, -): [r, p, q], swap; (0, 0, 0) is unreachable.
            self.rotation.next = 2.into();
            self.swap.next = true;
        }
    }
}

#[derive(LogicBlock, Default)]
pub struct AlignT1 {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// Signs of T1's vertices against T2's plane.
    pub t1_negative: [Signal<In, Bit>; 3],
    pub t1_zero: [Signal<In, Bit>; 3],
    /// Signs of T2's vertices against T1's plane.
    pub t2_negative: [Signal<In, Bit>; 3],
    pub t2_zero: [Signal<In, Bit>; 3],
    /// T1 becomes `[t1_k, t1_k+1, t1_k+2]` for `k = t1_rotation`.
    pub t1_rotation: Signal<Out, Bits<2>>,
    /// T2 becomes `[p2, r2, q2]`.
    pub t2_swap: Signal<Out, Bit>,
    /// T2's signs in T2's new vertex order.
    pub t2_aligned_negative: [Signal<Out, Bit>; 3],
    pub t2_aligned_zero: [Signal<Out, Bit>; 3],
    sign_table: AlignmentTable,
    t1_rotation_q: DFF<Bits<2>>,
    t2_swap_q: DFF<Bit>,
    t2_aligned_negative_q: [DFF<Bit>; 3],
    t2_aligned_zero_q: [DFF<Bit>; 3],
}

impl crate::unit::Unit for AlignT1 {
    const LATENCY: Option<usize> = Some(ALIGN_T1_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            sign_table,
            t1_rotation_q,
            t2_swap_q,
            t2_aligned_negative_q,
            t2_aligned_zero_q
        );
    }
}

impl Logic for AlignT1 {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..3 {
            self.sign_table.negative[i].next = self.t1_negative[i].val();
            self.sign_table.zero[i].next = self.t1_zero[i].val();
            self.t2_aligned_negative_q[i].clock.next = self.clock.val();
            self.t2_aligned_negative_q[i].d.next = self.t2_aligned_negative_q[i].q.val();
            self.t2_aligned_zero_q[i].clock.next = self.clock.val();
            self.t2_aligned_zero_q[i].d.next = self.t2_aligned_zero_q[i].q.val();
            self.t2_aligned_negative[i].next = self.t2_aligned_negative_q[i].q.val();
            self.t2_aligned_zero[i].next = self.t2_aligned_zero_q[i].q.val();
        }
        dff_setup!(self, clock, t1_rotation_q, t2_swap_q);
        if self.advance.val() {
            self.t1_rotation_q.d.next = self.sign_table.rotation.val();
            self.t2_swap_q.d.next = self.sign_table.swap.val();
            self.t2_aligned_negative_q[0].d.next = self.t2_negative[0].val();
            self.t2_aligned_zero_q[0].d.next = self.t2_zero[0].val();
            if self.sign_table.swap.val() {
                self.t2_aligned_negative_q[1].d.next = self.t2_negative[2].val();
                self.t2_aligned_zero_q[1].d.next = self.t2_zero[2].val();
                self.t2_aligned_negative_q[2].d.next = self.t2_negative[1].val();
                self.t2_aligned_zero_q[2].d.next = self.t2_zero[1].val();
            } else {
                self.t2_aligned_negative_q[1].d.next = self.t2_negative[1].val();
                self.t2_aligned_zero_q[1].d.next = self.t2_zero[1].val();
                self.t2_aligned_negative_q[2].d.next = self.t2_negative[2].val();
                self.t2_aligned_zero_q[2].d.next = self.t2_zero[2].val();
            }
        }
        self.t1_rotation.next = self.t1_rotation_q.q.val();
        self.t2_swap.next = self.t2_swap_q.q.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::pipeline::align_t1::{AlignT1, ALIGN_T1_LATENCY};
    use crate::pipeline::align_t2::{AlignT2, ALIGN_T2_LATENCY};
    use crate::pipeline::unit_vectors::{set_signs, sign_triples};
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;
    use tritri_geom::devillers_guigue::{align_t1, align_t2};
    use tritri_geom::sign::Sign;

    /// Steps (5) and (6) against `align_t1` and `align_t2` on labelled
    /// vertices (T1 = 0, 1, 2; T2 = 3, 4, 5), for every pair of sign triples.
    #[test]
    fn alignment_units_follow_the_models_sign_tables() {
        let vectors: Vec<([Sign; 3], [Sign; 3])> = sign_triples()
            .into_iter()
            .flat_map(|d1| sign_triples().into_iter().map(move |d2| (d1, d2)))
            .collect();
        let mut uut = AlignT1::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &vectors,
            ALIGN_T1_LATENCY,
            |u, (d1, d2)| {
                set_signs(&mut u.t1_negative, &mut u.t1_zero, d1);
                set_signs(&mut u.t2_negative, &mut u.t2_zero, d2);
            },
            |u| {
                let aligned = std::array::from_fn::<_, 3, _>(|k| {
                    (u.t2_aligned_negative[k].val(), u.t2_aligned_zero[k].val())
                });
                (
                    u.t1_rotation.val().to_u64() as usize,
                    u.t2_swap.val(),
                    aligned,
                )
            },
            |(d1, d2)| {
                let (t1, t2, d2) = align_t1([0usize, 1, 2], [3usize, 4, 5], *d1, *d2);
                (
                    t1[0],
                    t2 != [3, 4, 5],
                    d2.map(|s| (s == Sign::Negative, s == Sign::Zero)),
                )
            },
        );
        // Step (6): T2's rotation and T1's swap; step (5)'s pass through.
        let vectors: Vec<([Sign; 3], usize, bool)> = sign_triples()
            .into_iter()
            .enumerate()
            .map(|(k, d2)| (d2, k % 3, k % 2 == 0))
            .collect();
        let mut uut = AlignT2::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &vectors,
            ALIGN_T2_LATENCY,
            |u, (d2, rotation, swap)| {
                set_signs(&mut u.t2_aligned_negative, &mut u.t2_aligned_zero, d2);
                u.t1_rotation_in.next = (*rotation as u64).into();
                u.t2_swap_in.next = *swap;
            },
            |u| {
                (
                    u.t2_rotation.val().to_u64() as usize,
                    u.t1_swap.val(),
                    u.t1_rotation.val().to_u64() as usize,
                    u.t2_swap.val(),
                )
            },
            |(d2, rotation, swap)| {
                let aligned = align_t2([0usize, 1, 2], *d2);
                (aligned.t2[0], aligned.swap_t1, *rotation, *swap)
            },
        );
    }
}
