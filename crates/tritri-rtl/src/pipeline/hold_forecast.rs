//! The shared pipeline's `hold`, decided two clocks ahead: one register
//! for each value `advance` may take next clock, which the copies of
//! `hold` ([`super::hold_register::HoldRegister`]) pick from by `advance`.
//!
//! `hold` is high when the pair at the job stage is rare and the unit is
//! not ready for it (this pipeline's request), or when another pipeline
//! moving in step with this one requests it. In a clock `t`, knowing
//! `advance` now, the forecast works out the pipeline's state at `t + 1`:
//! * `hold` then: its copy's next value;
//! * the pair at the job stage and the one before it: the ones there now
//!   if the pipeline holds, else the ones a stage earlier (the rule at the
//!   sides stage, `sides_rare`, and `queued_rare`);
//! * the unit's readiness: it takes the job stage's pair now if that is
//!   rare and the pipeline moves; else it has at most two steps left at
//!   `t + 1` if it has at most three now (`unit_idle_in_two`).
//!
//! From that state it writes the request at `t + 1` as the one-clock rule
//! would, once for `advance` high at `t + 1` and once for low: the
//! pipeline moves then only if it does not hold, and then the pair moving
//! into the job stage waits if it is rare and the unit will not be ready a
//! clock later; otherwise the job stage's pair waits if it is rare and the
//! unit will not be ready.
//!
//! Pipelines that move in step (a system's) send both requests
//! (`request_if_advance`, `request_if_still`) and take the OR of all of
//! them (`others_*`, this one's included) into both registers in the same
//! clock, so that all their copies stay equal.

use super::hold_register::HoldRegister;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// A job taken now leaves the unit busy next clock, and a unit with three
/// steps left is ready two clocks later: the rule above, written against
/// the unit's step counts.
const _: () = assert!(
    super::shared_rare_cases::SEGMENTS_STEPS >= 3 && super::shared_rare_cases::COPLANAR_STEPS >= 3
);

#[derive(LogicBlock, Default)]
pub struct HoldForecast {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: no hold.
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    /// The pair at the sides stage is rare (the rule, from its zeros).
    pub sides_rare: Signal<In, Bit>,
    /// The pair a stage later, and the one at the job stage, are rare.
    pub queued_rare: Signal<In, Bit>,
    pub job_rare: Signal<In, Bit>,
    /// The unit has at most three steps left: ready two clocks from now
    /// unless it takes a job before.
    pub unit_idle_in_two: Signal<In, Bit>,
    /// Another pipeline moving in step with this one holds two clocks from
    /// now if `advance` is high next clock, and if it is low (the OR of all
    /// their requests; this one's may be included). 0 on its own.
    pub others_if_advance: Signal<In, Bit>,
    pub others_if_still: Signal<In, Bit>,
    /// This pipeline's rare pair will wait for the unit two clocks from
    /// now, if `advance` is high next clock, and if it is low.
    pub request_if_advance: Signal<Out, Bit>,
    pub request_if_still: Signal<Out, Bit>,
    /// `hold` next clock, if `advance` is high this clock and if it is low:
    /// the copies' inputs.
    pub if_advance: Signal<Out, Bit>,
    pub if_still: Signal<Out, Bit>,
    if_advance_q: DFF<Bit>,
    if_still_q: DFF<Bit>,
    /// The forecast's own copy of `hold`.
    hold: HoldRegister,
    moving: Signal<Local, Bit>,
    hold_next: Signal<Local, Bit>,
    queued_next: Signal<Local, Bit>,
    job_next: Signal<Local, Bit>,
    idle_next: Signal<Local, Bit>,
}

impl crate::unit::Unit for HoldForecast {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, if_advance_q, if_still_q, hold);
    }
}

impl Logic for HoldForecast {
    #[hdl_gen]
    fn update(&mut self) {
        // Each register's `d` is written once, so that it leaves the
        // combinational block as an `assign`: in the block, with the read
        // of `others_*` (the pipelines' requests, this one's among them),
        // Verilator's lint would see a loop through the requests.
        self.if_advance_q.clock.next = self.clock.val();
        self.if_still_q.clock.next = self.clock.val();
        self.if_advance.next = self.if_advance_q.q.val();
        self.if_still.next = self.if_still_q.q.val();
        self.hold.clock.next = self.clock.val();
        self.hold.reset.next = self.reset.val();
        self.hold.advance.next = self.advance.val();
        self.hold.if_advance.next = self.if_advance_q.q.val();
        self.hold.if_still.next = self.if_still_q.q.val();

        // The state at the next clock.
        self.moving.next = self.advance.val() && !self.hold.hold.val();
        self.hold_next.next = (self.advance.val() && self.if_advance_q.q.val())
            || (!self.advance.val() && self.if_still_q.q.val());
        if self.moving.val() {
            self.queued_next.next = self.sides_rare.val();
            self.job_next.next = self.queued_rare.val();
            self.idle_next.next = self.unit_idle_in_two.val() && !self.job_rare.val();
        } else {
            self.queued_next.next = self.queued_rare.val();
            self.job_next.next = self.job_rare.val();
            self.idle_next.next = self.unit_idle_in_two.val();
        }

        // The request at the next clock, by its `advance`.
        self.request_if_still.next = self.job_next.val() && !self.idle_next.val();
        if self.hold_next.val() {
            // Held, the pipeline stands still whatever `advance` is: the
            // request is `request_if_still`'s, written again because
            // reading that output back here puts it in the block that
            // reads `others_if_still`, a loop to Verilator's lint.
            self.request_if_advance.next = self.job_next.val() && !self.idle_next.val();
        } else {
            self.request_if_advance.next =
                self.queued_next.val() && (self.job_next.val() || !self.idle_next.val());
        }
        self.if_advance_q.d.next =
            (self.request_if_advance.val() || self.others_if_advance.val()) && !self.reset.val();
        self.if_still_q.d.next =
            (self.request_if_still.val() || self.others_if_still.val()) && !self.reset.val();
    }
}
