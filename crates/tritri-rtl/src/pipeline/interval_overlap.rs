//! Step (7), the interval overlap test: with both triangles aligned, the
//! segments they cut on the line where the planes meet overlap iff
//! `[q1, p2, p1, q2] <= 0` and `[p1, p2, r1, r2] <= 0`.
//!
//! Thesis, figure 3.8 (the interval-overlap test unit). Software model:
//! `interval_overlap` in devillers_guigue.rs (the reference macro
//! CHECK_MIN_MAX). This unit turns the rotations and swaps of steps (5) and
//! (6) into the vertex indices of the two orientation determinants (T1's
//! vertices are 0..2, T2's 3..5); the determinants themselves are computed
//! by the shared `orient3d` units, and the `<= 0` test is in `decision`.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from the alignment to the operand indices.
pub const INTERVAL_OVERLAP_LATENCY: usize = 1;

#[derive(LogicBlock, Default)]
pub struct IntervalOverlap {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub t1_rotation: Signal<In, Bits<2>>,
    pub t2_swap: Signal<In, Bit>,
    pub t2_rotation: Signal<In, Bits<2>>,
    pub t1_swap: Signal<In, Bit>,
    /// Vertex indices of `[q1, p2, p1, q2]`.
    pub first: [Signal<Out, Bits<3>>; 4],
    /// Vertex indices of `[p1, p2, r1, r2]`.
    pub second: [Signal<Out, Bits<3>>; 4],
    // Local: T1 aligned (p1, q1, r1 before step (6)'s swap), T2 after step
    // (5)'s swap (s0, s1, s2), and T2 aligned (p2, q2, r2).
    p1: Signal<Local, Bits<3>>,
    q1_unswapped: Signal<Local, Bits<3>>,
    r1_unswapped: Signal<Local, Bits<3>>,
    q1: Signal<Local, Bits<3>>,
    r1: Signal<Local, Bits<3>>,
    s1: Signal<Local, Bits<3>>,
    s2: Signal<Local, Bits<3>>,
    p2: Signal<Local, Bits<3>>,
    q2: Signal<Local, Bits<3>>,
    r2: Signal<Local, Bits<3>>,
    first_q: [DFF<Bits<3>>; 4],
    second_q: [DFF<Bits<3>>; 4],
}

impl crate::unit::Unit for IntervalOverlap {
    const LATENCY: Option<usize> = Some(INTERVAL_OVERLAP_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, first_q, second_q);
    }
}

impl Logic for IntervalOverlap {
    #[hdl_gen]
    fn update(&mut self) {
        // T1 rotated by step (5): [v_k, v_k+1, v_k+2].
        if self.t1_rotation.val() == 0 {
            self.p1.next = 0.into();
            self.q1_unswapped.next = 1.into();
            self.r1_unswapped.next = 2.into();
        } else if self.t1_rotation.val() == 1 {
            self.p1.next = 1.into();
            self.q1_unswapped.next = 2.into();
            self.r1_unswapped.next = 0.into();
        } else {
            self.p1.next = 2.into();
            self.q1_unswapped.next = 0.into();
            self.r1_unswapped.next = 1.into();
        }
        // Step (6) may swap q1 and r1.
        if self.t1_swap.val() {
            self.q1.next = self.r1_unswapped.val();
            self.r1.next = self.q1_unswapped.val();
        } else {
            self.q1.next = self.q1_unswapped.val();
            self.r1.next = self.r1_unswapped.val();
        }
        // T2 after step (5): [p2, q2, r2] or [p2, r2, q2] (indices 3..5).
        if self.t2_swap.val() {
            self.s1.next = 5.into();
            self.s2.next = 4.into();
        } else {
            self.s1.next = 4.into();
            self.s2.next = 5.into();
        }
        // Then rotated by step (6).
        if self.t2_rotation.val() == 0 {
            self.p2.next = 3.into();
            self.q2.next = self.s1.val();
            self.r2.next = self.s2.val();
        } else if self.t2_rotation.val() == 1 {
            self.p2.next = self.s1.val();
            self.q2.next = self.s2.val();
            self.r2.next = 3.into();
        } else {
            self.p2.next = self.s2.val();
            self.q2.next = 3.into();
            self.r2.next = self.s1.val();
        }
        for i in 0..4 {
            self.first_q[i].clock.next = self.clock.val();
            self.first_q[i].d.next = self.first_q[i].q.val();
            self.second_q[i].clock.next = self.clock.val();
            self.second_q[i].d.next = self.second_q[i].q.val();
            self.first[i].next = self.first_q[i].q.val();
            self.second[i].next = self.second_q[i].q.val();
        }
        if self.advance.val() {
            self.first_q[0].d.next = self.q1.val();
            self.first_q[1].d.next = self.p2.val();
            self.first_q[2].d.next = self.p1.val();
            self.first_q[3].d.next = self.q2.val();
            self.second_q[0].d.next = self.p1.val();
            self.second_q[1].d.next = self.p2.val();
            self.second_q[2].d.next = self.r1.val();
            self.second_q[3].d.next = self.r2.val();
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::pipeline::interval_overlap::{IntervalOverlap, INTERVAL_OVERLAP_LATENCY};
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;

    /// Step (7)'s vertex indices: with T1 rotated (and its last two swapped)
    /// and T2 swapped then rotated, the determinants `[q1, p2, p1, q2]` and
    /// `[p1, p2, r1, r2]` of `interval_overlap`, for every rotation and swap.
    #[test]
    fn interval_overlap_names_the_models_determinants() {
        let vectors: Vec<(usize, bool, usize, bool)> = (0..36)
            .map(|k| (k % 3, k / 3 % 2 == 1, k / 6 % 3, k / 18 == 1))
            .collect();
        let mut uut = IntervalOverlap::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &vectors,
            INTERVAL_OVERLAP_LATENCY,
            |u, (r1, s2, r2, s1)| {
                u.t1_rotation.next = (*r1 as u64).into();
                u.t2_swap.next = *s2;
                u.t2_rotation.next = (*r2 as u64).into();
                u.t1_swap.next = *s1;
            },
            |u| {
                (
                    u.first.each_ref().map(|i| i.val().to_u64()),
                    u.second.each_ref().map(|i| i.val().to_u64()),
                )
            },
            |(r1, s2, r2, s1)| {
                let rotate = |t: [u64; 3], k: usize| [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
                let [p1, mut q1, mut r1v] = rotate([0, 1, 2], *r1);
                if *s1 {
                    std::mem::swap(&mut q1, &mut r1v);
                }
                let t2 = if *s2 { [3, 5, 4] } else { [3, 4, 5] };
                let [p2, q2, r2v] = rotate(t2, *r2);
                ([q1, p2, p1, q2], [p1, p2, r1v, r2v])
            },
        );
    }
}
