//! The verdict of a pair and its certificate, from signs only
//! (docs/ARCHITECTURE.md, conventions), mirroring the control flow of
//! `intersects` in devillers_guigue.rs.
//!
//! The cases:
//!
//! * both triangles proper (`triangles_intersect`): no if either
//!   triangle's vertices are all strictly on one side of the other's plane
//!   (steps (2) and (4)); if T1 lies in T2's plane, the coplanar test;
//!   otherwise step (7): `[q1, p2, p1, q2] <= 0` and `[p1, p2, r1, r2] <= 0`
//!   (orient3d units 0 and 1);
//! * one degenerate, spanning `[a, b]` (`segment_triangle`): no if `a` and
//!   `b` are strictly on one side of the other triangle's plane; if both are
//!   on it, the coplanar test; otherwise yes iff the three signs of
//!   `[a, b, v_i, v_i+1]` (orient3d units 0 and 1, and the third
//!   determinant) are not strictly opposite;
//! * both degenerate (`degenerate_pair`): `[a, b, c, d] == 0` (unit 0) and
//!   the three-projection segment test.
//!
//! The signs of a degenerate triangle's segment ends against the other
//! plane are the plane-side signs of the vertices at `segment_low` and
//! `segment_high`.
//!
//! The certificate (`tritri_geom::certificate::certain`, whatever the
//! case): a triangle's vertices certainly strictly on one side of the
//! other's plane, or all six plane signs certain and step (7)'s two
//! determinants certain or one of them certainly positive.
//!
//! Three stages: each case's parts (the triangles' verdict, the segment
//! ends' signs, whether the segment case's signs are mixed, the flags),
//! registered; the case's verdict without the rare tests, and which rare
//! test's verdict it takes; then the verdict. In one stage, an orient3d
//! sign reached the verdict register through five LUT levels, the W = 8
//! pipeline's critical path on ECP5 (144 MHz); with the case chosen in the
//! first stage, a segment end's index reached the second through five
//! (W = 16, P = 1 shared system, seed 3: its worst path at 153.7 MHz, and
//! the last input short of 150 MHz at W = 8, P = 2). The rare tests'
//! verdicts (`coplanar_hit`, `degenerate_pair_hit`) come two clocks after
//! the other inputs, into the last stage, which is one LUT: with the
//! three cases' verdicts and the case registered instead, it was three
//! levels from the shared unit's verdict, across the chip, to `hit_q`
//! (W = 16 shared system, ECP5: the critical path, 148.3 MHz, 5.3 of 6.7
//! ns routing). Those two clocks are the shared rare-case unit's time
//! (`super::shared_rare_pipeline`): the middle stage is there for the
//! unit, whose pairs reach it a stage later since the pipelines hold
//! three clocks ahead (`super::hold_forecast`).

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from inputs to `hit`.
pub const DECISION_LATENCY: usize = 3;

#[derive(LogicBlock, Default)]
pub struct Decision {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub t1_degenerate: Signal<In, Bit>,
    pub t2_degenerate: Signal<In, Bit>,
    pub t1_segment_low: Signal<In, Bits<2>>,
    pub t1_segment_high: Signal<In, Bits<2>>,
    pub t2_segment_low: Signal<In, Bits<2>>,
    pub t2_segment_high: Signal<In, Bits<2>>,
    /// Signs of T1's vertices against T2's plane (steps 1-2).
    pub t1_side_negative: [Signal<In, Bit>; 3],
    pub t1_side_zero: [Signal<In, Bit>; 3],
    /// Signs of T2's vertices against T1's plane (steps 3-4).
    pub t2_side_negative: [Signal<In, Bit>; 3],
    pub t2_side_zero: [Signal<In, Bit>; 3],
    /// Signs of the two shared orient3d units, then of the segment-triangle
    /// case's third determinant (`super::third_determinant`).
    pub orient_negative: [Signal<In, Bit>; 3],
    pub orient_zero: [Signal<In, Bit>; 3],
    /// Certificates of the plane signs, and of orient3d units 0 and 1
    /// (step (7); the third determinant serves degenerate pairs only, never
    /// certain).
    pub t1_side_certain: [Signal<In, Bit>; 3],
    pub t2_side_certain: [Signal<In, Bit>; 3],
    pub orient_certain: [Signal<In, Bit>; 2],
    /// The rare tests' verdicts, two clocks after the inputs above (each
    /// is read only when the pair's case needs it).
    pub coplanar_hit: Signal<In, Bit>,
    pub degenerate_pair_hit: Signal<In, Bit>,
    pub hit: Signal<Out, Bit>,
    /// The verdict is the verdict on the original coordinates.
    pub certain: Signal<Out, Bit>,
    t1_side_positive: [Signal<Local, Bit>; 3],
    t2_side_positive: [Signal<Local, Bit>; 3],
    orient_positive: [Signal<Local, Bit>; 3],
    /// The triangles' verdict (both proper), unless they are coplanar.
    triangles_hit: Signal<Local, Bit>,
    triangles_coplanar: Signal<Local, Bit>,
    /// Signs of the degenerate triangle's segment ends against the other plane.
    end_a_negative: Signal<Local, Bit>,
    end_a_zero: Signal<Local, Bit>,
    end_b_negative: Signal<Local, Bit>,
    end_b_zero: Signal<Local, Bit>,
    /// The three signs of the segment case are not strictly opposite.
    orient_mixed: Signal<Local, Bit>,
    segment_hit: Signal<Local, Bit>,
    segment_coplanar: Signal<Local, Bit>,
    /// Every plane sign of T1 (of T2) is certain.
    t1_sides_certain: Signal<Local, Bit>,
    t2_sides_certain: Signal<Local, Bit>,
    /// Stage 1: the certificate's rules 1 or 2, and rule 3; stage 2: either;
    /// stage 3: the same.
    rejected_certainly_q: DFF<Bit>,
    interval_certain_q: DFF<Bit>,
    certain_q: DFF<Bit>,
    certain_out_q: DFF<Bit>,
    /// Stage 1: each case's parts: the triangles' verdict, the segment
    /// ends' signs, whether the segment case's signs are mixed, the
    /// degenerate flags and `[a, b, c, d] == 0`.
    triangles_hit_q: DFF<Bit>,
    triangles_coplanar_q: DFF<Bit>,
    end_a_negative_q: DFF<Bit>,
    end_a_zero_q: DFF<Bit>,
    end_b_negative_q: DFF<Bit>,
    end_b_zero_q: DFF<Bit>,
    orient_mixed_q: DFF<Bit>,
    t1_degenerate_q: DFF<Bit>,
    t2_degenerate_q: DFF<Bit>,
    segments_touch_q: DFF<Bit>,
    /// Stage 2: the case's verdict if it needs no rare test, and whether
    /// it is the coplanar test's or (two segments with `[a, b, c, d] ==
    /// 0`) the degenerate-pair test's instead.
    base_hit_q: DFF<Bit>,
    needs_coplanar_q: DFF<Bit>,
    needs_degenerate_pair_q: DFF<Bit>,
    hit_q: DFF<Bit>,
}

