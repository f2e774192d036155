//! The rare cases on one shared, slower path: the coplanar test and the
//! degenerate pair's segment test, computed by three orient2d lanes (six
//! multipliers) over several clocks instead of by the 18 + 12 orient2d of
//! [`super::coplanar_test::CoplanarTest`] and
//! [`super::degenerate_pair::DegeneratePair`] (60 multipliers).
//!
//! A job is one pair: its six vertices, the projection's axis and the
//! normals' signs (coplanar), or the two segments' ends (degenerate pair,
//! `in_segments`). It is taken when `in_valid` and `ready` are high, and its
//! verdict leaves with `done` in order, a fixed number of clocks later:
//! [`SHARED_RARE_CASES_LATENCY`]. The unit issues one step a clock, three
//! orient2d values each: [`COPLANAR_STEPS`] steps for a coplanar pair (the
//! eighteen values of `hulls_intersect_2d`), [`SEGMENTS_STEPS`] for two
//! segments (the components of `[a, b, c]`, `[a, b, d]`, `[c, d, a]`,
//! `[c, d, b]`). `ready` rises in the clock of a job's last step, so jobs
//! follow each other without a gap. Signs go into a register file at
//! `3 step + lane`, the numbering of [`super::rare_decisions`], whose
//! decisions then give the verdict; the coordinate comparisons and the
//! orientations (no multipliers) are formed once per job, at its last
//! step, and carried beside the lanes.
//!
//! A degenerate pair's job keeps its ends as points 0, 1 (`a`, `b`: T1's
//! lexicographic ends) and 3, 4 (`c`, `d`: T2's), so that its steps and
//! comparisons are fixed wiring.
//!
//! Stages of a step: the points (1), their differences (1), the
//! projection of each lane (1: axis `k` keeps coordinates `k + 1` and
//! `k + 2`; a degenerate pair's lane `k` drops axis `k`), orient2d
//! (`CROSS_PRODUCT_LATENCY`), the sign (1); then the register file (1),
//! the decision (2) and the output registers (1).

