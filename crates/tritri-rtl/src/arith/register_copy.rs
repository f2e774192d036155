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
//!
//! A copy has neither reset nor enable: kept apart, the module is also
//! kept from seeing constant ports, so an enable tied high and a reset
//! became a LUT in front of every copy's register, a level of logic behind
//! the long route to it (ECP5, W = 16 shared, the shared unit's offers,
//! 7.10 ns). Whoever drives `d` folds both into it.

use rust_hdl::prelude::*;

/// The part of the module names the ECP5 flow keeps apart.
pub const REGISTER_COPY_MODULE: &str = "register_copy";

#[derive(LogicBlock, Default)]
pub struct RegisterCopy<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    /// `d` one clock edge later.
    pub q: Signal<Out, T>,
    _q: T,
}

impl<T: Synth> crate::unit::Unit for RegisterCopy<T> {
    const LATENCY: Option<usize> = Some(1);
}

impl<T: Synth> Logic for RegisterCopy<T> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            self._q = self.d.val();
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
             always @(posedge clock) q <= d;\n",
            bits = T::BITS
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim_drive::clock_cycle;

    #[test]
    fn a_copy_follows_its_input_a_clock_later() {
        let mut unit = RegisterCopy::<Bits<4>>::default();
        unit.connect_all();
        for d in [5u64, 9, 9, 0, 3] {
            unit.d.next = Bits::from(d);
            clock_cycle(&mut unit, |u| &mut u.clock);
            assert_eq!(unit.q.val().to_u64(), d);
        }
    }
}
