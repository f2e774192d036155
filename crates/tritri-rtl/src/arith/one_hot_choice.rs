//! A registered choice among six values by a one-hot pick: `q` is the
//! value whose bit in `pick` is one (zero when no bit is), one clock edge
//! later.
//!
//! Written as an AND-OR, `({W{pick[0]}} & point_0) | ...`, so that each
//! bit is twelve inputs, two levels of LUT4; the same choice written as a
//! chain of `if`s on an encoded step became a chain of six LUTs shared
//! between bits (the shared rare-case unit's stage 1, ECP5). A primitive
//! with custom Verilog, because rust-hdl's generator writes a choice as
//! nested `if`s.

use rust_hdl::prelude::*;

#[derive(LogicBlock, Default)]
pub struct OneHotChoice<const W: usize> {
    pub clock: Signal<In, Clock>,
    /// At most one bit set: bit `p` takes `point_p`.
    pub pick: Signal<In, Bits<6>>,
    pub point_0: Signal<In, Bits<W>>,
    pub point_1: Signal<In, Bits<W>>,
    pub point_2: Signal<In, Bits<W>>,
    pub point_3: Signal<In, Bits<W>>,
    pub point_4: Signal<In, Bits<W>>,
    pub point_5: Signal<In, Bits<W>>,
    /// The picked point, registered in every clock.
    pub q: Signal<Out, Bits<W>>,
}

impl<const W: usize> crate::unit::Unit for OneHotChoice<W> {
    const LATENCY: Option<usize> = Some(1);
}

impl<const W: usize> Logic for OneHotChoice<W> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            let pick = self.pick.val();
            let points = [
                self.point_0.val(),
                self.point_1.val(),
                self.point_2.val(),
                self.point_3.val(),
                self.point_4.val(),
                self.point_5.val(),
            ];
            let mut q = Bits::<W>::default();
            for (p, point) in points.into_iter().enumerate() {
                if pick.get_bit(p) {
                    q = q | point;
                }
            }
            self.q.next = q;
        }
    }

    fn connect(&mut self) {
        self.q.connect();
    }

    fn hdl(&self) -> Verilog {
        let terms: Vec<String> = (0..6)
            .map(|p| format!("({{{W}{{pick[{p}]}}}} & point_{p})"))
            .collect();
        Verilog::Custom(format!(
            "// A registered one-hot choice among six {W}-bit points (one_hot_choice.rs).\n\
             initial q = {W}'d0;\n\
             always @(posedge clock) q <= {};\n",
            terms.join("\n    | ")
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_verilog_is_an_and_or_of_the_six_points() {
        let text = match OneHotChoice::<16>::default().hdl() {
            Verilog::Custom(text) => text,
            _ => unreachable!("a custom body"),
        };
        assert!(text.contains("({16{pick[0]}} & point_0)"), "{text}");
        assert!(text.contains("| ({16{pick[5]}} & point_5);"), "{text}");
    }
}