use super::rare_decisions::{
    CoplanarContacts, CoplanarDecision, SegmentContacts, SegmentsDecision,
    COPLANAR_DECISION_LATENCY, SEGMENTS_DECISION_LATENCY,
};
use super::step_programs::StepPrograms;
use crate::arith::compare::{SplitCompare, SPLIT_COMPARE_LATENCY};
use crate::arith::cross_product::{CrossProduct2d, CROSS_PRODUCT_LATENCY};
use crate::arith::delay_line::DelayLine;
use crate::arith::one_hot_choice::OneHotChoice;
use crate::arith::sign::{SignOf, SIGN_LATENCY};
use crate::arith::subtractor::{VectorSubtractor, SUBTRACTOR_LATENCY};
use crate::arith::valid_line::ValidLine;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Steps of a coplanar pair (18 orient2d values, three a clock; the
/// update's literal 6).
pub const COPLANAR_STEPS: usize = 6;
/// Steps of two segments (12 orient2d values; the update's literal 4).
pub const SEGMENTS_STEPS: usize = 4;
/// Clock edges from a step's issue (its points chosen) to its lanes' signs.
const LANE_LATENCY: usize = 1 + SUBTRACTOR_LATENCY + 1 + CROSS_PRODUCT_LATENCY + SIGN_LATENCY;
/// The job's context (comparisons, orientations, kind), formed in its last
/// step's clock, meets the complete register file a clock after the last
/// signs.
const CONTEXT_DELAY: usize = LANE_LATENCY + 1;
const _: () = assert!(SEGMENTS_DECISION_LATENCY < COPLANAR_DECISION_LATENCY);
/// A job's points load at the edge that takes it, and its first step is
/// issued at the next; the context is sampled at the edge that issues its
/// last step. The comparisons there see the points of `1 +
/// SPLIT_COMPARE_LATENCY` clocks before that clock (`compare_points_q`,
/// then the comparison's two stages), which must be this job's: a job of
/// `S` steps needs `S >= 2 + SPLIT_COMPARE_LATENCY`.
const _: () = assert!(SEGMENTS_STEPS >= 2 + SPLIT_COMPARE_LATENCY);
const _: () = assert!(COPLANAR_STEPS >= SEGMENTS_STEPS);
/// Clock edges from a coplanar job's acceptance to its `done`: its last
/// step is issued `COPLANAR_STEPS - 1` clocks after its first, which is
/// issued a clock after the job is taken; then the lanes, the register
/// file (the `+ 1` of `CONTEXT_DELAY`), the decision and the output
/// registers. A degenerate pair's job takes `COPLANAR_STEPS -
/// SEGMENTS_STEPS` fewer.
pub const SHARED_RARE_CASES_LATENCY: usize =
    COPLANAR_STEPS + CONTEXT_DELAY + COPLANAR_DECISION_LATENCY + OUTPUT_LATENCY - 1;
/// `done` and `hit` leave from registers: the verdict's way to the
/// pipeline's queue and on to its decision starts at the unit's edge, not
/// behind the choice between the kinds' verdicts (ECP5, W = 16 shared,
/// seed 2: the coplanar verdict through that choice, the queue's bypass,
/// since removed, and 6.4 ns of routing into the decision's `hit_q`, 123.9
/// MHz).
const OUTPUT_LATENCY: usize = 1;
/// Copies of the steps left, each with an `in_valid` of its own: one per
/// coordinate of stage 1's destinations (`u0`, `u1`, `w0`'s lanes, `w1`'s:
/// 8 × 3) and one for the lines beside the lanes (the update's literal 25).
pub const IN_VALID_COPIES: usize = 25;

#[derive(LogicBlock, Default)]
pub struct SharedRareCases<const W: usize, const D: usize, const C: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: no job in the unit.
    pub reset: Signal<In, Bit>,
    /// A job is offered; it is taken at the clock edge if `ready` is high.
    pub in_valid: Signal<In, Bit>,
    /// `in_valid` again, once for each copy of the steps left (`3 p + k`
    /// for point `p`'s coordinate `k`, and 24 for the lines): a pipeline
    /// drives each from a register of its own beside the copy's loads (W =
    /// 16, router1: one `in_valid` net into all 25 copies, 9.1 of 10.8 ns
    /// routing, 93.0 MHz).
    pub in_valid_copies: [Signal<In, Bit>; IN_VALID_COPIES],
    /// The job is a degenerate pair (else a coplanar pair).
    pub in_segments: Signal<In, Bit>,
    pub t1_vertices: [Signal<In, Bits<W>>; 9],
    pub t2_vertices: [Signal<In, Bits<W>>; 9],
    /// Coplanar: the axis the projection drops, and the normals' signs.
    pub axis: Signal<In, Bits<2>>,
    pub t1_normal_negative: [Signal<In, Bit>; 3],
    pub t1_normal_zero: [Signal<In, Bit>; 3],
    pub t2_normal_negative: [Signal<In, Bit>; 3],
    pub t2_normal_zero: [Signal<In, Bit>; 3],
    /// Degenerate pair: each segment's lexicographic ends.
    pub t1_segment_low: Signal<In, Bits<2>>,
    pub t1_segment_high: Signal<In, Bits<2>>,
    pub t2_segment_low: Signal<In, Bits<2>>,
    pub t2_segment_high: Signal<In, Bits<2>>,
    /// The unit takes a job at this clock's edge.
    pub ready: Signal<Out, Bit>,
    /// `ready` will be high three clocks from now unless a job is taken
    /// before: at most four steps of the current job are left.
    pub idle_in_three: Signal<Out, Bit>,
    /// A job's verdict is on `hit`.
    pub done: Signal<Out, Bit>,
    pub hit: Signal<Out, Bit>,
    /// The verdict of the job whose kind `segments_out` gives, before the
    /// output register.
    verdict: Signal<Local, Bit>,
    hit_q: DFF<Bit>,
    /// The job: point `i` coordinate `k` at `3 i + k` (T1: 0..2, T2: 3..5).
    points_q: [DFF<Bits<W>>; 18],
    segments_q: DFF<Bit>,
    axis_q: DFF<Bits<2>>,
    /// T1's normal's negative and zero flags (`k`, `3 + k`), then T2's.
    normal_q: [DFF<Bit>; 12],
    /// Steps left to issue (the current one included).
    remaining_q: DFF<Bits<3>>,
    /// The current step's number, the job's kind and the steps left, in
    /// copies: `3 d + k` for coordinate `k` of stage 1's destination `d`
    /// (`u0`, `u1`, `w0`'s lanes, then `w1`'s), and 24 for the lines beside
    /// the lanes. Each counts from its own value, so synthesis keeps them
    /// apart, and each loads by its own count (as does point `p`'s
    /// coordinate `k` by copy `3 p + k`), so that no register drives the
    /// loads of all of them (W = 16: one step per destination, 48
    /// bits, was 107.8 MHz; with `remaining_q` deciding the copies' loads,
    /// 7.4 ns of routing to their resets, 110.5 MHz).
    step_copy_q: [DFF<Bits<3>>; IN_VALID_COPIES],
    segments_copy_q: [DFF<Bit>; IN_VALID_COPIES],
    remaining_copy_q: [DFF<Bits<3>>; IN_VALID_COPIES],
    /// Copy `c` takes a new job this clock: the input is valid and the copy
    /// has at most its current step left.
    copy_loads: [Signal<Local, Bit>; IN_VALID_COPIES],
    /// The job's vertices (T1's, then T2's) and segment ends (T1 low,
    /// high, T2 low, high), as arrays, so that one loop loads the points.
    job_vertices: [Signal<Local, Bits<W>>; 18],
    job_ends: [Signal<Local, Bits<2>>; 4],
    /// Stage 1: the step's points, numbered as the copies are (`3 d + k`
    /// for coordinate `k` of destination `d`: `u0`, `u1`, `w0`'s lanes,
    /// `w1`'s), for `u = u1 - u0` and lane `l`'s `w = w1 - w0`; and each
    /// lane's axis.
    stage1_q: [OneHotChoice<W>; 24],
    /// The point each of them takes at the next clock edge, one-hot: copy
    /// `c`'s program at the step and kind that copy `c` holds then.
    programs: StepPrograms,
    /// Copy `c`'s step and kind after this clock's edge.
    step_next: [Signal<Local, Bits<3>>; IN_VALID_COPIES],
    segments_next: [Signal<Local, Bit>; IN_VALID_COPIES],
    lane_axis_q: [DFF<Bits<2>>; 3],
    /// Stage 2: the differences.
    u_difference: VectorSubtractor<W, D>,
    w_difference_0: VectorSubtractor<W, D>,
    w_difference_1: VectorSubtractor<W, D>,
    w_difference_2: VectorSubtractor<W, D>,
    lane_axis_2q: [DFF<Bits<2>>; 3],
    /// Stage 3: lane `l`'s `u.x, u.y, w.x, w.y` at `4 l + i`.
    projection_q: [DFF<Bits<D>>; 12],
    lane: [CrossProduct2d<D, C>; 3],
    sign: [SignOf<C>; 3],
    /// Each issued step's number and whether it is its job's last, beside
    /// the lanes.
    issue_line: ValidLine<LANE_LATENCY>,
    last_line: ValidLine<LANE_LATENCY>,
    step_line: DelayLine<Bits<3>, LANE_LATENCY>,
    /// The register file: orient2d value `3 step + lane`.
    negative_q: [DFF<Bit>; 18],
    zero_q: [DFF<Bit>; 18],
    /// The job's last signs are in the file.
    decide_q: DFF<Bit>,
    /// The job's points again, a clock later, for the comparisons alone:
    /// `points_q` also feeds stage 1's selects, and the placer put it
    /// between them and the comparisons (W = 16, router1: 3.6 ns of
    /// routing from `points_q` to a comparison's carry chain, the whole
    /// shared pipeline's critical path at 116.4 MHz). The comparisons'
    /// results are read at the job's last step, and the points are
    /// steady long before that (the assertion after the constants).
    compare_points_q: [DFF<Bits<W>>; 18],
    /// Coordinate `k` of `A_u` against `B_v` at `9 k + 3 u + v`.
    compare: [SplitCompare<W>; 27],
    /// The coplanar comparisons in the projection, `9 c + 3 u + v`.
    projected_less: [Signal<Local, Bit>; 18],
    projected_equal: [Signal<Local, Bit>; 18],
    coplanar_contacts: CoplanarContacts,
    segment_contacts: SegmentContacts,
    /// Orientation of A (negative, zero) and of B in the projection.
    orientation: [Signal<Local, Bit>; 4],
    /// The job's context beside the lanes: on-edge A (9), on-edge B (9),
    /// within (12), registered where they are formed and then delayed (a
    /// line that long is distributed RAM on ECP5, and from the axis
    /// through the projection's choice and the contacts into its write
    /// port, five levels, was the W = 16 shared pipeline's critical path
    /// with seed 1, 138.1 MHz); the orientations; the kind.
    contacts_q: [DFF<Bit>; 30],
    contacts_line: [DelayLine<Bit, { CONTEXT_DELAY - 1 }>; 30],
    orientation_line: [DelayLine<Bit, CONTEXT_DELAY>; 4],
    segments_line: DelayLine<Bit, CONTEXT_DELAY>,
    coplanar_decision: CoplanarDecision,
    segments_decision: SegmentsDecision,
    segments_hit: DelayLine<Bit, { COPLANAR_DECISION_LATENCY - SEGMENTS_DECISION_LATENCY }>,
    segments_out: DelayLine<Bit, COPLANAR_DECISION_LATENCY>,
    done_line: ValidLine<{ COPLANAR_DECISION_LATENCY + OUTPUT_LATENCY }>,
}

