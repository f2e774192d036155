//! One registered copy of the shared pipeline's `hold`; with `advance` it
//! makes the enable of a group of its registers.
//!
//! The enable reaches every register of the pipeline. Computed once from
//! the rare bit and the unit's state, it crossed the chip to some 11,000
//! clock enables (ECP5, W = 8: 6.6 ns of routing on that net alone, 79 MHz
//! post-route). So `hold` is a register, and there is one copy per group
//! of units ([`super::shared_rare_pipeline`]). With each copy deciding
//! `hold` a clock ahead from the rare bits and the unit's state, a copy
//! still reached up to 4,474 clock enables (W = 16, router1: 105.3 MHz, an
//! enable on the critical path), and a copy cost as much logic as the
//! decision. Now [`super::hold_next::HoldNext`] decides `hold` two clocks
//! ahead (from the requests [`super::hold_forecast::HoldForecast`] makes a
//! clock before), once for each value `advance` may take next clock, and
//! a copy only picks one of its two registers by `advance`: many copies,
//! each beside a small group, all equal clock by clock.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// The part of the module names the ECP5 flow keeps apart
/// ([`crate::route`]), as it keeps register copies. Flattened, the copies
/// are the same function of the same nets, and synthesis would make them
/// one register again (and with the copy's "moving" term, `advance` and
/// not `hold`, shared with its group's enable, the copy's next value went
/// out to that LUT by its group and came back: 10.5 ns of routing, W = 16,
/// router1, 83.3 MHz).
pub const HOLD_REGISTER_MODULE: &str = "hold_register";

#[derive(LogicBlock, Default)]
pub struct HoldRegister {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: no hold.
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    /// `hold` next clock if `advance` is high this clock, and if it is low
    /// (the forecast's registers).
    pub if_advance: Signal<In, Bit>,
    pub if_still: Signal<In, Bit>,
    pub hold: Signal<Out, Bit>,
    hold_q: DFF<Bit>,
}

impl crate::unit::Unit for HoldRegister {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, hold_q);
    }
}

impl Logic for HoldRegister {
    #[hdl_gen]
    fn update(&mut self) {
        self.hold_q.clock.next = self.clock.val();
        self.hold.next = self.hold_q.q.val();
        self.hold_q.d.next = ((self.advance.val() && self.if_advance.val())
            || (!self.advance.val() && self.if_still.val()))
            && !self.reset.val();
    }
}
