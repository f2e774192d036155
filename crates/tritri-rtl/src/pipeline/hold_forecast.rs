//! The shared pipeline's `hold`, requested three clocks ahead, so that
//! pipelines moving in step can exchange their requests through registers
//! ([`HoldNext`] takes them a clock later and decides `hold` two clocks
//! ahead, one register for each value `advance` may take next clock, which
//! the copies of `hold`, [`super::hold_register::HoldRegister`], pick from
//! by `advance`).
//!
//! `hold` is high when the pair at the job stage is rare and the unit is
//! not ready for it (this pipeline's request), or when another pipeline
//! moving in step with this one requests it. In a clock `t`, knowing
//! `advance` and `hold` now and `hold` at `t + 1` ([`HoldNext`]'s
//! registers), the forecast works out the pipeline's state at `t + 3`
//! for each value of `advance` at `t + 1` (`a`) and of "the pipeline moves
//! at `t + 2`" (`m`; `hold` at `t + 2` is still being exchanged):
//! * the pair at the job stage then: of the four pairs now at the job
//!   stage and the three stages before it (the rare bits `job_rare`,
//!   `rare_1`, `rare_2`, and the rule at the sides stage, `sides_rare`),
//!   the one the moves at `t`, `t + 1` and `t + 2` bring there;
//! * the unit's readiness: it takes the job stage's pair in a clock the
//!   pipeline moves if that pair is rare, and is then busy for three clocks
//!   at least; else it is ready at `t + 3` if it has at most four steps
//!   left now (`unit_idle_in_three`).
//!
//! The request for `(a, m)` is that pair rare and the unit not ready, a
//! register (`requests`, at `2 a + m`).
//!
//! Pipelines that move in step (a system's) send their requests and take
//! the OR of all of them (`others`, this one's included) into their
//! [`HoldNext`] in the next clock, so that all their copies stay equal.

use super::hold_next::{HoldNext, HOLD_REQUESTS};
use super::hold_register::HoldRegister;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// A job taken in a clock leaves the unit busy for the next three (its
/// steps left start at the job's steps and the unit is ready at one), so
/// a take at `t`, `t + 1` or `t + 2` leaves it busy at `t + 3`; and a unit
/// with four steps left is ready three clocks later.
const _: () = assert!(
    super::shared_rare_cases::SEGMENTS_STEPS >= 4 && super::shared_rare_cases::COPLANAR_STEPS >= 4
);

#[derive(LogicBlock, Default)]
pub struct HoldForecast {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: no hold.
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    /// The pair at the sides stage is rare (the rule, from its zeros).
    pub sides_rare: Signal<In, Bit>,
    /// The pairs one and two stages before the job stage, and the one at
    /// it, are rare.
    pub rare_2: Signal<In, Bit>,
    pub rare_1: Signal<In, Bit>,
    pub job_rare: Signal<In, Bit>,
    /// The unit has at most four steps left: ready three clocks from now
    /// unless it takes a job before.
    pub unit_idle_in_three: Signal<In, Bit>,
    /// The requests of the pipelines moving in step with this one, a clock
    /// old, ORed (this one's may be included); 0 on its own.
    pub others: Signal<In, Bits<HOLD_REQUESTS>>,
    /// This pipeline's rare pair will wait for the unit three clocks from
    /// now if `advance` is `a` next clock and the pipeline moves (`m`) two
    /// clocks from now, at `2 a + m`.
    pub requests: Signal<Out, Bits<HOLD_REQUESTS>>,
    /// `hold` next clock, if `advance` is high this clock and if it is low:
    /// the copies' inputs.
    pub if_advance: Signal<Out, Bit>,
    pub if_still: Signal<Out, Bit>,
    requests_q: [DFF<Bit>; HOLD_REQUESTS],
    /// The registers, gathered into `requests` bit by bit.
    request_bits: [Signal<Local, Bits<HOLD_REQUESTS>>; HOLD_REQUESTS + 1],
    next: HoldNext,
    /// The forecast's own copy of `hold`.
    hold: HoldRegister,
    /// At `t`: the pipeline moves; `hold` at `t + 1`.
    moving: Signal<Local, Bit>,
    hold_1: Signal<Local, Bit>,
    /// The unit is ready at `t + 3` unless it takes a job at `t + 1` or
    /// `t + 2`.
    unit_free: Signal<Local, Bit>,
    /// At `t + 1`: the pairs at the job stage and at the two stages before
    /// it are rare.
    job_1: Signal<Local, Bit>,
    before_job_1: Signal<Local, Bit>,
    two_before_job_1: Signal<Local, Bit>,
    /// With `advance` high at `t + 1`: the pipeline moves then, the unit
    /// takes a job then, and at `t + 2` the pairs at the job stage and the
    /// stage before it are rare.
    moving_1: Signal<Local, Bit>,
    take_1: Signal<Local, Bit>,
    job_2: Signal<Local, Bit>,
    before_job_2: Signal<Local, Bit>,
}

