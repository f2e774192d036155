//! The half-space test of the eight voxels of a level-1 cell, by their
//! centres (`tritri_geom::octree::plane`): voxel `o` of the cell whose low
//! corner has `f = value` has its centre at `f = value + S_o + Σn / 2`
//! (`S_o` the sum of the gradient's components along the axes in `o`), and
//! is in the half-space `f <= d` iff `2 (value + S_o) <= 2d - Σn`, the
//! right side a constant of the plane (`offset`). Eight adds and compares,
//! one register stage.
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
}

impl<const V: usize> Default for CentreTest<V> {
    fn default() -> Self {
        assert!((8..=127).contains(&V), "centre test of {V} bits is not supported");
        Self {
            clock: Default::default(),
            advance: Default::default(),
            value: Default::default(),
            gradient_x: Default::default(),
            gradient_y: Default::default(),
            gradient_z: Default::default(),
            offset: Default::default(),
            mask: Default::default(),
        }
    }
}

impl<const V: usize> Logic for CentreTest<V> {
    fn update(&mut self) {
        if !(self.clock.pos_edge() && self.advance.val()) {
            return;
        }
        let g = [self.gradient_x.val(), self.gradient_y.val(), self.gradient_z.val()].map(to_i128);
        let (value, offset) = (to_i128(self.value.val()), to_i128(self.offset.val()));
        let mask = (0..8usize).filter(|&o| {
            let sum = wrap_i128(value + (0..3).filter(|k| o >> k & 1 == 1).map(|k| g[k]).sum::<i128>(), V);
            wrap_i128(sum << 1, V) <= offset
        });
        self.mask.next = Bits::from(mask.fold(0u64, |m, o| m | 1 << o));
    }

    fn connect(&mut self) {
        self.mask.connect();
    }

    fn hdl(&self) -> Verilog {
        let v1 = V - 1;
        let text = format!(
            "\
// Voxel o of the level-1 cell: 2 (value + S_o) <= offset, S_o the subset sums of the gradient.
wire [{v1}:0] s [0:7];
assign s[0] = value;
assign s[1] = value + gradient_x;
assign s[2] = value + gradient_y;
assign s[3] = value + gradient_x + gradient_y;
assign s[4] = value + gradient_z;
assign s[5] = value + gradient_x + gradient_z;
assign s[6] = value + gradient_y + gradient_z;
assign s[7] = value + gradient_x + gradient_y + gradient_z;
integer i;
initial mask = 8'd0;
always @(posedge clock) begin
    if (advance) begin
        for (i = 0; i < 8; i = i + 1) begin
            mask[i] <= $signed({{s[i][{v2}:0], 1'b0}}) <= $signed(offset);
        end
    end
end
",
            v2 = V - 2,
        );
        Verilog::Custom(text)
    }
}
