//! The classifier for entries at their cell's own corner, one per clock:
//! a triangle's thirteen test functions, set up with the cell's low corner
//! as the root, to the mask of the cell's children the triangle meets. It
//! decides as [`super::cell_classifier`] does on entries whose values are
//! zero and which do not descend (what the binning lanes send it), with
//! [`CornerStep`]s in place of axis steps: their comparisons are at the
//! gradient's width, not the values'.
//!
//! The functions come in the setup's layout ([`super::triangle_setup`]:
//! the axes, the plane, the edges), whose gradients are bounded by the
//! grid ([`corner_gradient_bits`]).

use super::cell_classifier::{function_bits, shift_bits, AXES, TAG_BITS};
use super::corner_step::{CornerStep, CORNER_STEP_LATENCY};
use crate::arith::delay_line::DelayLine;
use crate::arith::valid_line::ValidLine;
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from an entry to its mask: the steps, then the AND (the
/// cell classifier's latency).
pub const CORNER_CLASSIFIER_LATENCY: usize = CORNER_STEP_LATENCY + 1;

/// The width of each function's gradient sums (every sum of up to three
/// of its components), in the setup's layout, for `V`-bit values of
/// `G = (V - 6) / 3`-bit grids. Vertices differ by less than `2^G`, so
/// an edge's components are below `2^G` and the normal's below `2^(2G+1)`:
/// * an axis (a unit vector): sums 0 or 1, 4 bits;
/// * an edge (`e × u_k`): sums below `3 · 2^G`, `G + 3` signed bits;
/// * the plane: sums below `3 · 2^(2G+1)`, `2G + 4` signed bits.
pub fn corner_gradient_bits(v: usize) -> [usize; AXES] {
    let g = (v - 6) / 3;
    std::array::from_fn(|i| match i {
        0..=2 => 4,
        3 => 2 * g + 4,
        _ => g + 3,
    })
}

#[derive(LogicBlock)]
pub struct CornerClassifier<const V: usize> {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub advance: Signal<In, Bit>,
    pub in_valid: Signal<In, Bit>,
    pub in_tag: Signal<In, Bits<TAG_BITS>>,
    /// Level of the classified cell (>= 1: it has children; at most the
    /// grid's `G`, the root cube's).
    pub in_level: Signal<In, Bits<6>>,
    pub in_gradient_x: [Signal<In, Bits<V>>; AXES],
    pub in_gradient_y: [Signal<In, Bits<V>>; AXES],
    pub in_gradient_z: [Signal<In, Bits<V>>; AXES],
    /// The triangle's intervals, relative to the cell's low corner.
    pub in_low: [Signal<In, Bits<V>>; AXES],
    pub in_high: [Signal<In, Bits<V>>; AXES],
    pub out_valid: Signal<Out, Bit>,
    pub out_tag: Signal<Out, Bits<TAG_BITS>>,
    /// Bit `o`: the triangle meets child `o` of the classified cell.
    pub out_mask: Signal<Out, Bits<8>>,
    step: [CornerStep<V>; AXES],
    mask_q: DFF<Bits<8>>,
    tag: DelayLine<Bits<TAG_BITS>, CORNER_CLASSIFIER_LATENCY>,
    valid: ValidLine<CORNER_CLASSIFIER_LATENCY>,
}

impl<const V: usize> crate::unit::Unit for CornerClassifier<V> {
    const LATENCY: Option<usize> = Some(CORNER_CLASSIFIER_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(self, units, step, mask_q, tag, valid);
    }
}

impl<const V: usize> Default for CornerClassifier<V> {
    fn default() -> Self {
        let (bits, sums, shift) = (function_bits(V), corner_gradient_bits(V), shift_bits(V));
        CornerClassifier {
            clock: Default::default(),
            reset: Default::default(),
            advance: Default::default(),
            in_valid: Default::default(),
            in_tag: Default::default(),
            in_level: Default::default(),
            in_gradient_x: Default::default(),
            in_gradient_y: Default::default(),
            in_gradient_z: Default::default(),
            in_low: Default::default(),
            in_high: Default::default(),
            out_valid: Default::default(),
            out_tag: Default::default(),
            out_mask: Default::default(),
            step: std::array::from_fn(|i| CornerStep::new(bits[i], sums[i], shift)),
            mask_q: Default::default(),
            tag: Default::default(),
            valid: Default::default(),
        }
    }
}

impl<const V: usize> Logic for CornerClassifier<V> {
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
            self.step[i].clock.next = self.clock.val();
            self.step[i].advance.next = self.advance.val();
            self.step[i].level.next = self.in_level.val();
            self.step[i].gradient_x.next = self.in_gradient_x[i].val();
            self.step[i].gradient_y.next = self.in_gradient_y[i].val();
            self.step[i].gradient_z.next = self.in_gradient_z[i].val();
            self.step[i].low.next = self.in_low[i].val();
            self.step[i].high.next = self.in_high[i].val();
        }
        if self.advance.val() {
            self.mask_q.d.next = self.step[0].mask.val()
                & self.step[1].mask.val()
                & self.step[2].mask.val()
                & self.step[3].mask.val()
                & self.step[4].mask.val()
                & self.step[5].mask.val()
                & self.step[6].mask.val()
                & self.step[7].mask.val()
                & self.step[8].mask.val()
                & self.step[9].mask.val()
                & self.step[10].mask.val()
                & self.step[11].mask.val()
                & self.step[12].mask.val();
        }
        self.out_mask.next = self.mask_q.q.val();
    }
}

// The binning models charge the lanes the cell classifier's latency.
const _: () = assert!(CORNER_CLASSIFIER_LATENCY == super::cell_classifier::CELL_CLASSIFIER_LATENCY);

// The AND over the functions is written with literals.
const _: () = assert!(AXES == 13);
