//! Everything computed once per triangle, before pairs are formed: the
//! normal (thesis steps (1)/(3)), the signs of its components, whether the
//! triangle is degenerate (normal zero), the dominant axis of its normal and
//! the ends of the segment a degenerate triangle spans, and the bit length
//! of its edges' sum of magnitudes for the certificates. The vertices travel
//! alongside so that the outputs describe one triangle.
//!
//! Software models: `tritri_geom::fixed_point::cross` (normal), `shape`
//! (degenerate flag and segment ends) and `dominant_normal_axis`.

use super::dominant_axis::{DominantAxis, DOMINANT_AXIS_LATENCY};
use super::normal::{NormalUnit, EDGES_BITS_LATENCY, NORMAL_LATENCY};
use super::segment_ends::{SegmentEnds, SEGMENT_ENDS_LATENCY};
use crate::arith::delay_line::DelayLine;
use crate::arith::sign::{SignOf, SIGN_LATENCY};
use rust_hdl::prelude::*;

/// Clock edges from vertices to the triangle's record.
pub const FRONT_END_LATENCY: usize = NORMAL_LATENCY + DOMINANT_AXIS_LATENCY;

// The normal's signs come one stage after the normal, the axis later.
const _: () = assert!(SIGN_LATENCY < DOMINANT_AXIS_LATENCY);
const _: () = assert!(SEGMENT_ENDS_LATENCY < FRONT_END_LATENCY);

#[derive(LogicBlock, Default)]
pub struct TriangleFrontEnd<const W: usize, const D: usize, const C: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub vertices_in: [Signal<In, Bits<W>>; 9],
    // The record, FRONT_END_LATENCY enabled edges later:
    pub vertices: [Signal<Out, Bits<W>>; 9],
    pub normal: [Signal<Out, Bits<C>>; 3],
    pub normal_negative: [Signal<Out, Bit>; 3],
    pub normal_zero: [Signal<Out, Bit>; 3],
    /// The normal is zero: three collinear vertices.
    pub degenerate: Signal<Out, Bit>,
    pub dominant_axis: Signal<Out, Bits<2>>,
    pub segment_low: Signal<Out, Bits<2>>,
    pub segment_high: Signal<Out, Bits<2>>,
    /// `ke = bitlen(|q - p|_1 + |r - p|_1)`, the certificates'
    /// (`tritri_geom::certificate`).
    pub edges_bits: Signal<Out, Bits<8>>,
    normal_unit: NormalUnit<W, D, C>,
    normal_sign: [SignOf<C>; 3],
    axis: DominantAxis<C>,
    ends: SegmentEnds<W>,
    vertex_delay: [DelayLine<Bits<W>, FRONT_END_LATENCY>; 9],
    normal_delay: [DelayLine<Bits<C>, DOMINANT_AXIS_LATENCY>; 3],
    normal_negative_delay: [DelayLine<Bit, { DOMINANT_AXIS_LATENCY - SIGN_LATENCY }>; 3],
    normal_zero_delay: [DelayLine<Bit, { DOMINANT_AXIS_LATENCY - SIGN_LATENCY }>; 3],
    segment_low_delay: DelayLine<Bits<2>, { FRONT_END_LATENCY - SEGMENT_ENDS_LATENCY }>,
    segment_high_delay: DelayLine<Bits<2>, { FRONT_END_LATENCY - SEGMENT_ENDS_LATENCY }>,
    edges_bits_delay: DelayLine<Bits<8>, { FRONT_END_LATENCY - EDGES_BITS_LATENCY }>,
}

impl<const W: usize, const D: usize, const C: usize> crate::unit::Unit
    for TriangleFrontEnd<W, D, C>
{
    const LATENCY: Option<usize> = Some(FRONT_END_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            normal_unit,
            normal_sign,
            axis,
            ends,
            vertex_delay,
            normal_delay,
            normal_negative_delay,
            normal_zero_delay,
            segment_low_delay,
            segment_high_delay,
            edges_bits_delay
        );
    }
}

