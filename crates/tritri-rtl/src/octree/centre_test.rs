//! The half-space test of the eight voxels of a level-1 cell, by their
//! centres (`tritri_geom::octree::plane`): voxel `o` of the cell whose low
//! corner has `f = value` has its centre at `f = value + S_o + Σn / 2`
//! (`S_o` the sum of the gradient's components along the axes in `o`), and
//! is in the half-space `f <= d` iff `2 value <= offset - 2 S_o` with
//! `offset = 2d - Σn`. The right sides are constants of the plane: they
//! are formed into eight threshold registers at every clock from the held
//! inputs (ready one clock after they are set, long before the first cell
//! arrives), so a cell's test is one comparison per voxel, registered.
//!
//! A custom-Verilog primitive with an exact i128 model evaluated at clock
//! edges, like [`super::axis_step::AxisStep`].

use crate::arith::convert::{to_i128, wrap_i128};
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct CentreTest<const V: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub value: Signal<In, Bits<V>>,
    pub gradient_x: Signal<In, Bits<V>>,
    pub gradient_y: Signal<In, Bits<V>>,
    pub gradient_z: Signal<In, Bits<V>>,
    /// `2d - Σn`.
    pub offset: Signal<In, Bits<V>>,
    /// Bit `o`: voxel `o`'s centre is in the half-space.
    pub mask: Signal<Out, Bits<8>>,
    _thresholds: [i128; 8],
}

impl<const V: usize> crate::unit::Unit for CentreTest<V> {}

impl<const V: usize> Default for CentreTest<V> {
    fn default() -> Self {
        assert!(
            (8..=127).contains(&V),
            "centre test of {V} bits is not supported"
        );
        Self {
            clock: Default::default(),
            advance: Default::default(),
            value: Default::default(),
            gradient_x: Default::default(),
            gradient_y: Default::default(),
            gradient_z: Default::default(),
            offset: Default::default(),
            mask: Default::default(),
            _thresholds: [0; 8],
        }
    }
}

impl<const V: usize> Logic for CentreTest<V> {
    fn update(&mut self) {
        if !self.clock.pos_edge() {
            return;
        }
        if self.advance.val() {
            let twice = wrap_i128(to_i128(self.value.val()) << 1, V);
            let mask = (0..8usize).filter(|&o| twice <= self._thresholds[o]);
            self.mask.next = Bits::from(mask.fold(0u64, |m, o| m | 1 << o));
        }
        let g = [
            self.gradient_x.val(),
            self.gradient_y.val(),
            self.gradient_z.val(),
        ]
        .map(to_i128);
        let offset = to_i128(self.offset.val());
        for (o, t) in self._thresholds.iter_mut().enumerate() {
            let sum: i128 = (0..3).filter(|k| o >> k & 1 == 1).map(|k| g[k]).sum();
            *t = wrap_i128(offset - wrap_i128(sum << 1, V), V);
        }
    }

    fn connect(&mut self) {
        self.mask.connect();
    }

    fn hdl(&self) -> Verilog {
        let v1 = V - 1;
        let text = format!(
            "\
// The plane's thresholds offset - 2 S_o (S_o: subset sums of the gradient), every clock.
reg [{v1}:0] t [0:7];
wire [{v1}:0] twice = value << 1;
integer i;
initial begin
    mask = 8'd0;
    for (i = 0; i < 8; i = i + 1) t[i] = {V}'d0;
end
always @(posedge clock) begin
    t[0] <= offset;
    t[1] <= offset - (gradient_x << 1);
    t[2] <= offset - (gradient_y << 1);
    t[3] <= offset - (gradient_x << 1) - (gradient_y << 1);
    t[4] <= offset - (gradient_z << 1);
    t[5] <= offset - (gradient_x << 1) - (gradient_z << 1);
    t[6] <= offset - (gradient_y << 1) - (gradient_z << 1);
    t[7] <= offset - (gradient_x << 1) - (gradient_y << 1) - (gradient_z << 1);
    if (advance) begin
        for (i = 0; i < 8; i = i + 1) begin
            mask[i] <= $signed(twice) <= $signed(t[i]);
        end
    end
end
",
        );
        Verilog::Custom(text)
    }
}
