//! Orientation determinant `[a,b,c,d] = (d-a)·((b-a)×(c-a))` of four
//! W-bit points, exact in 3W+2 bits, reduced to its sign, with a
//! certificate: whether the sign holds when every coordinate moves by half
//! a grid step.
//!
//! Thesis, step (7) (interval overlap test, figure 3.8) and the `orient3d`
//! predicate of `tritri_geom::fixed_point::orient3d_value`. The pipeline's
//! two units compute step (7)'s determinants, or two of the
//! segment-triangle case's three (the third follows from their values,
//! `super::third_determinant`), or the degenerate pair's `[a,b,c,d]`
//! (unit 0); the top multiplexes their inputs.
//!
//! Software model: `tritri_geom::certificate::orient3d_certified`.
//!
//! Stages: differences (1), cross product while `d-a` waits in a delay
//! line, dot product, sign and certificate (1). The certificate
//! (`tritri_geom::certificate::orient3d_certified`) compares the
//! determinant with its threshold, computed beside the dot product from
//! the operands the dot product takes (`d - a` and the cross product) and
//! the edges' `ke`.

use crate::arith::certificate::{
    CertainSign, CertificateThreshold, EdgesBitLength, NormalPart, CERTAIN_SIGN_LATENCY,
    CERTIFICATE_THRESHOLD_LATENCY, EDGES_BIT_LENGTH_LATENCY, NORMAL_PART_DELAY,
    NORMAL_PART_LATENCY,
};
use crate::arith::cross_product::{CrossProduct, CROSS_PRODUCT_LATENCY};
use crate::arith::delay_line::DelayLine;
use crate::arith::dot_product::{DotProduct, DOT_PRODUCT_LATENCY};
use crate::arith::subtractor::{
    TwoWaySubtractor, VectorMagnitude, VectorSubtractor, SUBTRACTOR_LATENCY,
};
use rust_hdl::prelude::*;

/// Clock edges from the four points to the sign and certificate.
pub const CERTIFIED_ORIENT3D_LATENCY: usize =
    SUBTRACTOR_LATENCY + CROSS_PRODUCT_LATENCY + DOT_PRODUCT_LATENCY + CERTAIN_SIGN_LATENCY;
/// Clock edges from the four points to [`CertifiedOrient3d::value`].
pub const ORIENT3D_VALUE_LATENCY: usize = CERTIFIED_ORIENT3D_LATENCY - CERTAIN_SIGN_LATENCY;

/// The threshold, from `d - a` and the cross product as the dot product
/// takes them, arrives with the determinant.
const _: () = assert!(CERTIFICATE_THRESHOLD_LATENCY == DOT_PRODUCT_LATENCY);
/// The edges' `ke` arrives with the cross product.
const _: () = assert!(EDGES_BIT_LENGTH_LATENCY == CROSS_PRODUCT_LATENCY);
/// The normal's part, from the cross product as the threshold takes the
/// offset, arrives as the threshold adds it.
const _: () = assert!(NORMAL_PART_LATENCY == NORMAL_PART_DELAY);

