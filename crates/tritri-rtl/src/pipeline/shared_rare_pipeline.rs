//! The other top: the triangle-pair pipeline with the rare cases on one
//! shared, slower unit (issue 14, part 3). The general path
//! ([`super::general_path`]) is the same as in
//! [`super::triangle_pipeline::TrianglePipeline`]; the coplanar test and the
//! degenerate pair's segment test are both done by
//! [`SharedRareCases`] (6 multipliers instead of 60), which takes a
//! coplanar pair every `COPLANAR_STEPS` clocks and two segments every
//! `SEGMENTS_STEPS`.
//!
//! A pair is rare when, beside its plane-side signs ([`SIDES_STAGE`]), its
//! case needs one of those tests (the rule of the decision, and of
//! `system::rare_case_model::rare_kind`): both triangles degenerate, or
//! the degenerate triangle's vertices (else T2's) all on the other's plane.
//! That is registered a stage later, twice more, and with the pair's job
//! three stages later ([`JOB_STAGE`]), and the job goes to the unit as the pair
//! leaves that stage. While the unit cannot take it, `hold` is high and
//! the whole pipeline holds, as if `advance` were low: the triangle on the
//! input bus is not taken and must stay there. The unit runs on, free of
//! `advance`, and its verdicts wait in a [`VerdictQueue`] for their pairs
//! to reach the decision, in order.
//!
//! `hold` goes into the enable of every register, so it is a register, in
//! copies: [`HoldForecast`] requests it three clocks ahead from the rare
//! bits of the four stages and the unit's steps left, its [`HoldNext`](super::hold_next::HoldNext)
//! decides it two clocks ahead, once for each value `advance` may take
//! next clock, and fourteen [`HoldRegister`]s pick from those two
//! registers by `advance`, each the enable of one group of units (a
//! fifteenth drives the `hold` port, a sixteenth the verdict queue's
//! `pop`, and `unit_hold` the unit's offers). The unit's input is
//! valid by registers of its own, a clock ahead too (`offer_next`), one
//! beside each group of its loads.
//! Pipelines that move in step (a system's) hold together: each sends its
//! requests (`hold_request`, registers) and takes the OR of all of them
//! (`hold_others`) into its [`HoldNext`](super::hold_next::HoldNext) a clock later, so that no
//! pipeline's enables wait for another's `hold`.
//! (Computed in the clock it acts, from the sides stage's zeros through
//! the rule to one enable net, it ran at 79 MHz post-route on ECP5 at
//! W = 8, 11.4 of its 12.7 ns routing; decided a clock ahead, one register
//! a group, 105.3 MHz at W = 16, a copy reaching 4,474 clock enables;
//! requested two clocks ahead and exchanged in the same clock, the
//! exchange crossed between the pipelines of a P = 2 system behind the
//! rule, 124.4 MHz at W = 8.)
//!
//! So the latency in advancing clocks is the parallel pipeline's
//! [`latency`]; a run takes `N1 + N1 N2 + L` clocks plus the clocks with
//! `hold` high, which `system::rare_case_model` counts.

use super::general_path::{GeneralPath, ADVANCE_COPIES, RARE_VERDICTS_STAGE, SIDES_STAGE};
use super::hold_forecast::HoldForecast;
use super::hold_next::HOLD_REQUESTS;
use super::hold_register::HoldRegister;
use super::shared_rare_cases::{SharedRareCases, IN_VALID_COPIES, SHARED_RARE_CASES_LATENCY};
use super::verdict_queue::{VerdictQueue, VERDICT_QUEUE_DEPTH};
use crate::arith::delay_line::DelayLine;
use crate::arith::register_copy::RegisterCopy;
use crate::arith::valid_line::ValidLine;
use rust_hdl::prelude::*;

pub use super::general_path::{latency, TRIANGLE_PIPELINE_LATENCY};

/// The stage whose pair offers its job to the unit: the rare bit,
/// registered three times after the plane side's zeros, so that the
/// forecast sees the rare bits of the next three pairs ([`HoldForecast`]).
pub const JOB_STAGE: usize = SIDES_STAGE + 3;

