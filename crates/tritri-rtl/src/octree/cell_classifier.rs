//! The octree engine's triangle classifier step, one entry per clock: a
//! triangle's thirteen test functions over a cell (optionally moved into a
//! child of the cell they were over) and the mask of the cell's children
//! that the triangle meets, exactly as `tritri_geom::octree::triangle_cell`
//! decides it.
//!
//! An entry is a triangle in a cell: the values of its thirteen affine
//! test functions at the cell's low corner, with the triangle's gradients
//! and intervals (fixed per triangle; the setup that computes them and the
//! root's values takes the multiplications and is not part of this unit).
//! Thirteen [`AxisStep`]s run side by side; a child is met when every
//! function's range meets its interval there (separating axes), so the
//! masks are ANDed. A triangle with fewer than thirteen distinct axes pads
//! with zero functions (gradient 0, interval `[0, 0]`), which meet every
//! cell.

use super::axis_step::{AxisStep, AXIS_STEP_LATENCY};
use crate::arith::delay_line::DelayLine;
use crate::arith::valid_line::ValidLine;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Test functions per triangle (`tritri_geom::octree::triangle_cell::MAX_AXES`).
pub const AXES: usize = 13;

/// Bits of the entry tag carried alongside (the controller's index).
pub const TAG_BITS: usize = 16;

/// Clock edges from an entry to its mask: the axis steps, then the AND.
pub const CELL_CLASSIFIER_LATENCY: usize = AXIS_STEP_LATENCY + 1;

#[derive(LogicBlock)]
pub struct CellClassifier<const V: usize> {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    pub in_valid: Signal<In, Bit>,
    pub in_tag: Signal<In, Bits<TAG_BITS>>,
    /// Level of the classified cell (>= 1: it has children; at most the
    /// grid's `G`, the root cube's).
    pub in_level: Signal<In, Bits<6>>,
    /// The values are over the parent; classify its child `in_octant`.
    pub in_descend: Signal<In, Bit>,
    pub in_octant: Signal<In, Bits<3>>,
    pub in_at_lo: [Signal<In, Bits<V>>; AXES],
    pub in_gradient_x: [Signal<In, Bits<V>>; AXES],
    pub in_gradient_y: [Signal<In, Bits<V>>; AXES],
    pub in_gradient_z: [Signal<In, Bits<V>>; AXES],
    pub in_low: [Signal<In, Bits<V>>; AXES],
    pub in_high: [Signal<In, Bits<V>>; AXES],
    pub out_valid: Signal<Out, Bit>,
    pub out_tag: Signal<Out, Bits<TAG_BITS>>,
    /// Bit `o`: the triangle meets child `o` of the classified cell.
    pub out_mask: Signal<Out, Bits<8>>,
    /// The values at the classified cell's low corner (the entry to store).
    pub out_at_lo: [Signal<Out, Bits<V>>; AXES],
    axis: [AxisStep<V>; AXES],
    mask_q: DFF<Bits<8>>,
    value_q: [DelayLine<Bits<V>, 1>; AXES],
    tag: DelayLine<Bits<TAG_BITS>, CELL_CLASSIFIER_LATENCY>,
    valid: ValidLine<CELL_CLASSIFIER_LATENCY>,
}

impl<const V: usize> crate::unit::Unit for CellClassifier<V> {
    const LATENCY: Option<usize> = Some(CELL_CLASSIFIER_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, axis, mask_q, value_q, tag, valid);
    }
}

