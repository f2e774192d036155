//! Signs of the three vertices of one triangle against the plane of the
//! other: `orient3d(p, q, r, v) = (v - p) · N` for each vertex `v`.
//!
//! Thesis, steps (2) and (4) and figure 3.5 (the polygon/plane intersection
//! test unit: three vector subtractions, three dot products with the normal,
//! then the signs). The two instances run in parallel (thesis 3.4.1).
//! Software model: `plane_side` in devillers_guigue.rs; the certificates
//! are `tritri_geom::certificate::orient3d_certified` of each vertex: its
//! threshold from the normal's part (once for the three), the offset
//! `v - p` and the bit length of the plane's edges' `|e1|_1 + |e2|_1`
//! (computed once per triangle, with its normal), beside the dot products.

use crate::arith::certificate::{
    CertainSign, CertificateThreshold, NormalPart, CERTAIN_SIGN_LATENCY,
    CERTIFICATE_THRESHOLD_LATENCY, NORMAL_PART_DELAY, NORMAL_PART_LATENCY,
};
use crate::arith::delay_line::DelayLine;
use crate::arith::dot_product::{DotProduct, DOT_PRODUCT_LATENCY};
use crate::arith::register_copy::RegisterCopy;
use crate::arith::subtractor::{MagnitudeSubtractor, MAGNITUDE_SUBTRACTOR_LATENCY};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::DFF;

/// Clock edges from inputs to signs.
pub const PLANE_SIDE_LATENCY: usize =
    MAGNITUDE_SUBTRACTOR_LATENCY + DOT_PRODUCT_LATENCY + CERTAIN_SIGN_LATENCY;

/// The thresholds, from the offsets and the normal as the dot products
/// take them, arrive with the distances.
const _: () = assert!(CERTIFICATE_THRESHOLD_LATENCY == DOT_PRODUCT_LATENCY);

/// The normal's part, from the shared stage of the normal's delay and
/// then a copy, arrives as each threshold adds it.
const _: () = assert!(
    MAGNITUDE_SUBTRACTOR_LATENCY - 1 + NORMAL_PART_LATENCY + 1
        == MAGNITUDE_SUBTRACTOR_LATENCY + NORMAL_PART_DELAY
);

/// `all_zero`'s one register comes with the signs.
const _: () = assert!(CERTAIN_SIGN_LATENCY == 1);

