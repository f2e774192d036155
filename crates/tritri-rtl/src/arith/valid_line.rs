//! The valid-bit companion of [`super::delay_line::DelayLine`]: an `N`-stage
//! enabled shift register of one bit with a synchronous active-high reset
//! (control state is reset, docs/ARCHITECTURE.md, conventions). It marks which pipeline slots hold
//! a pair.

use super::delay_line::delay_line_verilog;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct ValidLine<const N: usize> {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    pub d: Signal<In, Bit>,
    pub q: Signal<Out, Bit>,
    _stages: [bool; N],
}

impl<const N: usize> crate::unit::Unit for ValidLine<N> {
    const LATENCY: Option<usize> = Some(N);
}

impl<const N: usize> Default for ValidLine<N> {
    fn default() -> Self {
        assert!(N >= 1, "a valid line has at least one stage");
        Self {
            clock: Default::default(),
            reset: Default::default(),
            advance: Default::default(),
            d: Default::default(),
            q: Default::default(),
            _stages: [false; N],
        }
    }
}

impl<const N: usize> Logic for ValidLine<N> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            if self.reset.val() {
                self._stages = [false; N];
            } else if self.advance.val() {
                self._stages.copy_within(0..N - 1, 1);
                self._stages[0] = self.d.val();
            }
            self.q.next = self._stages[N - 1];
        }
    }

    fn connect(&mut self) {
        self.q.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(delay_line_verilog(1, N, Some("reset")))
    }
}
