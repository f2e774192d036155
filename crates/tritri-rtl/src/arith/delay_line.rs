//! An `N`-stage delay line with clock enable: `q` is `d` delayed by `N`
//! enabled clock edges. It carries vertex coordinates, normals, flags and
//! ids alongside the arithmetic so that every unit sees the operands of the
//! same pair (thesis, chapter 3: the base-polygon values "are passed on to
//! the registers of the next pipeline stage").
//!
//! Datapath only: no reset (docs/ARCHITECTURE.md, conventions). Valid bits use
//! [`super::valid_line::ValidLine`], which has one.
//! Verilog: one register per stage, `stage_<i>_q`, the last being `q`;
//! FPGA tools map long ones onto shift-register LUTs.

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct DelayLine<T: Synth, const N: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    _stages: [T; N],
}

impl<T: Synth, const N: usize> crate::unit::Unit for DelayLine<T, N> {
    const LATENCY: Option<usize> = Some(N);
}

impl<T: Synth, const N: usize> Default for DelayLine<T, N> {
    fn default() -> Self {
        assert!(N >= 1, "a delay line has at least one stage");
        Self {
            clock: Default::default(),
            advance: Default::default(),
            d: Default::default(),
            q: Default::default(),
            _stages: [T::default(); N],
        }
    }
}

impl<T: Synth, const N: usize> Logic for DelayLine<T, N> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.advance.val() {
            self._stages.copy_within(0..N - 1, 1);
            self._stages[0] = self.d.val();
            self.q.next = self._stages[N - 1];
        }
    }

    fn connect(&mut self) {
        self.q.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(delay_line_verilog(T::BITS, N, None))
    }
}

/// Verilog of an `n`-stage, `bits`-wide enabled shift register ending in `q`;
/// with `reset = Some(signal)`, a synchronous active-high reset clears it.
pub(crate) fn delay_line_verilog(bits: usize, n: usize, reset: Option<&str>) -> String {
    let range = if bits == 1 {
        String::new()
    } else {
        format!("[{}:0] ", bits - 1)
    };
    let name = |i: usize| {
        if i + 1 == n {
            "q".to_string()
        } else {
            format!("stage_{i}_q")
        }
    };
    let mut v = format!("// Delay line: {n} stage(s) of {bits} bit(s).\n");
    for i in 0..n - 1 {
        v += &format!("reg {range}{};\n", name(i));
    }
    v += "initial begin\n";
    for i in 0..n {
        v += &format!("    {} = {bits}'d0;\n", name(i));
    }
    v += "end\nalways @(posedge clock) begin\n";
    let shifts = |indent: &str| {
        let mut s = String::new();
        for i in 0..n {
            let src = if i == 0 { "d".to_string() } else { name(i - 1) };
            s += &format!("{indent}{} <= {src};\n", name(i));
        }
        s
    };
    match reset {
        Some(r) => {
            v += &format!("    if ({r}) begin\n");
            for i in 0..n {
                v += &format!("        {} <= {bits}'d0;\n", name(i));
            }
            v += "    end else if (advance) begin\n";
            v += &shifts("        ");
            v += "    end\n";
        }
        None => {
            v += "    if (advance) begin\n";
            v += &shifts("        ");
            v += "    end\n";
        }
    }
    v += "end\n";
    v
}