impl<const W: usize, const D: usize, const C: usize> Logic for TriangleFrontEnd<W, D, C> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            normal_unit,
            axis,
            ends,
            segment_low_delay,
            segment_high_delay,
            edges_bits_delay
        );
        self.normal_unit.advance.next = self.advance.val();
        self.axis.advance.next = self.advance.val();
        self.ends.advance.next = self.advance.val();
        self.segment_low_delay.advance.next = self.advance.val();
        self.segment_high_delay.advance.next = self.advance.val();
        self.edges_bits_delay.advance.next = self.advance.val();
        self.edges_bits_delay.d.next = self.normal_unit.edges_bits.val();
        self.edges_bits.next = self.edges_bits_delay.q.val();
        for i in 0..9 {
            self.vertex_delay[i].clock.next = self.clock.val();
            self.vertex_delay[i].advance.next = self.advance.val();
            self.normal_unit.vertices[i].next = self.vertices_in[i].val();
            self.ends.vertices[i].next = self.vertices_in[i].val();
            self.vertex_delay[i].d.next = self.vertices_in[i].val();
            self.vertices[i].next = self.vertex_delay[i].q.val();
        }
        for k in 0..3 {
            self.normal_sign[k].clock.next = self.clock.val();
            self.normal_sign[k].advance.next = self.advance.val();
            self.normal_delay[k].clock.next = self.clock.val();
            self.normal_delay[k].advance.next = self.advance.val();
            self.normal_negative_delay[k].clock.next = self.clock.val();
            self.normal_negative_delay[k].advance.next = self.advance.val();
            self.normal_zero_delay[k].clock.next = self.clock.val();
            self.normal_zero_delay[k].advance.next = self.advance.val();
            self.normal_sign[k].value.next = self.normal_unit.normal[k].val();
            self.axis.normal[k].next = self.normal_unit.normal[k].val();
            self.axis.negated[k].next = self.normal_unit.negated_normal[k].val();
            self.normal_delay[k].d.next = self.normal_unit.normal[k].val();
            self.normal_negative_delay[k].d.next = self.normal_sign[k].negative.val();
            self.normal_zero_delay[k].d.next = self.normal_sign[k].zero.val();
            self.normal[k].next = self.normal_delay[k].q.val();
            self.normal_negative[k].next = self.normal_negative_delay[k].q.val();
            self.normal_zero[k].next = self.normal_zero_delay[k].q.val();
        }
        self.degenerate.next = self.normal_zero_delay[0].q.val()
            && self.normal_zero_delay[1].q.val()
            && self.normal_zero_delay[2].q.val();
        self.dominant_axis.next = self.axis.axis.val();
        self.segment_low_delay.d.next = self.ends.low.val();
        self.segment_high_delay.d.next = self.ends.high.val();
        self.segment_low.next = self.segment_low_delay.q.val();
        self.segment_high.next = self.segment_high_delay.q.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::arith::convert::to_i128;
    use crate::pipeline::triangle_front_end::{TriangleFrontEnd, FRONT_END_LATENCY};
    use crate::pipeline::unit_vectors::{
        edges_bits, lexicographic_ends, normal, set_vertices, triangles_and_degenerate_ones,
    };
    use crate::sim_drive::assert_stream_matches;
    use rust_hdl::prelude::*;
    use tritri_geom::fixed_point::FixedPoint;
    use tritri_geom::kernel::ExactKernel;

    /// The front end: the vertices, the normal and its signs, the degenerate
    /// flag, the dominant axis, the segment ends and the edges' bit length of
    /// each triangle, all `FRONT_END_LATENCY` clocks later.
    #[test]
    fn front_end_describes_each_triangle() {
        type Description = (
            [i128; 9],
            [i128; 3],
            [(bool, bool); 3],
            bool,
            usize,
            (usize, usize),
            u64,
        );
        let mut uut = TriangleFrontEnd::<24, 25, 49>::default();
        uut.connect_all();
        uut.advance.next = true;
        assert_stream_matches(
            &mut uut,
            |u| &mut u.clock,
            &triangles_and_degenerate_ones(11),
            FRONT_END_LATENCY,
            |u, t| set_vertices(&mut u.vertices_in, t),
            |u| -> Description {
                (
                    u.vertices.each_ref().map(|v| to_i128(v.val())),
                    u.normal.each_ref().map(|n| to_i128(n.val())),
                    std::array::from_fn(|k| (u.normal_negative[k].val(), u.normal_zero[k].val())),
                    u.degenerate.val(),
                    u.dominant_axis.val().to_u64() as usize,
                    (
                        u.segment_low.val().to_u64() as usize,
                        u.segment_high.val().to_u64() as usize,
                    ),
                    u.edges_bits.val().to_u64(),
                )
            },
            |t| -> Description {
                let n = normal(t);
                (
                    std::array::from_fn(|k| t[k / 3][k % 3] as i128),
                    n,
                    n.map(|c| (c < 0, c == 0)),
                    n == [0, 0, 0],
                    FixedPoint::dominant_normal_axis(t[0], t[1], t[2]),
                    lexicographic_ends(t),
                    edges_bits(t),
                )
            },
        );
    }
}