impl crate::unit::Unit for HoldForecast {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, requests_q, next, hold);
    }
}

/// The update's literal 4.
const _: () = assert!(HOLD_REQUESTS == 4);

impl Logic for HoldForecast {
    #[hdl_gen]
    fn update(&mut self) {
        self.next.clock.next = self.clock.val();
        self.next.reset.next = self.reset.val();
        self.next.advance.next = self.advance.val();
        self.if_advance.next = self.next.if_advance.val();
        self.if_still.next = self.next.if_still.val();
        self.hold.clock.next = self.clock.val();
        self.hold.reset.next = self.reset.val();
        self.hold.advance.next = self.advance.val();
        self.hold.if_advance.next = self.next.if_advance.val();
        self.hold.if_still.next = self.next.if_still.val();
        self.request_bits[0].next = 0.into();
        for k in 0..4 {
            self.requests_q[k].clock.next = self.clock.val();
            self.request_bits[k + 1].next = self.request_bits[k]
                .val()
                .replace_bit(k, self.requests_q[k].q.val());
        }
        self.requests.next = self.request_bits[4].val();
        self.next.requests.next = self.request_bits[4].val() | self.others.val();

        // Now, and at t + 1.
        self.moving.next = self.advance.val() && !self.hold.hold.val();
        // `HoldNext` makes the same choice inside; made here from its
        // registers, `advance` reaches the request registers without going
        // into a unit and back out, a path direct-drive simulation would
        // see a delta cycle after the clock edge (`sim_drive::clock_cycle`).
        if self.advance.val() {
            self.hold_1.next = self.next.if_advance.val();
        } else {
            self.hold_1.next = self.next.if_still.val();
        }
        self.unit_free.next =
            self.unit_idle_in_three.val() && !(self.moving.val() && self.job_rare.val());
        if self.moving.val() {
            self.job_1.next = self.rare_1.val();
            self.before_job_1.next = self.rare_2.val();
            self.two_before_job_1.next = self.sides_rare.val();
        } else {
            self.job_1.next = self.job_rare.val();
            self.before_job_1.next = self.rare_1.val();
            self.two_before_job_1.next = self.rare_2.val();
        }

        // `advance` low at t + 1: the pipeline stands, and takes no job.
        self.requests_q[0].d.next = self.job_1.val() && !self.unit_free.val() && !self.reset.val();
        self.requests_q[1].d.next = self.before_job_1.val()
            && !(self.unit_free.val() && !self.job_1.val())
            && !self.reset.val();

        // `advance` high at t + 1: the pipeline moves unless it holds.
        self.moving_1.next = !self.hold_1.val();
        self.take_1.next = self.moving_1.val() && self.job_1.val();
        if self.moving_1.val() {
            self.job_2.next = self.before_job_1.val();
            self.before_job_2.next = self.two_before_job_1.val();
        } else {
            self.job_2.next = self.job_1.val();
            self.before_job_2.next = self.before_job_1.val();
        }
        self.requests_q[2].d.next =
            self.job_2.val() && !(self.unit_free.val() && !self.take_1.val()) && !self.reset.val();
        self.requests_q[3].d.next = self.before_job_2.val()
            && !(self.unit_free.val() && !self.take_1.val() && !self.job_2.val())
            && !self.reset.val();
    }
}