#[derive(LogicBlock, Default)]
pub struct CertifiedOrient3d<const W: usize, const D: usize, const C: usize, const O: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    pub a: [Signal<In, Bits<W>>; 3],
    pub b: [Signal<In, Bits<W>>; 3],
    pub c: [Signal<In, Bits<W>>; 3],
    pub d: [Signal<In, Bits<W>>; 3],
    /// `[a,b,c,d] < 0`, `CERTIFIED_ORIENT3D_LATENCY` enabled edges later.
    pub negative: Signal<Out, Bit>,
    /// `[a,b,c,d] == 0`.
    pub zero: Signal<Out, Bit>,
    /// The sign holds for every move of the points by half a grid step (two
    /// clocks after the sign: `CERTIFICATE_LATENCY`,
    /// `crate::arith::certificate`).
    pub certain: Signal<Out, Bit>,
    /// `[a,b,c,d]` itself, `ORIENT3D_VALUE_LATENCY` edges after the points.
    pub value: Signal<Out, Bits<O>>,
    /// The edges of the normal, each also negated for its magnitudes in
    /// `edges_bits`.
    edge_ab: TwoWaySubtractor<W, D>,
    edge_ac: TwoWaySubtractor<W, D>,
    edge_ad: VectorSubtractor<W, D>,
    normal: CrossProduct<D, C>,
    edge_ad_delay_0: DelayLine<Bits<D>, { CROSS_PRODUCT_LATENCY - SUBTRACTOR_LATENCY }>,
    edge_ad_delay_1: DelayLine<Bits<D>, { CROSS_PRODUCT_LATENCY - SUBTRACTOR_LATENCY }>,
    edge_ad_delay_2: DelayLine<Bits<D>, { CROSS_PRODUCT_LATENCY - SUBTRACTOR_LATENCY }>,
    /// `d - a` and `|d - a|` (for the threshold), with the normal.
    edge_ad_last: VectorMagnitude<D>,
    determinant: DotProduct<D, C, O>,
    /// The certificate's threshold: `ke` of the edges `b - a`, `c - a`,
    /// then the threshold from `d - a` and the normal's part.
    edges_bits: EdgesBitLength<D>,
    normal_part: NormalPart<C, O>,
    threshold: CertificateThreshold<D, C, O>,
    sign: CertainSign<O>,
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> crate::unit::Unit
    for CertifiedOrient3d<W, D, C, O>
{
    const LATENCY: Option<usize> = Some(CERTIFIED_ORIENT3D_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            edge_ab,
            edge_ac,
            edge_ad,
            normal,
            edge_ad_delay_0,
            edge_ad_delay_1,
            edge_ad_delay_2,
            edge_ad_last,
            determinant,
            edges_bits,
            normal_part,
            threshold,
            sign
        );
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> Logic
    for CertifiedOrient3d<W, D, C, O>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            edge_ab,
            edge_ac,
            edge_ad,
            normal,
            edge_ad_delay_0,
            edge_ad_delay_1,
            edge_ad_delay_2,
            edge_ad_last,
            determinant,
            sign,
            edges_bits,
            normal_part,
            threshold
        );
        self.edge_ab.advance.next = self.advance.val();
        self.edge_ac.advance.next = self.advance.val();
        self.edge_ad.advance.next = self.advance.val();
        self.normal.advance.next = self.advance.val();
        self.edge_ad_delay_0.advance.next = self.advance.val();
        self.edge_ad_delay_1.advance.next = self.advance.val();
        self.edge_ad_delay_2.advance.next = self.advance.val();
        self.edge_ad_last.advance.next = self.advance.val();
        self.determinant.advance.next = self.advance.val();
        self.sign.advance.next = self.advance.val();
        self.edges_bits.advance.next = self.advance.val();
        self.normal_part.advance.next = self.advance.val();
        self.threshold.advance.next = self.advance.val();
        for i in 0..3 {
            self.edge_ab.a[i].next = self.b[i].val();
            self.edge_ab.b[i].next = self.a[i].val();
            self.edge_ac.a[i].next = self.c[i].val();
            self.edge_ac.b[i].next = self.a[i].val();
            self.edge_ad.a[i].next = self.d[i].val();
            self.edge_ad.b[i].next = self.a[i].val();
            self.normal.u[i].next = self.edge_ab.difference[i].val();
            self.normal.v[i].next = self.edge_ac.difference[i].val();
            self.determinant.v[i].next = self.normal.product[i].val();
        }
        for i in 0..3 {
            self.edges_bits.a[i].next = self.edge_ab.difference[i].val();
            self.edges_bits.b[i].next = self.edge_ac.difference[i].val();
            self.edges_bits.a_negated[i].next = self.edge_ab.negated[i].val();
            self.edges_bits.b_negated[i].next = self.edge_ac.negated[i].val();
            self.normal_part.normal[i].next = self.normal.product[i].val();
        }
        self.threshold.edges_bits.next = self.edges_bits.bits.val();
        self.threshold.normal_part.next = self.normal_part.part.val();
        self.edge_ad_last.v[0].next = self.edge_ad_delay_0.q.val();
        self.edge_ad_last.v[1].next = self.edge_ad_delay_1.q.val();
        self.edge_ad_last.v[2].next = self.edge_ad_delay_2.q.val();
        for i in 0..3 {
            self.threshold.offset_magnitude[i].next = self.edge_ad_last.magnitude[i].val();
            self.determinant.u[i].next = self.edge_ad_last.value[i].val();
        }
        self.edge_ad_delay_0.d.next = self.edge_ad.difference[0].val();
        self.edge_ad_delay_1.d.next = self.edge_ad.difference[1].val();
        self.edge_ad_delay_2.d.next = self.edge_ad.difference[2].val();
        self.sign.value.next = self.determinant.product.val();
        self.sign.value_zero_parts.next = self.determinant.zero_parts.val();
        self.value.next = self.determinant.product.val();
        self.sign.threshold.next = self.threshold.threshold.val();
        self.negative.next = self.sign.negative.val();
        self.zero.next = self.sign.zero.val();
        self.certain.next = self.sign.certain.val();
    }
}