/// The unit's verdict is in the queue's head register by the time its
/// pair reaches [`RARE_VERDICTS_STAGE`]: the job is taken at the edge that
/// moves the pair to `JOB_STAGE + 1`, `done` is high
/// `SHARED_RARE_CASES_LATENCY` edges after that one, and the verdict is
/// written at the end of that clock, when the pair, never faster than a
/// stage a clock, is at most at `JOB_STAGE + 1 +
/// SHARED_RARE_CASES_LATENCY`, a stage before the decision reads it. A
/// stage fewer, and a pair that found the unit idle and every stage moving
/// missed its verdict by a clock: the rust-hdl test caught 3 of 5,136,
/// until the verdicts moved into the decision's second stage (now its
/// third, as the job stage moved a stage later for the three clocks'
/// forecast).
const _: () = assert!(RARE_VERDICTS_STAGE - JOB_STAGE > SHARED_RARE_CASES_LATENCY + 1);
/// Every verdict waiting or in the unit belongs to a pair between the two
/// stages, at most one a stage.
const _: () = assert!(RARE_VERDICTS_STAGE - JOB_STAGE < VERDICT_QUEUE_DEPTH);
/// The update's literals: copies 1 to 12 are the general path's, 13 the job's normals and axis.
const _: () = assert!(ADVANCE_COPIES == 12);
/// The update's literals 25 and 26: one offer for each of the unit's
/// copies, and the last for its `in_valid`.
const _: () = assert!(IN_VALID_COPIES == 25);

