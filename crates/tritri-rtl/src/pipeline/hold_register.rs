//! One registered copy of the shared pipeline's `hold`; with `advance` it
//! makes the enable of a group of its registers.
//!
//! The enable reaches every register of the pipeline. Computed once from
//! the rare bit and the unit's state, it crossed the chip to some 11,000
//! clock enables (ECP5, W = 8: 6.6 ns of routing on that net alone, 79 MHz
//! post-route). So `hold` is a register, decided a clock ahead, and there
//! is one copy per group of units ([`super::shared_rare_pipeline`]). Each
//! copy computes its next value from its own output, so the copies stay
//! equal clock by clock, yet synthesis sees different logic and keeps
//! them apart (Yosys merges registers with the same inputs, `keep` or not).
//!
//! `hold` is high when the pair at the job stage is rare and the unit is
//! not ready (this pipeline's request), or when another pipeline moving in
//! step with this one requests it (`others`, in a system of several). Each
//! pipeline's request for next clock leaves as `request` and comes back to
//! every pipeline's copies in the same clock, so the copies of all
//! pipelines stay equal and each group's enable is a register of its own
//! pipeline (with the other pipelines' `hold` read in the clock it acts, a
//! P = 2 system ran at 63.6 MHz on ECP5, its path one net across the chip).
//! The request for next clock:
//! * that pair is the one moving in from the sides stage (`rare`) if the
//!   pipeline moves now, else the same (`job_rare`);
//! * the unit is ready unless it takes a job now (the job stage's pair is
//!   rare and moves) or has more than two steps of its current job left
//!   (`unit_idle_next` is low).

use rust_hdl::prelude::*;

/// The part of the module names the ECP5 flow keeps apart
/// ([`crate::route`]), as it keeps register copies. Flattened, a copy's
/// own "moving" term (`advance` and not `hold`) is its group's enable, the
/// same function of the same nets, and synthesis shares one LUT for both:
/// the copy's next value then went out to that LUT by its group and came
/// back, 10.5 ns of routing (W = 16, router1: 83.3 MHz).
pub const HOLD_REGISTER_MODULE: &str = "hold_register";

/// A job taken now leaves the unit busy next clock (it is ready with one
/// step left): the rule above, written against the unit's step counts.
const _: () = assert!(
    super::shared_rare_cases::SEGMENTS_STEPS >= 2 && super::shared_rare_cases::COPLANAR_STEPS >= 2
);
use rust_hdl::widgets::prelude::DFF;

#[derive(LogicBlock, Default)]
pub struct HoldRegister {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: no hold.
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    /// The pair at the sides stage is rare.
    pub rare: Signal<In, Bit>,
    /// The pair at the job stage is rare.
    pub job_rare: Signal<In, Bit>,
    /// The unit will be ready next clock if it takes no job now.
    pub unit_idle_next: Signal<In, Bit>,
    /// Another pipeline moving with this one holds next clock (its
    /// `request`; this one's may be included).
    pub others: Signal<In, Bit>,
    pub hold: Signal<Out, Bit>,
    /// This pipeline's rare pair will wait for the unit next clock.
    pub request: Signal<Out, Bit>,
    hold_q: DFF<Bit>,
    rare_next: Signal<Local, Bit>,
    ready_next: Signal<Local, Bit>,
}

impl crate::unit::Unit for HoldRegister {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, hold_q);
    }
}

impl Logic for HoldRegister {
    #[hdl_gen]
    fn update(&mut self) {
        // `d` is written once, below, so that it leaves the combinational
        // block as an `assign`: in the block, with the read of `others`
        // (the pipelines' requests, this one's among them), Verilator's
        // lint would see a loop through `request`.
        self.hold_q.clock.next = self.clock.val();
        self.hold.next = self.hold_q.q.val();
        if self.advance.val() && !self.hold_q.q.val() {
            self.rare_next.next = self.rare.val();
            self.ready_next.next = !self.job_rare.val() && self.unit_idle_next.val();
        } else {
            self.rare_next.next = self.job_rare.val();
            self.ready_next.next = self.unit_idle_next.val();
        }
        self.request.next = self.rare_next.val() && !self.ready_next.val();
        self.hold_q.d.next = ((self.rare_next.val() && !self.ready_next.val())
            || self.others.val())
            && !self.reset.val();
    }
}
