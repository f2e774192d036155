//! Whether one group of the base polygon's registers loads at the next
//! edge where `advance` is high: a register beside the group, with a copy
//! of `hold` of its own beside it.
//!
//! The load is pending while the record at the record stage (the front
//! end's output, which the base loads) has `BSET`: it is registered from
//! `load_ahead` where the pipeline moves (`advance` high, `hold` low), as
//! that record moves in. The group's
//! enable is then `advance` and the pending load, not `hold`: while the
//! pipeline holds, the front end's output holds too, so the group loads
//! the same record again, and the only pair formed with the base then is
//! the `BSET` record's own, which is not valid.
//!
//! Why a unit per group: the base polygon's registers sit by their loads,
//! across the chip. With the load registered once per group but `hold` in
//! every group's enable, one copy of `hold` reached all the groups: W = 16
//! with the rare cases shared, nextpnr's seed 2, that copy into the enable
//! of the base's id register was the critical path (7.4 ns of routing,
//! 119.7 MHz), 32 of the 96 register inputs short of 150 MHz on that
//! register. Here `hold` only decides the pending load's next value, from
//! a [`HoldRegister`] of the unit's own beside it.
//!
//! A top that never holds ties `hold_if_advance` and `hold_if_still` low.

use super::hold_register::HoldRegister;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// The part of the module names the ECP5 flow keeps apart
/// ([`crate::route`]): flattened, the units of the groups are the same
/// function of the same nets, and synthesis would make them one again.
pub const LOAD_ENABLE_MODULE: &str = "load_enable";

#[derive(LogicBlock, Default)]
pub struct LoadEnable {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high: no load pending, no hold.
    pub reset: Signal<In, Bit>,
    /// `advance` before `hold` (the top's input).
    pub advance: Signal<In, Bit>,
    /// The next edge where the pipeline moves brings a record to load.
    pub load_ahead: Signal<In, Bit>,
    /// `hold` next clock if `advance` is high this clock, and if it is low
    /// (the forecast's registers).
    pub hold_if_advance: Signal<In, Bit>,
    pub hold_if_still: Signal<In, Bit>,
    /// The group loads at the next edge where `advance` is high.
    pub load: Signal<Out, Bit>,
    hold: HoldRegister,
    pending_q: DFF<Bit>,
}

impl crate::unit::Unit for LoadEnable {
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, hold, pending_q);
    }
}

impl Logic for LoadEnable {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, pending_q);
        self.hold.clock.next = self.clock.val();
        self.hold.reset.next = self.reset.val();
        self.hold.advance.next = self.advance.val();
        self.hold.if_advance.next = self.hold_if_advance.val();
        self.hold.if_still.next = self.hold_if_still.val();
        if self.advance.val() && !self.hold.hold.val() {
            self.pending_q.d.next = self.load_ahead.val();
        }
        if self.reset.val() {
            self.pending_q.d.next = false;
        }
        self.load.next = self.pending_q.q.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim_drive::clock_cycle;

    /// The unit against a model of `hold` (as the hold register computes
    /// it) and of the pending load (a register enabled by `advance` and not
    /// `hold`), on a random walk of its inputs with resets.
    #[test]
    fn load_is_the_pending_load_moved_on_where_the_pipeline_moves() {
        let mut unit = LoadEnable::default();
        unit.connect_all();
        let (mut hold, mut pending) = (false, false);
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for step in 0..4000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let bit = |k: u32| (state >> k) & 1 == 1;
            let reset = step < 2 || (state >> 20) % 97 == 0;
            let (advance, load_ahead, if_advance, if_still) = (bit(0), bit(1), bit(2), bit(3));
            unit.reset.next = reset;
            unit.advance.next = advance;
            unit.load_ahead.next = load_ahead;
            unit.hold_if_advance.next = if_advance;
            unit.hold_if_still.next = if_still;
            clock_cycle(&mut unit, |u| &mut u.clock);
            let (next_hold, next_pending) = if reset {
                (false, false)
            } else {
                (
                    if advance { if_advance } else { if_still },
                    if advance && !hold {
                        load_ahead
                    } else {
                        pending
                    },
                )
            };
            hold = next_hold;
            pending = next_pending;
            assert_eq!(unit.load.val(), pending, "clock {step}");
        }
    }
}