impl<const W: usize, const D: usize, const C: usize> crate::unit::Unit
    for SharedRareCases<W, D, C>
{
    const LATENCY: Option<usize> = Some(SHARED_RARE_CASES_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            points_q,
            segments_q,
            axis_q,
            normal_q,
            remaining_q,
            step_copy_q,
            segments_copy_q,
            remaining_copy_q,
            stage1_q,
            programs,
            lane_axis_q,
            u_difference,
            w_difference_0,
            w_difference_1,
            w_difference_2,
            lane_axis_2q,
            projection_q,
            lane,
            sign,
            issue_line,
            last_line,
            step_line,
            negative_q,
            zero_q,
            decide_q,
            compare_points_q,
            compare,
            coplanar_contacts,
            segment_contacts,
            contacts_q,
            contacts_line,
            orientation_line,
            segments_line,
            coplanar_decision,
            segments_decision,
            segments_hit,
            segments_out,
            done_line,
            hit_q
        );
    }
}

impl<const W: usize, const D: usize, const C: usize> Logic for SharedRareCases<W, D, C> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            programs,
            u_difference,
            w_difference_0,
            w_difference_1,
            w_difference_2,
            issue_line,
            last_line,
            step_line,
            coplanar_decision,
            segments_decision,
            segments_hit,
            segments_out,
            done_line,
            segments_line
        );
        dff_setup!(
            self,
            clock,
            segments_q,
            axis_q,
            remaining_q,
            decide_q,
            hit_q
        );
        self.u_difference.advance.next = true;
        self.w_difference_0.advance.next = true;
        self.w_difference_1.advance.next = true;
        self.w_difference_2.advance.next = true;
        self.issue_line.advance.next = true;
        self.last_line.advance.next = true;
        self.step_line.advance.next = true;
        self.coplanar_decision.advance.next = true;
        self.segments_decision.advance.next = true;
        self.segments_hit.advance.next = true;
        self.segments_out.advance.next = true;
        self.done_line.advance.next = true;
        self.segments_line.advance.next = true;
        self.issue_line.reset.next = self.reset.val();
        self.last_line.reset.next = self.reset.val();
        self.done_line.reset.next = self.reset.val();

        // The job: taken when the last step of the one before is issued.
        self.ready.next = self.remaining_q.q.val() == 0 || self.remaining_q.q.val() == 1;
        self.idle_in_three.next = self.remaining_q.q.val() == 0
            || self.remaining_q.q.val() == 1
            || self.remaining_q.q.val() == 2
            || self.remaining_q.q.val() == 3
            || self.remaining_q.q.val() == 4;
        for i in 0..18 {
            self.points_q[i].clock.next = self.clock.val();
            self.points_q[i].d.next = self.points_q[i].q.val();
        }
        for i in 0..12 {
            self.normal_q[i].clock.next = self.clock.val();
            self.normal_q[i].d.next = self.normal_q[i].q.val();
        }
        if self.remaining_q.q.val() != 0 {
            self.remaining_q.d.next = self.remaining_q.q.val() - 1;
        }
        if self.in_valid.val() && (self.remaining_q.q.val() == 0 || self.remaining_q.q.val() == 1) {
            self.segments_q.d.next = self.in_segments.val();
            self.axis_q.d.next = self.axis.val();
            if self.in_segments.val() {
                self.remaining_q.d.next = 4.into();
            } else {
                self.remaining_q.d.next = 6.into();
            }
            for k in 0..3 {
                self.normal_q[k].d.next = self.t1_normal_negative[k].val();
                self.normal_q[3 + k].d.next = self.t1_normal_zero[k].val();
                self.normal_q[6 + k].d.next = self.t2_normal_negative[k].val();
                self.normal_q[9 + k].d.next = self.t2_normal_zero[k].val();
            }
        }
        if self.reset.val() {
            self.remaining_q.d.next = 0.into();
        }
        for c in 0..25 {
            self.copy_loads[c].next = self.in_valid_copies[c].val()
                && (self.remaining_copy_q[c].q.val() == 0 || self.remaining_copy_q[c].q.val() == 1);
        }
        // The job's points: point `p`'s coordinate `k` loads by copy
        // `3 p + k` of the steps left, as the copies do (with `remaining_q`
        // for all 18, W = 16: 6.8 ns of routing to the clock enables,
        // 128.9 MHz). Two segments put their ends at points 0, 1 (a, b)
        // and 3, 4 (c, d).
        for i in 0..9 {
            self.job_vertices[i].next = self.t1_vertices[i].val();
            self.job_vertices[9 + i].next = self.t2_vertices[i].val();
        }
        self.job_ends[0].next = self.t1_segment_low.val();
        self.job_ends[1].next = self.t1_segment_high.val();
        self.job_ends[2].next = self.t2_segment_low.val();
        self.job_ends[3].next = self.t2_segment_high.val();
        for t in 0..2 {
            for k in 0..3 {
                // Triangle `t`'s vertices 0 and 1, or its segment's ends.
                for e in 0..2 {
                    if self.copy_loads[9 * t + 3 * e + k].val() {
                        if !self.in_segments.val() {
                            self.points_q[9 * t + 3 * e + k].d.next =
                                self.job_vertices[9 * t + 3 * e + k].val();
                        } else if self.job_ends[2 * t + e].val() == 1 {
                            self.points_q[9 * t + 3 * e + k].d.next =
                                self.job_vertices[9 * t + 3 + k].val();
                        } else if self.job_ends[2 * t + e].val() == 2 {
                            self.points_q[9 * t + 3 * e + k].d.next =
                                self.job_vertices[9 * t + 6 + k].val();
                        } else {
                            self.points_q[9 * t + 3 * e + k].d.next =
                                self.job_vertices[9 * t + k].val();
                        }
                    }
                }
                if self.copy_loads[9 * t + 6 + k].val() {
                    self.points_q[9 * t + 6 + k].d.next = self.job_vertices[9 * t + 6 + k].val();
                }
            }
        }
        // The copies count as `segments_q` and `remaining_q` do.
        for c in 0..25 {
            self.step_copy_q[c].clock.next = self.clock.val();
            self.segments_copy_q[c].clock.next = self.clock.val();
            self.remaining_copy_q[c].clock.next = self.clock.val();
            self.step_next[c].next = self.step_copy_q[c].q.val();
            self.segments_next[c].next = self.segments_copy_q[c].q.val();
            self.remaining_copy_q[c].d.next = self.remaining_copy_q[c].q.val();
            if self.remaining_copy_q[c].q.val() != 0 {
                self.step_next[c].next = self.step_copy_q[c].q.val() + 1;
                self.remaining_copy_q[c].d.next = self.remaining_copy_q[c].q.val() - 1;
            }
            if self.copy_loads[c].val() {
                self.step_next[c].next = 0.into();
                self.segments_next[c].next = self.in_segments.val();
                if self.in_segments.val() {
                    self.remaining_copy_q[c].d.next = 4.into();
                } else {
                    self.remaining_copy_q[c].d.next = 6.into();
                }
            }
            if self.reset.val() {
                self.remaining_copy_q[c].d.next = 0.into();
            }
            self.step_copy_q[c].d.next = self.step_next[c].val();
            self.segments_copy_q[c].d.next = self.segments_next[c].val();
        }

        // Stage 1: the step's points, by the program of its kind.
        for i in 0..3 {
            self.lane_axis_q[i].clock.next = self.clock.val();
            self.lane_axis_2q[i].clock.next = self.clock.val();
            self.lane_axis_2q[i].d.next = self.lane_axis_q[i].q.val();
            self.lane_axis_q[i].d.next = self.axis_q.q.val();
        }
        // A degenerate pair's lane k computes component k of a cross
        // product: the orient2d that drops axis k.
        if self.segments_q.q.val() {
            self.lane_axis_q[0].d.next = 0.into();
            self.lane_axis_q[1].d.next = 1.into();
            self.lane_axis_q[2].d.next = 2.into();
        }
        // Each destination coordinate's point: a one-hot choice among the
        // six points, `programs.pick`, registered a clock ahead from the next step
        // and kind by the program of its kind, so that stage 1 is an
        // AND-OR of six (two LUT levels; decoding the step there was a
        // chain of six LUTs shared between bits, the whole W = 16 shared
        // pipeline's critical path at 122.8 MHz). Each destination
        // coordinate has its own copy of the step and kind, so that a
        // select reaches W bits. (ECP5, W = 8: one step for all 24
        // coordinates was the critical path, 5.3 ns of it one net's
        // routing, 96.7 MHz; W = 16 with a copy per destination, 48 bits
        // each: 107.8 MHz.)
        for d in 0..8 {
            for k in 0..3 {
                self.stage1_q[3 * d + k].clock.next = self.clock.val();
                self.stage1_q[3 * d + k].pick.next = self.programs.pick[3 * d + k].val();
                self.stage1_q[3 * d + k].point_0.next = self.points_q[k].q.val();
                self.stage1_q[3 * d + k].point_1.next = self.points_q[3 + k].q.val();
                self.stage1_q[3 * d + k].point_2.next = self.points_q[6 + k].q.val();
                self.stage1_q[3 * d + k].point_3.next = self.points_q[9 + k].q.val();
                self.stage1_q[3 * d + k].point_4.next = self.points_q[12 + k].q.val();
                self.stage1_q[3 * d + k].point_5.next = self.points_q[15 + k].q.val();
            }
        }
        // The programs: each destination coordinate's point at each step.
        for c in 0..24 {
            self.programs.load[c].next = self.copy_loads[c].val();
            self.programs.step[c].next = self.step_copy_q[c].q.val();
            self.programs.segments[c].next = self.segments_copy_q[c].q.val();
            self.programs.moving[c].next = self.remaining_copy_q[c].q.val() != 0;
        }
        self.programs.load_segments.next = self.in_segments.val();
        self.issue_line.d.next = self.remaining_q.q.val() != 0;
        self.last_line.d.next = self.remaining_q.q.val() == 1;
        self.step_line.d.next = self.step_copy_q[24].q.val();

        // Stage 2: the differences.
        for k in 0..3 {
            self.u_difference.a[k].next = self.stage1_q[3 + k].q.val();
            self.u_difference.b[k].next = self.stage1_q[k].q.val();
            self.w_difference_0.a[k].next = self.stage1_q[15 + k].q.val();
            self.w_difference_0.b[k].next = self.stage1_q[6 + k].q.val();
            self.w_difference_1.a[k].next = self.stage1_q[18 + k].q.val();
            self.w_difference_1.b[k].next = self.stage1_q[9 + k].q.val();
            self.w_difference_2.a[k].next = self.stage1_q[21 + k].q.val();
            self.w_difference_2.b[k].next = self.stage1_q[12 + k].q.val();
        }

        // Stage 3: each lane's projection; then orient2d and its sign.
        for i in 0..12 {
            self.projection_q[i].clock.next = self.clock.val();
            self.projection_q[i].d.next = self.projection_q[i].q.val();
        }
        if self.lane_axis_2q[0].q.val() == 0 {
            self.projection_q[0].d.next = self.u_difference.difference[1].val();
            self.projection_q[1].d.next = self.u_difference.difference[2].val();
            self.projection_q[2].d.next = self.w_difference_0.difference[1].val();
            self.projection_q[3].d.next = self.w_difference_0.difference[2].val();
        } else if self.lane_axis_2q[0].q.val() == 1 {
            self.projection_q[0].d.next = self.u_difference.difference[2].val();
            self.projection_q[1].d.next = self.u_difference.difference[0].val();
            self.projection_q[2].d.next = self.w_difference_0.difference[2].val();
            self.projection_q[3].d.next = self.w_difference_0.difference[0].val();
        } else {
            self.projection_q[0].d.next = self.u_difference.difference[0].val();
            self.projection_q[1].d.next = self.u_difference.difference[1].val();
            self.projection_q[2].d.next = self.w_difference_0.difference[0].val();
            self.projection_q[3].d.next = self.w_difference_0.difference[1].val();
        }
        if self.lane_axis_2q[1].q.val() == 0 {
            self.projection_q[4].d.next = self.u_difference.difference[1].val();
            self.projection_q[5].d.next = self.u_difference.difference[2].val();
            self.projection_q[6].d.next = self.w_difference_1.difference[1].val();
            self.projection_q[7].d.next = self.w_difference_1.difference[2].val();
        } else if self.lane_axis_2q[1].q.val() == 1 {
            self.projection_q[4].d.next = self.u_difference.difference[2].val();
            self.projection_q[5].d.next = self.u_difference.difference[0].val();
            self.projection_q[6].d.next = self.w_difference_1.difference[2].val();
            self.projection_q[7].d.next = self.w_difference_1.difference[0].val();
        } else {
            self.projection_q[4].d.next = self.u_difference.difference[0].val();
            self.projection_q[5].d.next = self.u_difference.difference[1].val();
            self.projection_q[6].d.next = self.w_difference_1.difference[0].val();
            self.projection_q[7].d.next = self.w_difference_1.difference[1].val();
        }
        if self.lane_axis_2q[2].q.val() == 0 {
            self.projection_q[8].d.next = self.u_difference.difference[1].val();
            self.projection_q[9].d.next = self.u_difference.difference[2].val();
            self.projection_q[10].d.next = self.w_difference_2.difference[1].val();
            self.projection_q[11].d.next = self.w_difference_2.difference[2].val();
        } else if self.lane_axis_2q[2].q.val() == 1 {
            self.projection_q[8].d.next = self.u_difference.difference[2].val();
            self.projection_q[9].d.next = self.u_difference.difference[0].val();
            self.projection_q[10].d.next = self.w_difference_2.difference[2].val();
            self.projection_q[11].d.next = self.w_difference_2.difference[0].val();
        } else {
            self.projection_q[8].d.next = self.u_difference.difference[0].val();
            self.projection_q[9].d.next = self.u_difference.difference[1].val();
            self.projection_q[10].d.next = self.w_difference_2.difference[0].val();
            self.projection_q[11].d.next = self.w_difference_2.difference[1].val();
        }
        for l in 0..3 {
            self.lane[l].clock.next = self.clock.val();
            self.lane[l].advance.next = true;
            self.lane[l].u_x.next = self.projection_q[4 * l].q.val();
            self.lane[l].u_y.next = self.projection_q[4 * l + 1].q.val();
            self.lane[l].w_x.next = self.projection_q[4 * l + 2].q.val();
            self.lane[l].w_y.next = self.projection_q[4 * l + 3].q.val();
            self.sign[l].clock.next = self.clock.val();
            self.sign[l].advance.next = true;
            self.sign[l].value.next = self.lane[l].product.val();
        }

        // The register file, then the decision a clock after the last step.
        for i in 0..18 {
            self.negative_q[i].clock.next = self.clock.val();
            self.negative_q[i].d.next = self.negative_q[i].q.val();
            self.zero_q[i].clock.next = self.clock.val();
            self.zero_q[i].d.next = self.zero_q[i].q.val();
        }
        if self.issue_line.q.val() {
            if self.step_line.q.val() == 0 {
                for l in 0..3 {
                    self.negative_q[l].d.next = self.sign[l].negative.val();
                    self.zero_q[l].d.next = self.sign[l].zero.val();
                }
            } else if self.step_line.q.val() == 1 {
                for l in 0..3 {
                    self.negative_q[3 + l].d.next = self.sign[l].negative.val();
                    self.zero_q[3 + l].d.next = self.sign[l].zero.val();
                }
            } else if self.step_line.q.val() == 2 {
                for l in 0..3 {
                    self.negative_q[6 + l].d.next = self.sign[l].negative.val();
                    self.zero_q[6 + l].d.next = self.sign[l].zero.val();
                }
            } else if self.step_line.q.val() == 3 {
                for l in 0..3 {
                    self.negative_q[9 + l].d.next = self.sign[l].negative.val();
                    self.zero_q[9 + l].d.next = self.sign[l].zero.val();
                }
            } else if self.step_line.q.val() == 4 {
                for l in 0..3 {
                    self.negative_q[12 + l].d.next = self.sign[l].negative.val();
                    self.zero_q[12 + l].d.next = self.sign[l].zero.val();
                }
            } else if self.step_line.q.val() == 5 {
                for l in 0..3 {
                    self.negative_q[15 + l].d.next = self.sign[l].negative.val();
                    self.zero_q[15 + l].d.next = self.sign[l].zero.val();
                }
            }
        }
        self.decide_q.d.next = self.last_line.q.val() && !self.reset.val();

        // The job's context: comparisons (no multipliers) and orientations.
        for i in 0..18 {
            self.compare_points_q[i].clock.next = self.clock.val();
            self.compare_points_q[i].d.next = self.points_q[i].q.val();
        }
        for k in 0..3 {
            for u in 0..3 {
                for v in 0..3 {
                    self.compare[9 * k + 3 * u + v].clock.next = self.clock.val();
                    self.compare[9 * k + 3 * u + v].a.next =
                        self.compare_points_q[3 * u + k].q.val();
                    self.compare[9 * k + 3 * u + v].b.next =
                        self.compare_points_q[9 + 3 * v + k].q.val();
                }
            }
        }
        for c in 0..2 {
            for u in 0..3 {
                for v in 0..3 {
                    if self.axis_q.q.val() == 0 {
                        self.projected_less[9 * c + 3 * u + v].next =
                            self.compare[9 * (c + 1) + 3 * u + v].less.val();
                        self.projected_equal[9 * c + 3 * u + v].next =
                            self.compare[9 * (c + 1) + 3 * u + v].equal.val();
                    } else if self.axis_q.q.val() == 1 {
                        self.projected_less[9 * c + 3 * u + v].next =
                            self.compare[9 * ((c + 2) % 3) + 3 * u + v].less.val();
                        self.projected_equal[9 * c + 3 * u + v].next =
                            self.compare[9 * ((c + 2) % 3) + 3 * u + v].equal.val();
                    } else {
                        self.projected_less[9 * c + 3 * u + v].next =
                            self.compare[9 * c + 3 * u + v].less.val();
                        self.projected_equal[9 * c + 3 * u + v].next =
                            self.compare[9 * c + 3 * u + v].equal.val();
                    }
                }
            }
        }
        for i in 0..18 {
            self.coplanar_contacts.less[i].next = self.projected_less[i].val();
            self.coplanar_contacts.equal[i].next = self.projected_equal[i].val();
        }
        // The pairs (a, c), (a, d), (b, c), (b, d): points (0, 3), (0, 4),
        // (1, 3), (1, 4).
        for k in 0..3 {
            for p in 0..4 {
                self.segment_contacts.less[3 * p + k].next =
                    self.compare[9 * k + 3 * (p / 2) + p % 2].less.val();
                self.segment_contacts.equal[3 * p + k].next =
                    self.compare[9 * k + 3 * (p / 2) + p % 2].equal.val();
            }
        }
        if self.axis_q.q.val() == 0 {
            self.orientation[0].next = self.normal_q[0].q.val();
            self.orientation[1].next = self.normal_q[3].q.val();
            self.orientation[2].next = self.normal_q[6].q.val();
            self.orientation[3].next = self.normal_q[9].q.val();
        } else if self.axis_q.q.val() == 1 {
            self.orientation[0].next = self.normal_q[1].q.val();
            self.orientation[1].next = self.normal_q[4].q.val();
            self.orientation[2].next = self.normal_q[7].q.val();
            self.orientation[3].next = self.normal_q[10].q.val();
        } else {
            self.orientation[0].next = self.normal_q[2].q.val();
            self.orientation[1].next = self.normal_q[5].q.val();
            self.orientation[2].next = self.normal_q[8].q.val();
            self.orientation[3].next = self.normal_q[11].q.val();
        }
        for i in 0..30 {
            self.contacts_q[i].clock.next = self.clock.val();
            self.contacts_line[i].clock.next = self.clock.val();
            self.contacts_line[i].advance.next = true;
            self.contacts_line[i].d.next = self.contacts_q[i].q.val();
        }
        for i in 0..4 {
            self.orientation_line[i].clock.next = self.clock.val();
            self.orientation_line[i].advance.next = true;
        }
        for i in 0..9 {
            self.contacts_q[i].d.next = self.coplanar_contacts.on_edge_a[i].val();
            self.contacts_q[9 + i].d.next = self.coplanar_contacts.on_edge_b[i].val();
        }
        for i in 0..12 {
            self.contacts_q[18 + i].d.next = self.segment_contacts.within[i].val();
        }
        for i in 0..4 {
            self.orientation_line[i].d.next = self.orientation[i].val();
        }
        self.segments_line.d.next = self.segments_copy_q[24].q.val();

        // The decisions on the file, and the job's.
        for i in 0..18 {
            self.coplanar_decision.negative[i].next = self.negative_q[i].q.val();
            self.coplanar_decision.zero[i].next = self.zero_q[i].q.val();
        }
        for i in 0..9 {
            self.coplanar_decision.on_edge_a[i].next = self.contacts_line[i].q.val();
            self.coplanar_decision.on_edge_b[i].next = self.contacts_line[9 + i].q.val();
        }
        for i in 0..4 {
            self.coplanar_decision.orientation[i].next = self.orientation_line[i].q.val();
        }
        for i in 0..12 {
            self.segments_decision.negative[i].next = self.negative_q[i].q.val();
            self.segments_decision.zero[i].next = self.zero_q[i].q.val();
            self.segments_decision.within[i].next = self.contacts_line[18 + i].q.val();
        }
        self.segments_hit.d.next = self.segments_decision.hit.val();
        self.segments_out.d.next = self.segments_line.q.val();
        self.done_line.d.next = self.decide_q.q.val();
        self.done.next = self.done_line.q.val();
        if self.segments_out.q.val() {
            self.verdict.next = self.segments_hit.q.val();
        } else {
            self.verdict.next = self.coplanar_decision.hit.val();
        }
        self.hit_q.d.next = self.verdict.val();
        self.hit.next = self.hit_q.q.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::pipeline::shared_rare_cases::{
        SharedRareCases, COPLANAR_STEPS, SEGMENTS_STEPS, SHARED_RARE_CASES_LATENCY,
    };
    use crate::pipeline::unit_vectors::{
        coplanar_pairs, degenerate_pairs, lexicographic_ends, normal, segments_meet, set_vertices,
    };
    use crate::sim_drive::{clock_cycle, reset_one_clock};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rust_hdl::prelude::*;
    use tritri_geom::devillers_guigue::coplanar_triangles;
    use tritri_geom::fixed_point::{dominant_axis, FixedPoint, FixedTriangle};

    /// The shared rare-case unit gives the parallel tests' verdicts: coplanar
    /// pairs and degenerate pairs interleaved, offered with gaps and back to
    /// back, each verdict in order and exactly its kind's latency after the
    /// job was taken; jobs offered back to back are taken a job's steps apart.
    #[test]
    fn shared_rare_cases_equal_the_parallel_tests() {
        let coplanar = coplanar_pairs(8)
            .into_iter()
            .filter(|(t1, _)| normal(t1) != [0, 0, 0]);
        let segments = degenerate_pairs();
        // (segments?, t1, t2), alternating in runs.
        let mut jobs: Vec<(bool, FixedTriangle, FixedTriangle)> = Vec::new();
        for (i, (c, d)) in coplanar.zip(segments).enumerate() {
            let first_segments = i % 3 == 0;
            jobs.push((
                first_segments,
                if first_segments { d.0 } else { c.0 },
                if first_segments { d.1 } else { c.1 },
            ));
            jobs.push((
                !first_segments,
                if first_segments { c.0 } else { d.0 },
                if first_segments { c.1 } else { d.1 },
            ));
        }
        let expected: Vec<bool> = jobs
            .iter()
            .map(|&(is_segments, t1, t2)| {
                if is_segments {
                    segments_meet(&(t1, t2))
                } else {
                    coplanar_triangles::<FixedPoint>(t1, t2)
                }
            })
            .collect();
        let mut uut = SharedRareCases::<24, 25, 49>::default();
        uut.connect_all();
        reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let (mut next, mut cycle) = (0usize, 0u64);
        let mut taken_at: Vec<u64> = Vec::new();
        let mut offered_since: Option<u64> = None;
        let mut back_to_back = 0;
        let mut verdicts: Vec<(bool, u64)> = Vec::new();
        while verdicts.len() < jobs.len() {
            assert!(
                cycle < 20 * jobs.len() as u64 + 100,
                "no verdicts after {cycle} clocks"
            );
            // Offer the next job, now and then after a gap.
            let offer = next < jobs.len() && (offered_since.is_some() || rng.gen_bool(0.7));
            uut.in_valid.next = offer;
            for copy in uut.in_valid_copies.iter_mut() {
                copy.next = offer;
            }
            if offer {
                let (is_segments, t1, t2) = &jobs[next];
                uut.in_segments.next = *is_segments;
                set_vertices(&mut uut.t1_vertices, t1);
                set_vertices(&mut uut.t2_vertices, t2);
                let (n1, n2) = (normal(t1), normal(t2));
                uut.axis.next = (dominant_axis(n1.map(|c| c.unsigned_abs())) as u64).into();
                for k in 0..3 {
                    uut.t1_normal_negative[k].next = n1[k] < 0;
                    uut.t1_normal_zero[k].next = n1[k] == 0;
                    uut.t2_normal_negative[k].next = n2[k] < 0;
                    uut.t2_normal_zero[k].next = n2[k] == 0;
                }
                let ((a, b), (c, d)) = (lexicographic_ends(t1), lexicographic_ends(t2));
                uut.t1_segment_low.next = (a as u64).into();
                uut.t1_segment_high.next = (b as u64).into();
                uut.t2_segment_low.next = (c as u64).into();
                uut.t2_segment_high.next = (d as u64).into();
                offered_since.get_or_insert(cycle);
            }
            uut.update_all();
            let taken = offer && uut.ready.val();
            clock_cycle(&mut uut, |u| &mut u.clock);
            cycle += 1;
            if taken {
                // Offered since the previous job was taken: taken exactly
                // that job's steps after it.
                if let (Some(&previous), Some(since)) = (taken_at.last(), offered_since) {
                    if since < previous + 1 {
                        let steps = if jobs[next - 1].0 {
                            SEGMENTS_STEPS
                        } else {
                            COPLANAR_STEPS
                        };
                        assert_eq!(
                            cycle - previous,
                            steps as u64,
                            "job {next} taken back to back"
                        );
                        back_to_back += 1;
                    }
                }
                taken_at.push(cycle);
                offered_since = None;
                next += 1;
            }
            if uut.done.val() {
                verdicts.push((uut.hit.val(), cycle));
            }
        }
        assert!(
            back_to_back > jobs.len() / 4,
            "{back_to_back} jobs back to back"
        );
        for (j, ((hit, at), expected)) in verdicts.iter().zip(&expected).enumerate() {
            assert_eq!(*hit, *expected, "job {j}: {:?}", jobs[j]);
            let latency = if jobs[j].0 {
                SHARED_RARE_CASES_LATENCY - (COPLANAR_STEPS - SEGMENTS_STEPS)
            } else {
                SHARED_RARE_CASES_LATENCY
            };
            assert_eq!(at - taken_at[j], latency as u64, "job {j}'s latency");
        }
    }
}