impl crate::unit::Unit for Decision {
    const LATENCY: Option<usize> = Some(DECISION_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            rejected_certainly_q,
            interval_certain_q,
            certain_q,
            triangles_hit_q,
            triangles_coplanar_q,
            end_a_negative_q,
            end_a_zero_q,
            end_b_negative_q,
            end_b_zero_q,
            orient_mixed_q,
            t1_degenerate_q,
            t2_degenerate_q,
            segments_touch_q,
            base_hit_q,
            needs_coplanar_q,
            needs_degenerate_pair_q,
            hit_q,
            certain_out_q
        );
    }
}

impl Logic for Decision {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..3 {
            self.t1_side_positive[i].next =
                !self.t1_side_negative[i].val() && !self.t1_side_zero[i].val();
            self.t2_side_positive[i].next =
                !self.t2_side_negative[i].val() && !self.t2_side_zero[i].val();
            self.orient_positive[i].next =
                !self.orient_negative[i].val() && !self.orient_zero[i].val();
        }
        // triangles_intersect.
        if (self.t1_side_positive[0].val()
            && self.t1_side_positive[1].val()
            && self.t1_side_positive[2].val())
            || (self.t1_side_negative[0].val()
                && self.t1_side_negative[1].val()
                && self.t1_side_negative[2].val())
            || (self.t2_side_positive[0].val()
                && self.t2_side_positive[1].val()
                && self.t2_side_positive[2].val())
            || (self.t2_side_negative[0].val()
                && self.t2_side_negative[1].val()
                && self.t2_side_negative[2].val())
        {
            self.triangles_hit.next = false;
            self.triangles_coplanar.next = false;
        } else if self.t1_side_zero[0].val()
            && self.t1_side_zero[1].val()
            && self.t1_side_zero[2].val()
        {
            self.triangles_hit.next = false;
            self.triangles_coplanar.next = true;
        } else {
            self.triangles_hit.next =
                !self.orient_positive[0].val() && !self.orient_positive[1].val();
            self.triangles_coplanar.next = false;
        }
        // segment_triangle: the ends' signs.
        self.end_a_negative.next = false;
        self.end_a_zero.next = false;
        self.end_b_negative.next = false;
        self.end_b_zero.next = false;
        if self.t1_degenerate.val() {
            for v in 0..3 {
                if self.t1_segment_low.val().index() == v {
                    self.end_a_negative.next = self.t1_side_negative[v].val();
                    self.end_a_zero.next = self.t1_side_zero[v].val();
                }
                if self.t1_segment_high.val().index() == v {
                    self.end_b_negative.next = self.t1_side_negative[v].val();
                    self.end_b_zero.next = self.t1_side_zero[v].val();
                }
            }
        } else {
            for v in 0..3 {
                if self.t2_segment_low.val().index() == v {
                    self.end_a_negative.next = self.t2_side_negative[v].val();
                    self.end_a_zero.next = self.t2_side_zero[v].val();
                }
                if self.t2_segment_high.val().index() == v {
                    self.end_b_negative.next = self.t2_side_negative[v].val();
                    self.end_b_zero.next = self.t2_side_zero[v].val();
                }
            }
        }
        self.orient_mixed.next = (self.orient_positive[0].val()
            || self.orient_positive[1].val()
            || self.orient_positive[2].val())
            && (self.orient_negative[0].val()
                || self.orient_negative[1].val()
                || self.orient_negative[2].val());
        // segment_triangle's verdict, from stage 1's registers.
        if (self.end_a_negative_q.q.val() && self.end_b_negative_q.q.val())
            || (!self.end_a_negative_q.q.val()
                && !self.end_a_zero_q.q.val()
                && !self.end_b_negative_q.q.val()
                && !self.end_b_zero_q.q.val())
        {
            self.segment_hit.next = false;
            self.segment_coplanar.next = false;
        } else if self.end_a_zero_q.q.val() && self.end_b_zero_q.q.val() {
            self.segment_hit.next = false;
            self.segment_coplanar.next = true;
        } else {
            self.segment_coplanar.next = false;
            self.segment_hit.next = !self.orient_mixed_q.q.val();
        }
        // The certificate's rules 1 and 2, and rule 3.
        self.t1_sides_certain.next = self.t1_side_certain[0].val()
            && self.t1_side_certain[1].val()
            && self.t1_side_certain[2].val();
        self.t2_sides_certain.next = self.t2_side_certain[0].val()
            && self.t2_side_certain[1].val()
            && self.t2_side_certain[2].val();
        dff_setup!(
            self,
            clock,
            triangles_hit_q,
            triangles_coplanar_q,
            end_a_negative_q,
            end_a_zero_q,
            end_b_negative_q,
            end_b_zero_q,
            orient_mixed_q,
            t1_degenerate_q,
            t2_degenerate_q,
            segments_touch_q,
            base_hit_q,
            needs_coplanar_q,
            needs_degenerate_pair_q,
            hit_q,
            rejected_certainly_q,
            interval_certain_q,
            certain_q,
            certain_out_q
        );
        if self.advance.val() {
            self.triangles_hit_q.d.next = self.triangles_hit.val();
            self.triangles_coplanar_q.d.next = self.triangles_coplanar.val();
            self.end_a_negative_q.d.next = self.end_a_negative.val();
            self.end_a_zero_q.d.next = self.end_a_zero.val();
            self.end_b_negative_q.d.next = self.end_b_negative.val();
            self.end_b_zero_q.d.next = self.end_b_zero.val();
            self.orient_mixed_q.d.next = self.orient_mixed.val();
            self.t1_degenerate_q.d.next = self.t1_degenerate.val();
            self.t2_degenerate_q.d.next = self.t2_degenerate.val();
            self.segments_touch_q.d.next = self.orient_zero[0].val();
            if !self.t1_degenerate_q.q.val() && !self.t2_degenerate_q.q.val() {
                self.base_hit_q.d.next = self.triangles_hit_q.q.val();
                self.needs_coplanar_q.d.next = self.triangles_coplanar_q.q.val();
                self.needs_degenerate_pair_q.d.next = false;
            } else if self.t1_degenerate_q.q.val() && self.t2_degenerate_q.q.val() {
                self.base_hit_q.d.next = false;
                self.needs_coplanar_q.d.next = false;
                self.needs_degenerate_pair_q.d.next = self.segments_touch_q.q.val();
            } else {
                self.base_hit_q.d.next = self.segment_hit.val();
                self.needs_coplanar_q.d.next = self.segment_coplanar.val();
                self.needs_degenerate_pair_q.d.next = false;
            }
            self.rejected_certainly_q.d.next = (self.t1_sides_certain.val()
                && ((self.t1_side_positive[0].val()
                    && self.t1_side_positive[1].val()
                    && self.t1_side_positive[2].val())
                    || (self.t1_side_negative[0].val()
                        && self.t1_side_negative[1].val()
                        && self.t1_side_negative[2].val())))
                || (self.t2_sides_certain.val()
                    && ((self.t2_side_positive[0].val()
                        && self.t2_side_positive[1].val()
                        && self.t2_side_positive[2].val())
                        || (self.t2_side_negative[0].val()
                            && self.t2_side_negative[1].val()
                            && self.t2_side_negative[2].val())));
            self.interval_certain_q.d.next = self.t1_sides_certain.val()
                && self.t2_sides_certain.val()
                && ((self.orient_certain[0].val() && self.orient_certain[1].val())
                    || (self.orient_certain[0].val() && self.orient_positive[0].val())
                    || (self.orient_certain[1].val() && self.orient_positive[1].val()));
            self.certain_q.d.next =
                self.rejected_certainly_q.q.val() || self.interval_certain_q.q.val();
            self.certain_out_q.d.next = self.certain_q.q.val();
            self.hit_q.d.next = self.base_hit_q.q.val()
                || (self.needs_coplanar_q.q.val() && self.coplanar_hit.val())
                || (self.needs_degenerate_pair_q.q.val() && self.degenerate_pair_hit.val());
        }
        self.hit.next = self.hit_q.q.val();
        self.certain.next = self.certain_out_q.q.val();
    }
}
