//! The emitted cone-of-normals unit ([`crate::bezier::cone_unit`]): its
//! name, port meanings and timing, at the widths it is built for.

use super::{emit, EmitError, EmittedDesign, UnitDescription};
pub use crate::bezier::cone_unit::CONE_UNIT_WIDTHS;
use crate::bezier::cone_unit::{
    cone_value_bits, eye_bits, ConeUnit, CONE_TAG_BITS, CONE_UNIT_LATENCY,
};
use crate::bezier::patch_tessellator::net_bits;
use rust_hdl::prelude::*;
use tritri_geom::bezier::cone_fixed::{EYE_EXTRA_BITS, THRESHOLD_BITS, THRESHOLD_FRACTION_BITS};

/// `tritri_cone_unit_w<W>`.
pub fn cone_unit_name(w: usize) -> String {
    format!("tritri_cone_unit_w{w}")
}

pub fn cone_unit(w: usize) -> UnitDescription {
    let f = THRESHOLD_FRACTION_BITS;
    UnitDescription::new(
        &cone_unit_name(w),
        "The Bezier system's cone-of-normals test: one patch and eye point a clock, the patch back-facing (culled), \
         front-facing, or possibly holding a silhouette, exactly as tritri_geom::bezier::cone_fixed::facing decides it.",
    )
    .detail(&format!(
        "Back-facing when every control point c, with d = c - e, has a.d > 0 and (a.d)^2 2^{f} > S |a|^2 |d|^2 (the \
         angle between the cone's axis a and d is below 90 degrees less the cone's half-angle); front-facing is the \
         mirror, a.d < 0. The patch lies in the hull of its control points, so the answers are guarantees. The host \
         rounds the axis to 16 bits and widens the threshold S = sin^2(alpha) 2^{f} by the rounding (rounded up), so \
         the integer cone holds the f64 cone."
    ))
    .detail(&format!(
        "All sixteen control points side by side, {}-bit values throughout (nothing wraps): 132 multiplications.",
        cone_value_bits(w)
    ))
    .parameter("W", &format!("{w}: bits of a control point's coordinate, two's complement"))
    .pipelined_control_ports()
    .port("in_valid", "A patch and eye are on the inputs this cycle.")
    .port("in_tag", &format!("{CONE_TAG_BITS}-bit tag, returned as out_tag."))
    .port("in_net", &format!("The 16 control points: coordinate a of the point in row r, column c at bits [(3 (4 r + c) + a) {w} +: {w}] ({} bits).", net_bits(w)))
    .port("in_eye", &format!("The eye on the net's grid, {} bits a coordinate: coordinate k at bits [k {} +: {}] ({} bits).", w + EYE_EXTRA_BITS, w + EYE_EXTRA_BITS, w + EYE_EXTRA_BITS, eye_bits(w)))
    .port("in_axis", "The cone's axis, 16-bit two's complement components (x at bits [15:0]), about 2^14 long.")
    .port("in_threshold", &format!("S, unsigned ({THRESHOLD_BITS} bits); 2^{f} + 1 for a cone that decides nothing."))
    .port("out_valid", &format!("The class of the patch that entered {CONE_UNIT_LATENCY} clocks earlier is on out_class."))
    .port("out_tag", "Its tag.")
    .port("out_class", "0: front-facing, 1: back-facing (culled), 2: may hold a silhouette.")
    .latency(CONE_UNIT_LATENCY as u64)
    .throughput("one patch and eye per clock while advance is high.")
}

pub fn emit_cone_unit(w: usize) -> Result<EmittedDesign, EmitError> {
    fn one<const W: usize, const NET: usize, const EYE: usize>() -> Result<EmittedDesign, EmitError>
    {
        let mut uut = ConeUnit::<W, NET, EYE>::default();
        uut.connect_all();
        emit(&crate::unit::RawDesign::of(&uut), &cone_unit(W))
    }
    crate::with_cone_unit!(w, one())
        .unwrap_or_else(|| panic!("the cone unit is built for W in {CONE_UNIT_WIDTHS:?}, not {w}"))
}
