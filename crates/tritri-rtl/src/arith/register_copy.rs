//! A register that holds the same value as others, on purpose: a copy of a
//! widely used register (an enable, a select) for one group of its loads,
//! so that each copy can sit by its group instead of one register driving
//! the whole group across the chip.
//!
//! Yosys merges registers with the same inputs (`opt_merge`, `keep` or
//! not), so copies written as plain registers come out of synthesis as
//! one again. The copy is therefore a module of its own: the ECP5 flow
//! ([`crate::route`]) gives every `*_register_copy*` module
//! `keep_hierarchy`, which keeps each instance, and nextpnr places them
//! apart. Other flows see ordinary registers, and may merge them or
//! duplicate by their own fan-out rules.

use rust_hdl::prelude::*;

/// The part of the module names the ECP5 flow keeps apart.
pub const REGISTER_COPY_MODULE: &str = "register_copy";

#[derive(LogicBlock, Default)]
pub struct RegisterCopy<T: Synth> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active high, before `advance`: the copy of a register
    /// that has a reset (tied low for one that has none).
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    pub d: Signal<In, T>,
    /// `d` one enabled clock edge later.
    pub q: Signal<Out, T>,
    _q: T,
}

impl<T: Synth> crate::unit::Unit for RegisterCopy<T> {
    const LATENCY: Option<usize> = Some(1);
}

impl<T: Synth> Logic for RegisterCopy<T> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            if self.reset.val() {
                self._q = T::default();
            } else if self.advance.val() {
                self._q = self.d.val();
            }
            self.q.next = self._q;
        }
    }

    fn connect(&mut self) {
        self.q.connect();
    }

    // Written apart from `DelayLine`'s one stage (which the emitter would
    // otherwise merge with it as the same text).
    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "// A copy of a register for one group of its loads (register_copy.rs).\n\
             initial q = {bits}'d0;\n\
             always @(posedge clock) q <= reset ? {bits}'d0 : advance ? d : q;\n",
            bits = T::BITS
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim_drive::clock_cycle;

    #[test]
    fn a_copy_follows_its_input_on_enabled_edges() {
        let mut unit = RegisterCopy::<Bits<4>>::default();
        unit.connect_all();
        for (d, reset, advance, expect) in [
            (5u64, false, true, 5u64),
            (9, false, false, 5),
            (9, false, true, 9),
            (3, true, true, 0),
        ] {
            unit.d.next = Bits::from(d);
            unit.reset.next = reset;
            unit.advance.next = advance;
            clock_cycle(&mut unit, |u| &mut u.clock);
            assert_eq!(unit.q.val().to_u64(), expect);
        }
    }
}