/// The width each of the thirteen functions is computed at, in the
/// setup's order ([`super::triangle_setup`]: the axes, the plane, the
/// edges), for the `V`-bit values of `G = (V - 6) / 3`-bit grids.
///
/// Over the root cube (corners within `2^G` of its low corner, coordinates
/// differing by less than `2^G`):
/// * an axis (`g` a unit vector): values, interval ends and `q_k` below
///   `2^G + 1`, so `δ` and `ε` below `2^(G+2)`: `G + 3` signed bits;
/// * an edge (`g = e × u_k`, two components below `2^G`): values and
///   interval ends below `2^(2G+1) + 2^(G+1)`, the `q_k` below `2^(2G-1)`,
///   so `δ`, `ε` below `2^(2G+3)`: `2G + 4` signed bits;
/// * the plane: the full `V` ([`super::value_bits`]).
///
/// One bit of slack on each; a padding function (zero) fits any width.
/// The steps shift by `level - 1` in [`shift_bits`] bits.
pub fn function_bits(v: usize) -> [usize; AXES] {
    let g = (v - 6) / 3;
    let axis = (g + 4).min(v);
    let edge = (2 * g + 5).min(v);
    std::array::from_fn(|i| match i {
        0..=2 => axis,
        3 => v,
        _ => edge,
    })
}

/// Bits of `level - 1` for the levels of a `G = (V - 6) / 3`-bit grid: a
/// cell of the root cube is at most at level `G`.
pub fn shift_bits(v: usize) -> usize {
    let g = (v - 6) / 3;
    (usize::BITS - (g - 1).leading_zeros()) as usize
}

impl<const V: usize> Default for CellClassifier<V> {
    fn default() -> Self {
        let bits = function_bits(V);
        let shift = shift_bits(V);
        CellClassifier {
            clock: Default::default(),
            reset: Default::default(),
            advance: Default::default(),
            in_valid: Default::default(),
            in_tag: Default::default(),
            in_level: Default::default(),
            in_descend: Default::default(),
            in_octant: Default::default(),
            in_at_lo: Default::default(),
            in_gradient_x: Default::default(),
            in_gradient_y: Default::default(),
            in_gradient_z: Default::default(),
            in_low: Default::default(),
            in_high: Default::default(),
            out_valid: Default::default(),
            out_tag: Default::default(),
            out_mask: Default::default(),
            out_at_lo: Default::default(),
            axis: std::array::from_fn(|i| AxisStep::with_bits(bits[i], shift)),
            mask_q: Default::default(),
            value_q: Default::default(),
            tag: Default::default(),
            valid: Default::default(),
        }
    }
}

impl<const V: usize> Logic for CellClassifier<V> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, mask_q);
        clock!(self, clock, tag, valid);
        self.tag.advance.next = self.advance.val();
        self.tag.d.next = self.in_tag.val();
        self.out_tag.next = self.tag.q.val();
        self.valid.reset.next = self.reset.val();
        self.valid.advance.next = self.advance.val();
        self.valid.d.next = self.in_valid.val();
        self.out_valid.next = self.valid.q.val();
        for i in 0..AXES {
            self.axis[i].clock.next = self.clock.val();
            self.axis[i].advance.next = self.advance.val();
            self.axis[i].level.next = self.in_level.val();
            self.axis[i].descend.next = self.in_descend.val();
            self.axis[i].octant.next = self.in_octant.val();
            self.axis[i].at_lo.next = self.in_at_lo[i].val();
            self.axis[i].gradient_x.next = self.in_gradient_x[i].val();
            self.axis[i].gradient_y.next = self.in_gradient_y[i].val();
            self.axis[i].gradient_z.next = self.in_gradient_z[i].val();
            self.axis[i].low.next = self.in_low[i].val();
            self.axis[i].high.next = self.in_high[i].val();
            self.value_q[i].clock.next = self.clock.val();
            self.value_q[i].advance.next = self.advance.val();
            self.value_q[i].d.next = self.axis[i].value.val();
            self.out_at_lo[i].next = self.value_q[i].q.val();
        }
        if self.advance.val() {
            self.mask_q.d.next = self.axis[0].mask.val()
                & self.axis[1].mask.val()
                & self.axis[2].mask.val()
                & self.axis[3].mask.val()
                & self.axis[4].mask.val()
                & self.axis[5].mask.val()
                & self.axis[6].mask.val()
                & self.axis[7].mask.val()
                & self.axis[8].mask.val()
                & self.axis[9].mask.val()
                & self.axis[10].mask.val()
                & self.axis[11].mask.val()
                & self.axis[12].mask.val();
        }
        self.out_mask.next = self.mask_q.q.val();
    }
}