#[derive(LogicBlock, Default)]
pub struct PlaneSide<const W: usize, const D: usize, const C: usize, const O: usize> {
    pub clock: Signal<In, Clock>,
    pub advance: Signal<In, Bit>,
    /// A vertex `p` of the plane's triangle.
    pub plane_point: [Signal<In, Bits<W>>; 3],
    /// The plane's triangle's normal `(q - p) × (r - p)`.
    pub plane_normal: [Signal<In, Bits<C>>; 3],
    /// `ke`, the bit length of `|e1|_1 + |e2|_1` of the plane's triangle's
    /// edges, with its normal.
    pub plane_edges_bits: Signal<In, Bits<8>>,
    /// The three vertices to classify.
    pub vertices: [Signal<In, Bits<W>>; 9],
    /// Vertex `i` is strictly below the plane (`PLANE_SIDE_LATENCY` later).
    pub negative: [Signal<Out, Bit>; 3],
    /// Vertex `i` is on the plane.
    pub zero: [Signal<Out, Bit>; 3],
    /// All three vertices are on the plane, with `zero`. (From the dot
    /// products' parts like `zero`, in a register of its own: the rare
    /// rule of the shared pipeline reads it and goes on to the hold
    /// forecast in the same clock. ANDed from the three signs' `zero`,
    /// the rule's path on ECP5 started at three registers spread over the
    /// plane side: 3.4 ns of routing to the rule, 130.8 MHz at W = 16.)
    pub all_zero: Signal<Out, Bit>,
    /// Vertex `i`'s sign holds for every move by half a grid step (two
    /// clocks after the sign: `CERTIFICATE_LATENCY`,
    /// `crate::arith::certificate`).
    pub certain: [Signal<Out, Bit>; 3],
    /// Vertex `i`'s value `(v - p) · N`, a stage before its sign
    /// (`PLANE_SIDE_LATENCY - CERTAIN_SIGN_LATENCY` edges after the inputs):
    /// the segment ends' values give the segment-triangle case's third
    /// determinant (`super::third_determinant`).
    pub distance: [Signal<Out, Bits<O>>; 3],
    // (rust-hdl's Verilog generator resolves one array index per name, so
    // units with array ports are separate fields rather than arrays.)
    offset_0: MagnitudeSubtractor<W, D>,
    offset_1: MagnitudeSubtractor<W, D>,
    offset_2: MagnitudeSubtractor<W, D>,
    /// The normal waits for the offsets: a stage shared, then a last
    /// stage for the dot products; the thresholds' part of it (once for
    /// the three) starts from the shared stage, and each threshold adds a
    /// copy of its own (`normal_part_copies[i]`), which sits beside it.
    /// (Each threshold summed the normal from the dot products' register,
    /// placed by the multipliers, 3.7 ns of routing to its first LUT: 12
    /// register inputs short of 150 MHz, ECP5, W = 16, P = 1 shared
    /// system, seed 3, 141.6 MHz; from nine copies of the normal, a later
    /// stage of the same sums, 8 of 11 at 144.1 MHz.)
    normal_early: [DelayLine<Bits<C>, { MAGNITUDE_SUBTRACTOR_LATENCY - 1 }>; 3],
    normal_for_products: [DelayLine<Bits<C>, 1>; 3],
    normal_part: NormalPart<C, O>,
    normal_part_copies: [RegisterCopy<Bits<O>>; 3],
    distance_0: DotProduct<D, C, O>,
    distance_1: DotProduct<D, C, O>,
    distance_2: DotProduct<D, C, O>,
    /// The certificate's threshold per vertex (`arith::certificate`), from
    /// the offset as the dot product takes it.
    edges_bits_delay: DelayLine<Bits<8>, MAGNITUDE_SUBTRACTOR_LATENCY>,
    threshold_0: CertificateThreshold<D, C, O>,
    threshold_1: CertificateThreshold<D, C, O>,
    threshold_2: CertificateThreshold<D, C, O>,
    sign: [CertainSign<O>; 3],
    all_zero_q: DFF<Bit>,
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> crate::unit::Unit
    for PlaneSide<W, D, C, O>
{
    const LATENCY: Option<usize> = Some(PLANE_SIDE_LATENCY);
    fn sub_units(&self, units: &mut crate::unit::UnitWalk) {
        crate::sub_units!(
            self,
            units,
            offset_0,
            offset_1,
            offset_2,
            normal_early,
            normal_for_products,
            normal_part,
            normal_part_copies,
            distance_0,
            distance_1,
            distance_2,
            edges_bits_delay,
            threshold_0,
            threshold_1,
            threshold_2,
            sign,
            all_zero_q
        );
    }
}

impl<const W: usize, const D: usize, const C: usize, const O: usize> Logic
    for PlaneSide<W, D, C, O>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            offset_0,
            offset_1,
            offset_2,
            distance_0,
            distance_1,
            distance_2,
            edges_bits_delay,
            normal_part,
            threshold_0,
            threshold_1,
            threshold_2
        );
        dff_setup!(self, clock, all_zero_q);
        self.offset_0.advance.next = self.advance.val();
        self.offset_1.advance.next = self.advance.val();
        self.offset_2.advance.next = self.advance.val();
        self.distance_0.advance.next = self.advance.val();
        self.distance_1.advance.next = self.advance.val();
        self.distance_2.advance.next = self.advance.val();
        self.edges_bits_delay.advance.next = self.advance.val();
        self.edges_bits_delay.d.next = self.plane_edges_bits.val();
        for k in 0..3 {
            self.normal_early[k].clock.next = self.clock.val();
            self.normal_early[k].advance.next = self.advance.val();
            self.normal_early[k].d.next = self.plane_normal[k].val();
            self.normal_for_products[k].clock.next = self.clock.val();
            self.normal_for_products[k].advance.next = self.advance.val();
            self.normal_for_products[k].d.next = self.normal_early[k].q.val();
            self.normal_part.normal[k].next = self.normal_early[k].q.val();
            self.sign[k].clock.next = self.clock.val();
            self.sign[k].advance.next = self.advance.val();
            self.offset_0.a[k].next = self.vertices[k].val();
            self.offset_1.a[k].next = self.vertices[3 + k].val();
            self.offset_2.a[k].next = self.vertices[6 + k].val();
            self.offset_0.b[k].next = self.plane_point[k].val();
            self.offset_1.b[k].next = self.plane_point[k].val();
            self.offset_2.b[k].next = self.plane_point[k].val();
            self.distance_0.u[k].next = self.offset_0.difference[k].val();
            self.distance_1.u[k].next = self.offset_1.difference[k].val();
            self.distance_2.u[k].next = self.offset_2.difference[k].val();
            self.distance_0.v[k].next = self.normal_for_products[k].q.val();
            self.distance_1.v[k].next = self.normal_for_products[k].q.val();
            self.distance_2.v[k].next = self.normal_for_products[k].q.val();
        }
        self.distance[0].next = self.distance_0.product.val();
        self.distance[1].next = self.distance_1.product.val();
        self.distance[2].next = self.distance_2.product.val();
        self.sign[0].value.next = self.distance_0.product.val();
        self.sign[1].value.next = self.distance_1.product.val();
        self.sign[2].value.next = self.distance_2.product.val();
        self.sign[0].value_zero_parts.next = self.distance_0.zero_parts.val();
        self.sign[1].value_zero_parts.next = self.distance_1.zero_parts.val();
        self.sign[2].value_zero_parts.next = self.distance_2.zero_parts.val();
        if self.advance.val() {
            self.all_zero_q.d.next = self.distance_0.zero_parts.val().all()
                && self.distance_1.zero_parts.val().all()
                && self.distance_2.zero_parts.val().all();
        }
        self.all_zero.next = self.all_zero_q.q.val();
        self.threshold_0.advance.next = self.advance.val();
        self.threshold_1.advance.next = self.advance.val();
        self.threshold_2.advance.next = self.advance.val();
        self.threshold_0.edges_bits.next = self.edges_bits_delay.q.val();
        self.threshold_1.edges_bits.next = self.edges_bits_delay.q.val();
        self.threshold_2.edges_bits.next = self.edges_bits_delay.q.val();
        for k in 0..3 {
            self.threshold_0.offset_magnitude[k].next = self.offset_0.magnitude[k].val();
            self.threshold_1.offset_magnitude[k].next = self.offset_1.magnitude[k].val();
            self.threshold_2.offset_magnitude[k].next = self.offset_2.magnitude[k].val();
        }
        self.normal_part.advance.next = self.advance.val();
        self.threshold_0.normal_part.next = self.normal_part_copies[0].q.val();
        self.threshold_1.normal_part.next = self.normal_part_copies[1].q.val();
        self.threshold_2.normal_part.next = self.normal_part_copies[2].q.val();
        // The copies have no enable: `advance` is folded into `d`.
        for i in 0..3 {
            self.normal_part_copies[i].clock.next = self.clock.val();
            self.normal_part_copies[i].d.next = self.normal_part_copies[i].q.val();
            if self.advance.val() {
                self.normal_part_copies[i].d.next = self.normal_part.part.val();
            }
        }
        self.sign[0].threshold.next = self.threshold_0.threshold.val();
        self.sign[1].threshold.next = self.threshold_1.threshold.val();
        self.sign[2].threshold.next = self.threshold_2.threshold.val();
        for v in 0..3 {
            self.negative[v].next = self.sign[v].negative.val();
            self.zero[v].next = self.sign[v].zero.val();
            self.certain[v].next = self.sign[v].certain.val();
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::arith::certificate::{CERTAIN_SIGN_LATENCY, CERTIFICATE_LATENCY};
    use crate::arith::convert::from_i128;
    use crate::pipeline::plane_side::{PlaneSide, PLANE_SIDE_LATENCY};
    use crate::pipeline::unit_vectors::{
        edges_bits, normal, point, set_vertices, triangles, LIMIT,
    };
    use crate::sim_drive::assert_stream_matches;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rust_hdl::prelude::*;
    use tritri_geom::certificate::orient3d_certified;
    use tritri_geom::fixed_point::{FixedPoint3, FixedTriangle};
    use tritri_geom::sign::Sign;

    /// The signs of three vertices against a plane and their certificates:
    /// `orient3d_certified(p, q, r, v)` for each vertex `v`.
    #[test]
    fn plane_side_signs_and_certificates() {
        let planes = triangles(5);
        let mut rng = ChaCha8Rng::seed_from_u64(6);
        let vectors: Vec<(FixedTriangle, FixedTriangle)> = planes
            .iter()
            .enumerate()
            .map(|(k, plane)| {
                // Vertices near the plane (small offsets from its points) as
                // well as anywhere, so that zero and uncertain signs occur.
                let near = |rng: &mut ChaCha8Rng| -> FixedPoint3 {
                    let p = plane[rng.gen_range(0..3)];
                    std::array::from_fn(|i| (p[i] + rng.gen_range(-2..3)).clamp(-LIMIT, LIMIT - 1))
                };
                let t = if k % 2 == 0 {
                    std::array::from_fn(|_| near(&mut rng))
                } else {
                    std::array::from_fn(|_| point(&mut rng, k))
                };
                (*plane, t)
            })
            .collect();
        // The signs, then the certificates two clocks later (`CERTIFICATE_LATENCY`).
        for certificates in [false, true] {
            let mut uut = PlaneSide::<24, 25, 49, 74>::default();
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
                PLANE_SIDE_LATENCY
                    + usize::from(certificates) * (CERTIFICATE_LATENCY - CERTAIN_SIGN_LATENCY),
                |u, (plane, t)| {
                    for k in 0..3 {
                        u.plane_point[k].next = from_i128(plane[0][k] as i128);
                    }
                    // The normal and edges' bit length arrive from the base polygon,
                    // computed by the normal unit (tested above).
                    for (k, n) in normal(plane).iter().enumerate() {
                        u.plane_normal[k].next = from_i128(*n);
                    }
                    u.plane_edges_bits.next = edges_bits(plane).into();
                    set_vertices(&mut u.vertices, t);
                },
                |u| {
                    std::array::from_fn::<_, 3, _>(|k| {
                        shown((u.negative[k].val(), u.zero[k].val(), u.certain[k].val()))
                    })
                },
                |(plane, t)| {
                    t.map(|v| {
                        let (sign, certain) = orient3d_certified(plane[0], plane[1], plane[2], v);
                        shown((sign == Sign::Negative, sign == Sign::Zero, certain))
                    })
                },
            );
        }
    }
}
