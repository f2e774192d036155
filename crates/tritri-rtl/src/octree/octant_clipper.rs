//! The octree engine's clipping unit (`octree_engine.txt`, table 1): one
//! octant per clock against an axis-aligned box of voxels, out as inside,
//! outside or crossing (`tritri_geom::octree::clip::classify`). The box is
//! half-open, `lo <= v < hi`, clamped by the host into `[0, 2^level]`
//! (which changes no octant's class). Two stages: the octant's upper
//! corner, then the six comparisons of each kind.

use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Classes on `out_class`.
pub const CLASS_OUTSIDE: u64 = 0;
pub const CLASS_INSIDE: u64 = 1;
pub const CLASS_CROSSING: u64 = 2;

/// Clock edges from an octant in to its class out.
pub const CLIPPER_LATENCY: usize = 2;

#[derive(LogicBlock, Default)]
pub struct OctantClipper {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    // The box, held while octants flow.
    pub box_lo_x: Signal<In, Bits<11>>,
    pub box_lo_y: Signal<In, Bits<11>>,
    pub box_lo_z: Signal<In, Bits<11>>,
    pub box_hi_x: Signal<In, Bits<11>>,
    pub box_hi_y: Signal<In, Bits<11>>,
    pub box_hi_z: Signal<In, Bits<11>>,
    pub in_valid: Signal<In, Bit>,
    pub in_x: Signal<In, Bits<11>>,
    pub in_y: Signal<In, Bits<11>>,
    pub in_z: Signal<In, Bits<11>>,
    /// The octant's side is `2^in_level` voxels (0 to 10).
    pub in_level: Signal<In, Bits<4>>,
    pub out_valid: Signal<Out, Bit>,
    /// 0 outside, 1 inside, 2 crossing.
    pub out_class: Signal<Out, Bits<2>>,
    valid_1: DFF<Bit>,
    lo_x: DFF<Bits<12>>,
    lo_y: DFF<Bits<12>>,
    lo_z: DFF<Bits<12>>,
    hi_x: DFF<Bits<12>>,
    hi_y: DFF<Bits<12>>,
    hi_z: DFF<Bits<12>>,
    valid_2: DFF<Bit>,
    class_2: DFF<Bits<2>>,
    size: Signal<Local, Bits<12>>,
    apart: Signal<Local, Bit>,
    within: Signal<Local, Bit>,
}

impl crate::unit::Unit for OctantClipper {
    const LATENCY: Option<usize> = Some(CLIPPER_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self, units, valid_1, lo_x, lo_y, lo_z, hi_x, hi_y, hi_z, valid_2, class_2
        );
    }
}

impl Logic for OctantClipper {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, valid_1, lo_x, lo_y, lo_z, hi_x, hi_y, hi_z, valid_2, class_2);
        // Stage 1: the octant's corners.
        self.size.next = bits::<12>(1) << self.in_level.val();
        self.valid_1.d.next = self.in_valid.val();
        self.lo_x.d.next = bit_cast::<12, 11>(self.in_x.val());
        self.lo_y.d.next = bit_cast::<12, 11>(self.in_y.val());
        self.lo_z.d.next = bit_cast::<12, 11>(self.in_z.val());
        self.hi_x.d.next = bit_cast::<12, 11>(self.in_x.val()) + self.size.val();
        self.hi_y.d.next = bit_cast::<12, 11>(self.in_y.val()) + self.size.val();
        self.hi_z.d.next = bit_cast::<12, 11>(self.in_z.val()) + self.size.val();
        // Stage 2: apart on some axis, or within on every axis.
        self.apart.next = (self.hi_x.q.val() <= bit_cast::<12, 11>(self.box_lo_x.val()))
            | (self.lo_x.q.val() >= bit_cast::<12, 11>(self.box_hi_x.val()))
            | (self.hi_y.q.val() <= bit_cast::<12, 11>(self.box_lo_y.val()))
            | (self.lo_y.q.val() >= bit_cast::<12, 11>(self.box_hi_y.val()))
            | (self.hi_z.q.val() <= bit_cast::<12, 11>(self.box_lo_z.val()))
            | (self.lo_z.q.val() >= bit_cast::<12, 11>(self.box_hi_z.val()));
        self.within.next = (bit_cast::<12, 11>(self.box_lo_x.val()) <= self.lo_x.q.val())
            & (self.hi_x.q.val() <= bit_cast::<12, 11>(self.box_hi_x.val()))
            & (bit_cast::<12, 11>(self.box_lo_y.val()) <= self.lo_y.q.val())
            & (self.hi_y.q.val() <= bit_cast::<12, 11>(self.box_hi_y.val()))
            & (bit_cast::<12, 11>(self.box_lo_z.val()) <= self.lo_z.q.val())
            & (self.hi_z.q.val() <= bit_cast::<12, 11>(self.box_hi_z.val()));
        self.valid_2.d.next = self.valid_1.q.val();
        if self.apart.val() {
            self.class_2.d.next = 0.into();
        } else if self.within.val() {
            self.class_2.d.next = 1.into();
        } else {
            self.class_2.d.next = 2.into();
        }
        self.out_valid.next = self.valid_2.q.val();
        self.out_class.next = self.class_2.q.val();
        if self.reset.val() {
            self.valid_1.d.next = false;
            self.valid_2.d.next = false;
        }
    }
}
