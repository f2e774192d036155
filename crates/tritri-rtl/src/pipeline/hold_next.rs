//! `hold` next clock, once for each value `advance` may take this clock:
//! the two registers the copies of `hold`
//! ([`super::hold_register::HoldRegister`]) pick from, made from the
//! pipelines' requests of the clock before.
//!
//! A request ([`super::hold_forecast::HoldForecast`]) was decided a clock
//! ago for three clocks after it: a pipeline holds two clocks from now,
//! once for each value `advance` takes this clock (`a`) and each value of
//! "the pipelines move next clock" (`m`), at index `2 a + m`. The requests
//! arrive here from registers, ORed over the pipelines that move in step,
//! so that between pipelines they cross the chip from a register into one
//! LUT (W = 8, P = 2: decided in the clock they acted, a plane-side sign
//! of one pipeline reached the other's forecast register through four
//! levels, 6.6 of 8.0 ns routing, 124.4 MHz). Here, knowing `advance`,
//! the unit picks `a`; knowing `hold` next clock from its own registers,
//! it picks `m` for `advance` high next clock (the pipelines move then
//! unless they hold), and `m = 0` for `advance` low.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Requests per pipeline: `2 a + m`, for `a` and `m` in {0, 1}.
pub const HOLD_REQUESTS: usize = 4;

#[derive(LogicBlock, Default)]
pub struct HoldNext {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: no hold.
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    /// The pipelines' requests of the clock before, ORed: some pipeline
    /// holds two clocks from now if `advance` is `a` this clock and the
    /// pipelines move (`m`) next clock, at `2 a + m`.
    pub requests: Signal<In, Bits<HOLD_REQUESTS>>,
    /// `hold` next clock, if `advance` is high this clock and if it is low.
    pub if_advance: Signal<Out, Bit>,
    pub if_still: Signal<Out, Bit>,
    if_advance_q: DFF<Bit>,
    if_still_q: DFF<Bit>,
    /// `hold` next clock.
    hold_next: Signal<Local, Bit>,
    /// Some pipeline holds two clocks from now if they stand still next
    /// clock, and if they move.
    if_standing: Signal<Local, Bit>,
    if_moving: Signal<Local, Bit>,
}

impl crate::unit::Unit for HoldNext {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, if_advance_q, if_still_q);
    }
}

/// The update's literals 0 to 3.
const _: () = assert!(HOLD_REQUESTS == 4);

impl Logic for HoldNext {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, if_advance_q, if_still_q);
        self.if_advance.next = self.if_advance_q.q.val();
        self.if_still.next = self.if_still_q.q.val();
        if self.advance.val() {
            self.hold_next.next = self.if_advance_q.q.val();
            self.if_standing.next = self.requests.val().get_bit(2);
            self.if_moving.next = self.requests.val().get_bit(3);
        } else {
            self.hold_next.next = self.if_still_q.q.val();
            self.if_standing.next = self.requests.val().get_bit(0);
            self.if_moving.next = self.requests.val().get_bit(1);
        }
        self.if_still_q.d.next = self.if_standing.val() && !self.reset.val();
        if self.hold_next.val() {
            self.if_advance_q.d.next = self.if_standing.val() && !self.reset.val();
        } else {
            self.if_advance_q.d.next = self.if_moving.val() && !self.reset.val();
        }
    }
}