#[cfg(test)]
mod tests {
    use crate::arith::certificate::{CERTAIN_SIGN_LATENCY, CERTIFICATE_LATENCY};
    use crate::arith::convert::from_i128;
    use crate::pipeline::certified_orient3d::{CertifiedOrient3d, CERTIFIED_ORIENT3D_LATENCY};
    use crate::pipeline::unit_vectors::{point, LIMIT, VECTORS};
    use crate::sim_drive::assert_stream_matches;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rust_hdl::prelude::*;
    use tritri_geom::certificate::orient3d_certified;
    use tritri_geom::fixed_point::FixedPoint3;
    use tritri_geom::sign::Sign;

    #[test]
    fn certified_orient3d_is_the_models_sign_and_certificate() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let vectors: Vec<[FixedPoint3; 4]> = (0..VECTORS)
            .map(|k| {
                let [a, b, c] = [point(&mut rng, k), point(&mut rng, k), point(&mut rng, k)];
                // d on or next to the plane of a, b, c half the time.
                let d = if k % 2 == 0 {
                    std::array::from_fn(|i| (b[i] + rng.gen_range(-1..2)).clamp(-LIMIT, LIMIT - 1))
                } else {
                    point(&mut rng, k)
                };
                [a, b, c, d]
            })
            .collect();
        // The sign, then the certificate two clocks later (`CERTIFICATE_LATENCY`).
        for certificates in [false, true] {
            let mut uut = CertifiedOrient3d::<24, 25, 49, 74>::default();
            uut.connect_all();
            uut.advance.next = true;
            let shown = move |(negative, zero, certain): (bool, bool, bool)| {
                if certificates {
                    (false, false, certain)
                } else {
                    (negative, zero, false)
                }
            };
            assert_stream_matches(
                &mut uut,
                |u| &mut u.clock,
                &vectors,
                CERTIFIED_ORIENT3D_LATENCY
                    + usize::from(certificates) * (CERTIFICATE_LATENCY - CERTAIN_SIGN_LATENCY),
                |u, [a, b, c, d]| {
                    for k in 0..3 {
                        u.a[k].next = from_i128(a[k] as i128);
                        u.b[k].next = from_i128(b[k] as i128);
                        u.c[k].next = from_i128(c[k] as i128);
                        u.d[k].next = from_i128(d[k] as i128);
                    }
                },
                |u| shown((u.negative.val(), u.zero.val(), u.certain.val())),
                |[a, b, c, d]| {
                    let (sign, certain) = orient3d_certified(*a, *b, *c, *d);
                    shown((sign == Sign::Negative, sign == Sign::Zero, certain))
                },
            );
        }
    }
}