crate::pipeline_ports! {
    // The ports: crate::pipeline::ports, and `hold`.
    #[derive(LogicBlock, Default)]
    pub struct SharedRarePipeline<const W: usize, const D: usize, const C: usize, const O: usize> {
        /// A rare pair waits for the unit: the pipeline holds this clock,
        /// and the input bus is not taken: this pipeline's rare pair or
        /// (`hold_others`) another's waits.
        pub hold: Signal<Out, Bit>,
        /// This pipeline's rare pair will wait for the unit three clocks
        /// from now if `advance` is `a` next clock and the pipeline moves
        /// (`m`) two clocks from now, at `2 a + m` (registers): for the
        /// pipelines that move in step with this one.
        pub hold_request: Signal<Out, Bits<HOLD_REQUESTS>>,
        /// The OR of the `hold_request`s of the pipelines moving in step
        /// with this one, this one's may be included: hold with them. 0 for
        /// a pipeline on its own.
        pub hold_others: Signal<In, Bits<HOLD_REQUESTS>>,
        path: GeneralPath<W, D, C, O>,
        rare_cases: SharedRareCases<W, D, C>,
        verdicts: VerdictQueue,
        /// The job, from the pair to the job stage: vertices (T1's, then
        /// T2's), axis, normals' signs (T1's negative, zero, then T2's) and
        /// segment ends (T1 low, high, T2 low, high).
        vertices_to_job: [DelayLine<Bits<W>, JOB_STAGE>; 18],
        axis_to_job: DelayLine<Bits<2>, JOB_STAGE>,
        normals_to_job: [DelayLine<Bit, JOB_STAGE>; 12],
        segment_ends_to_job: [DelayLine<Bits<2>, JOB_STAGE>; 4],
        /// The degenerate flags, to the sides stage, for the rule.
        degenerate_to_sides: [DelayLine<Bit, SIDES_STAGE>; 2],
        /// The rule's outcome a stage after the sides stage, two, and at
        /// the job stage.
        rare_queued: ValidLine<1>,
        rare_queued_2: ValidLine<1>,
        rare_to_job: ValidLine<1>,
        segments_to_job: DelayLine<Bit, { JOB_STAGE - SIDES_STAGE }>,
        /// A rare pair, from the job stage to the decision's last stage.
        rare_to_decision: ValidLine<{ RARE_VERDICTS_STAGE - JOB_STAGE }>,
        segments: Signal<Local, Bit>,
        coplanar: Signal<Local, Bit>,
        rare: Signal<Local, Bit>,
        /// The job stage's pair is rare.
        job_rare: Signal<Local, Bit>,
        /// The unit's `in_valid` without `advance`, from the forecast a
        /// clock ahead: one register for each of the unit's copies of its
        /// steps left (`in_valid_copies`), and the last for `in_valid`, so
        /// that each sits by its loads (W = 16, router1: from a copy of
        /// `hold` and the job stage's rare bit into all of them, 93.0 MHz,
        /// 9.1 of its 10.8 ns routing).
        offers: [RegisterCopy<Bit>; IN_VALID_COPIES + 1],
        /// The offers' next value: next clock, the job stage's pair is rare
        /// and the pipeline does not hold. Formed here, from the forecast's
        /// registers and `advance`: through the forecast and back, `advance`
        /// reached the offers' inputs a delta cycle after their clock edge
        /// in rust-hdl's simulation (`sim_drive::clock_cycle`), and the
        /// back-pressure test failed. It reads `hold` from a copy of its
        /// own, `unit_hold` (the queue has another, `holds[15]`): from copy 0, synthesis
        /// shared the term `advance` and not `hold` with the general path's
        /// enable, a net with thousands of loads, and the offers came a
        /// level of logic and that net's delay later (7.10 ns, ECP5,
        /// W = 16, router1).
        offer_next: Signal<Local, Bit>,
        unit_hold: HoldRegister,
        /// The unit's `ready`: the forecast predicts it instead (Verilator's
        /// lint: unused on purpose).
        unused_ready: Signal<Local, Bit>,
        forecast: HoldForecast,
        /// `hold`, one copy per group of registers: the general path's
        /// `advance` (0, with this top's rare bits), its `advance_copies`
        /// (1 to 12; the job's segment ends and degenerate flags ride on 4,
        /// the operands', T1's and T2's vertices on 10 and 11, as the
        /// general path delays the same fields on them and synthesis shares
        /// the lines), the job's normals and axis (13), and the `hold`
        /// port (14): the system's result FIFO counts and writes on it, and
        /// through copy 0, which also enables the general path, its counts
        /// were 25 of the 31 register inputs short of 150 MHz (ECP5, W =
        /// 16, P = 1, seed 3: 128.6 MHz), and the verdict queue's `pop`
        /// (15): read from `unit_hold`, 3.9 ns of routing from that register
        /// by the offers to the queue's slots and count (ECP5, W = 16 alone,
        /// router1, seed 1: 133.7 MHz, 74 inputs short). The base polygon
        /// works out its own from the forecast, beside each group
        /// ([`super::load_enable`]).
        holds: [HoldRegister; 16],
        /// `advance`, unless a rare pair waits (copy 0's).
        moving: Signal<Local, Bit>,
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> crate::unit::Unit
    for SharedRarePipeline<W, D, C, O>
{
    const LATENCY: Option<usize> = Some(TRIANGLE_PIPELINE_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            path,
            rare_cases,
            verdicts,
            forecast,
            holds,
            vertices_to_job,
            axis_to_job,
            normals_to_job,
            segment_ends_to_job,
            degenerate_to_sides,
            rare_queued,
            rare_queued_2,
            rare_to_job,
            offers,
            unit_hold,
            segments_to_job,
            rare_to_decision
        );
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize>
    SharedRarePipeline<W, D, C, O>
{
    /// A pipeline for W-bit coordinates. Panics unless `D`, `C`, `O` are the
    /// widths `tritri_geom::widths` derives from `W`.
    pub fn new() -> Self {
        GeneralPath::<W, D, C, O>::new();
        Self::default()
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> Logic
    for SharedRarePipeline<W, D, C, O>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            path,
            rare_cases,
            verdicts,
            axis_to_job,
            rare_queued,
            rare_queued_2,
            rare_to_job,
            segments_to_job,
            rare_to_decision
        );
        // Which pairs are rare: two segments; else the degenerate
        // triangle's vertices, or T2's, all on the other plane (for two
        // proper triangles, T2 in T1's plane is T1 in T2's). First, since
        // rust-hdl wants a local written before it is read.
        self.segments.next =
            self.degenerate_to_sides[0].q.val() && self.degenerate_to_sides[1].q.val();
        if self.degenerate_to_sides[0].q.val() {
            self.coplanar.next = self.path.sides_t1_all_zero.val();
        } else {
            self.coplanar.next = self.path.sides_t2_all_zero.val();
        }
        self.rare.next =
            self.path.sides_valid.val() && (self.segments.val() || self.coplanar.val());
        self.job_rare.next = self.rare_to_job.q.val();
        self.forecast.clock.next = self.clock.val();
        self.forecast.reset.next = self.reset.val();
        self.forecast.advance.next = self.advance.val();
        self.forecast.sides_rare.next = self.rare.val();
        self.forecast.rare_2.next = self.rare_queued.q.val();
        self.forecast.rare_1.next = self.rare_queued_2.q.val();
        self.forecast.job_rare.next = self.job_rare.val();
        self.forecast.unit_idle_in_three.next = self.rare_cases.idle_in_three.val();
        self.forecast.others.next = self.hold_others.val();
        self.hold_request.next = self.forecast.requests.val();
        self.unit_hold.clock.next = self.clock.val();
        self.unit_hold.reset.next = self.reset.val();
        self.unit_hold.advance.next = self.advance.val();
        self.unit_hold.if_advance.next = self.forecast.if_advance.val();
        self.unit_hold.if_still.next = self.forecast.if_still.val();
        for i in 0..16 {
            self.holds[i].clock.next = self.clock.val();
            self.holds[i].reset.next = self.reset.val();
            self.holds[i].advance.next = self.advance.val();
            self.holds[i].if_advance.next = self.forecast.if_advance.val();
            self.holds[i].if_still.next = self.forecast.if_still.val();
        }
        // Each group's enable: `advance` and its copy of `hold`, formed here
        // (in rust-hdl's simulation an enable formed inside a unit below
        // would reach the registers a delta cycle after the clock edge).
        self.hold.next = self.holds[14].hold.val();
        self.unused_ready.next = self.rare_cases.ready.val();
        self.moving.next = self.advance.val() && !self.holds[0].hold.val();
        self.path.advance.next = self.moving.val();
        for i in 0..12 {
            self.path.advance_copies[i].next = self.advance.val() && !self.holds[1 + i].hold.val();
        }
        self.path.base_advance.next = self.advance.val();
        self.path.base_hold_if_advance.next = self.forecast.if_advance.val();
        self.path.base_hold_if_still.next = self.forecast.if_still.val();

        // The job's vertices, segment ends and the degenerate flags share
        // the copies of the general path's lines to the operands: it
        // delays the same fields on them, and synthesis shares lines on one
        // enable.
        for i in 0..9 {
            self.vertices_to_job[i].clock.next = self.clock.val();
            self.vertices_to_job[i].advance.next = self.advance.val() && !self.holds[10].hold.val();
            self.vertices_to_job[9 + i].clock.next = self.clock.val();
            self.vertices_to_job[9 + i].advance.next =
                self.advance.val() && !self.holds[11].hold.val();
        }
        for i in 0..4 {
            self.segment_ends_to_job[i].clock.next = self.clock.val();
            self.segment_ends_to_job[i].advance.next =
                self.advance.val() && !self.holds[4].hold.val();
        }
        for i in 0..2 {
            self.degenerate_to_sides[i].clock.next = self.clock.val();
            self.degenerate_to_sides[i].advance.next =
                self.advance.val() && !self.holds[4].hold.val();
        }
        for i in 0..12 {
            self.normals_to_job[i].clock.next = self.clock.val();
            self.normals_to_job[i].advance.next = self.advance.val() && !self.holds[13].hold.val();
        }
        self.axis_to_job.advance.next = self.advance.val() && !self.holds[13].hold.val();
        self.rare_queued.advance.next = self.moving.val();
        self.rare_queued.reset.next = self.reset.val();
        self.rare_queued_2.advance.next = self.moving.val();
        self.rare_queued_2.reset.next = self.reset.val();
        self.rare_to_job.advance.next = self.moving.val();
        self.rare_to_job.reset.next = self.reset.val();
        // As the forecast works out the job stage's pair and `hold` of the
        // next clock.
        if self.advance.val() && !self.unit_hold.hold.val() {
            self.offer_next.next = self.rare_queued_2.q.val();
        } else {
            self.offer_next.next = self.job_rare.val();
        }
        if (self.advance.val() && self.forecast.if_advance.val())
            || (!self.advance.val() && self.forecast.if_still.val())
            || self.reset.val()
        {
            self.offer_next.next = false;
        }
        for c in 0..26 {
            self.offers[c].clock.next = self.clock.val();
            self.offers[c].d.next = self.offer_next.val();
        }
        self.segments_to_job.advance.next = self.moving.val();
        self.rare_to_decision.advance.next = self.moving.val();
        self.rare_to_decision.reset.next = self.reset.val();
        self.path.reset.next = self.reset.val();
        self.rare_cases.reset.next = self.reset.val();
        self.verdicts.reset.next = self.reset.val();

        // The ports, through to the path.
        self.path.in_valid.next = self.in_valid.val();
        self.path.in_bset.next = self.in_bset.val();
        self.path.in_id.next = self.in_id.val();
        self.path.in_x0.next = self.in_x0.val();
        self.path.in_y0.next = self.in_y0.val();
        self.path.in_z0.next = self.in_z0.val();
        self.path.in_x1.next = self.in_x1.val();
        self.path.in_y1.next = self.in_y1.val();
        self.path.in_z1.next = self.in_z1.val();
        self.path.in_x2.next = self.in_x2.val();
        self.path.in_y2.next = self.in_y2.val();
        self.path.in_z2.next = self.in_z2.val();
        self.out_valid.next = self.path.out_valid.val();
        self.out_hit.next = self.path.out_hit.val();
        self.out_certain.next = self.path.out_certain.val();
        self.out_base_id.next = self.path.out_base_id.val();
        self.out_stream_id.next = self.path.out_stream_id.val();

        // The job, to the job stage; the rule's outcome beside it.
        for i in 0..9 {
            self.vertices_to_job[i].d.next = self.path.pair_t1_vertices[i].val();
            self.vertices_to_job[9 + i].d.next = self.path.pair_t2_vertices[i].val();
        }
        self.axis_to_job.d.next = self.path.pair_axis.val();
        for k in 0..3 {
            self.normals_to_job[k].d.next = self.path.pair_t1_normal_negative[k].val();
            self.normals_to_job[3 + k].d.next = self.path.pair_t1_normal_zero[k].val();
            self.normals_to_job[6 + k].d.next = self.path.pair_t2_normal_negative[k].val();
            self.normals_to_job[9 + k].d.next = self.path.pair_t2_normal_zero[k].val();
        }
        self.degenerate_to_sides[0].d.next = self.path.pair_t1_degenerate.val();
        self.degenerate_to_sides[1].d.next = self.path.pair_t2_degenerate.val();
        self.segment_ends_to_job[0].d.next = self.path.pair_t1_segment_low.val();
        self.segment_ends_to_job[1].d.next = self.path.pair_t1_segment_high.val();
        self.segment_ends_to_job[2].d.next = self.path.pair_t2_segment_low.val();
        self.segment_ends_to_job[3].d.next = self.path.pair_t2_segment_high.val();
        self.rare_queued.d.next = self.rare.val();
        self.rare_queued_2.d.next = self.rare_queued.q.val();
        self.rare_to_job.d.next = self.rare_queued_2.q.val();
        self.segments_to_job.d.next = self.segments.val();

        // The job, taken as the pair leaves the job stage.
        self.rare_cases.in_valid.next = self.offers[25].q.val() && self.advance.val();
        for c in 0..25 {
            self.rare_cases.in_valid_copies[c].next = self.offers[c].q.val() && self.advance.val();
        }
        self.rare_cases.in_segments.next = self.segments_to_job.q.val();
        for i in 0..9 {
            self.rare_cases.t1_vertices[i].next = self.vertices_to_job[i].q.val();
            self.rare_cases.t2_vertices[i].next = self.vertices_to_job[9 + i].q.val();
        }
        self.rare_cases.axis.next = self.axis_to_job.q.val();
        for k in 0..3 {
            self.rare_cases.t1_normal_negative[k].next = self.normals_to_job[k].q.val();
            self.rare_cases.t1_normal_zero[k].next = self.normals_to_job[3 + k].q.val();
            self.rare_cases.t2_normal_negative[k].next = self.normals_to_job[6 + k].q.val();
            self.rare_cases.t2_normal_zero[k].next = self.normals_to_job[9 + k].q.val();
        }
        self.rare_cases.t1_segment_low.next = self.segment_ends_to_job[0].q.val();
        self.rare_cases.t1_segment_high.next = self.segment_ends_to_job[1].q.val();
        self.rare_cases.t2_segment_low.next = self.segment_ends_to_job[2].q.val();
        self.rare_cases.t2_segment_high.next = self.segment_ends_to_job[3].q.val();

        // Its verdict, queued until the pair reaches the decision.
        self.rare_to_decision.d.next = self.job_rare.val();
        self.verdicts.push.next = self.rare_cases.done.val();
        self.verdicts.push_hit.next = self.rare_cases.hit.val();
        self.verdicts.pop.next =
            self.rare_to_decision.q.val() && self.advance.val() && !self.holds[15].hold.val();
        self.path.coplanar_hit.next = self.verdicts.head.val();
        self.path.degenerate_pair_hit.next = self.verdicts.head.val();
    }
}
