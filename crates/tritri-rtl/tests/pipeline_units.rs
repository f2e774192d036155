//! The pipeline's geometric units alone, by direct drive against their
//! software models in tritri-geom, each with its latency constant asserted
//! (`sim_drive::assert_stream_matches`). W = 24 (D = 25, C = 49, O = 74).
//! The operand selection (`orient3d_operands`) and the decision, whose
//! model is the control flow of `fixed_point::intersects` itself, are
//! covered in context by the whole pipeline's co-simulations
//! (tritri-cosim).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rust_hdl::prelude::*;
use tritri_geom::certificate::{bit_length, l1, orient3d_certified};
use tritri_geom::devillers_guigue::{align_t1, align_t2, coplanar_triangles, hulls_intersect_2d};
use tritri_geom::fixed_point::{
    cross, dominant_axis, orient3d_value, FixedPoint, FixedPoint3, FixedTriangle,
};
use tritri_geom::kernel::ExactKernel;
use tritri_geom::sign::Sign;
use tritri_rtl::arith::certificate::{CERTAIN_SIGN_LATENCY, CERTIFICATE_LATENCY};
use tritri_rtl::arith::convert::{from_i128, to_i128, wrap_i128};
use tritri_rtl::pipeline::align_t1::{AlignT1, ALIGN_T1_LATENCY};
use tritri_rtl::pipeline::align_t2::{AlignT2, ALIGN_T2_LATENCY};
use tritri_rtl::pipeline::base_polygon::BasePolygon;
use tritri_rtl::pipeline::certified_orient3d::{CertifiedOrient3d, CERTIFIED_ORIENT3D_LATENCY};
use tritri_rtl::pipeline::coplanar_test::{CoplanarTest, COPLANAR_TEST_LATENCY};
use tritri_rtl::pipeline::degenerate_pair::{DegeneratePair, DEGENERATE_PAIR_LATENCY};
use tritri_rtl::pipeline::dominant_axis::{DominantAxis, DOMINANT_AXIS_LATENCY};
use tritri_rtl::pipeline::interval_overlap::{IntervalOverlap, INTERVAL_OVERLAP_LATENCY};
use tritri_rtl::pipeline::normal::{NormalUnit, EDGES_BITS_LATENCY, NORMAL_LATENCY};
use tritri_rtl::pipeline::plane_side::{PlaneSide, PLANE_SIDE_LATENCY};
use tritri_rtl::pipeline::segment_ends::{SegmentEnds, SEGMENT_ENDS_LATENCY};
use tritri_rtl::pipeline::shared_rare_cases::{
    SharedRareCases, COPLANAR_STEPS, SEGMENTS_STEPS, SHARED_RARE_CASES_LATENCY,
};
use tritri_rtl::pipeline::third_determinant::{
    EndsDifference, ThirdDeterminant, ENDS_DIFFERENCE_LATENCY, THIRD_DETERMINANT_LATENCY,
};
use tritri_rtl::pipeline::triangle_front_end::{TriangleFrontEnd, FRONT_END_LATENCY};
use tritri_rtl::sim_drive::{assert_stream_matches, clock_cycle, reset_one_clock};

const VECTORS: usize = 300;
const LIMIT: i64 = 1 << 23;

/// A random W = 24 point: uniform, at the ends of the range, or small.
fn point(rng: &mut ChaCha8Rng, kind: usize) -> FixedPoint3 {
    std::array::from_fn(|_| match kind % 3 {
        0 => rng.gen_range(-LIMIT..LIMIT),
        1 => {
            if rng.gen_bool(0.5) {
                -LIMIT
            } else {
                LIMIT - 1
            }
        }
        _ => rng.gen_range(-3..4),
    })
}

fn triangles(seed: u64) -> Vec<FixedTriangle> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..VECTORS)
        .map(|k| std::array::from_fn(|_| point(&mut rng, k)))
        .collect()
}

/// Triangles in one lattice plane `o + a u + b v` (small `a`, `b`), so that
/// pairs of them are exactly coplanar and often touch; a few degenerate.
fn coplanar_pairs(seed: u64) -> Vec<(FixedTriangle, FixedTriangle)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..VECTORS)
        .map(|_| {
            let o = point(&mut rng, 2);
            let span = 1 << rng.gen_range(0..18);
            let u: [i64; 3] = std::array::from_fn(|_| rng.gen_range(-span..=span));
            let v: [i64; 3] = std::array::from_fn(|_| rng.gen_range(-span..=span));
            let mut at = || {
                let (a, b) = (rng.gen_range(-4..5), rng.gen_range(-4..5));
                std::array::from_fn(|k| o[k] + a * u[k] + b * v[k])
            };
            ([at(), at(), at()], [at(), at(), at()])
        })
        .collect()
}

fn set_vertices<const W: usize>(signals: &mut [Signal<In, Bits<W>>; 9], t: &FixedTriangle) {
    for (k, s) in signals.iter_mut().enumerate() {
        s.next = from_i128(t[k / 3][k % 3] as i128);
    }
}

fn edges(t: &FixedTriangle) -> ([i64; 3], [i64; 3]) {
    let [p, q, r] = *t;
    (
        std::array::from_fn(|k| q[k] - p[k]),
        std::array::from_fn(|k| r[k] - p[k]),
    )
}

fn normal(t: &FixedTriangle) -> [i128; 3] {
    let (u, v) = edges(t);
    cross(u, v)
}

/// Indices of the lexicographically smallest and largest vertex, the first
/// on ties (as `devillers_guigue::shape` picks a degenerate triangle's ends).
fn lexicographic_ends(t: &FixedTriangle) -> (usize, usize) {
    let order = |i: usize, j: usize| FixedPoint::compare_lexicographic(t[i], t[j]);
    let low = (1..3).fold(0, |lo, i| if order(i, lo).is_lt() { i } else { lo });
    let high = (1..3).fold(0, |hi, i| if order(i, hi).is_gt() { i } else { hi });
    (low, high)
}

/// `ke = bitlen(|q - p|_1 + |r - p|_1)`, the certificates' of a triangle's
/// plane.
fn edges_bits(t: &FixedTriangle) -> u64 {
    let (u, v) = edges(t);
    bit_length(l1(u) + l1(v)) as u64
}

#[test]
fn normal_unit_gives_the_cross_product_its_negation_and_its_edges_bit_length() {
    let vectors = triangles(1);
    let mut uut = NormalUnit::<24, 25, 49>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &vectors,
        NORMAL_LATENCY,
        |u, t| set_vertices(&mut u.vertices, t),
        |u| {
            (
                u.normal.each_ref().map(|n| to_i128(n.val())),
                u.negated_normal.each_ref().map(|n| to_i128(n.val())),
            )
        },
        |t| {
            let n = normal(t);
            (n, n.map(|c| -c))
        },
    );
    let mut uut = NormalUnit::<24, 25, 49>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &vectors,
        EDGES_BITS_LATENCY,
        |u, t| set_vertices(&mut u.vertices, t),
        |u| u.edges_bits.val().to_u64(),
        edges_bits,
    );
}

#[test]
fn dominant_axis_is_the_largest_component_ties_low() {
    // Normals of random triangles, and ties: equal magnitudes of either sign.
    let mut normals: Vec<[i128; 3]> = triangles(2).iter().map(normal).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..100 {
        let m: i128 = rng.gen_range(0..1 << 40);
        let s = |rng: &mut ChaCha8Rng| if rng.gen_bool(0.5) { m } else { -m };
        normals.push([s(&mut rng), s(&mut rng), rng.gen_range(-m..=m)]);
        normals.push([rng.gen_range(-m..=m), s(&mut rng), s(&mut rng)]);
    }
    let mut uut = DominantAxis::<49>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &normals,
        DOMINANT_AXIS_LATENCY,
        |u, n| {
            for k in 0..3 {
                u.normal[k].next = from_i128(n[k]);
                u.negated[k].next = from_i128(-n[k]);
            }
        },
        |u| u.axis.val().to_u64() as usize,
        |n| dominant_axis(n.map(|c| c.unsigned_abs())),
    );
}

#[test]
fn segment_ends_are_the_lexicographic_extremes_first_index_on_ties() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    // Small coordinates: many equal coordinates and equal vertices.
    let vectors: Vec<FixedTriangle> = (0..VECTORS)
        .map(|_| std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-1..2))))
        .collect();
    let mut uut = SegmentEnds::<24>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &vectors,
        SEGMENT_ENDS_LATENCY,
        |u, t| set_vertices(&mut u.vertices, t),
        |u| {
            (
                u.low.val().to_u64() as usize,
                u.high.val().to_u64() as usize,
            )
        },
        lexicographic_ends,
    );
}

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

/// The segment-triangle case's third determinant: `s_b - s_a` of the
/// degenerate triangle's chosen ends, then `[a, b, r, p]`'s sign from it and
/// `[a, b, p, q]`, `[a, b, q, r]` (the identity in
/// `pipeline::third_determinant`), at W = 24's extremes where the 74-bit
/// arithmetic wraps.
#[test]
fn third_determinant_is_the_models_sign() {
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    // [p, q, r, a, b], and the pair's other triangle's vertices.
    let points: Vec<([FixedPoint3; 5], FixedTriangle)> = (0..VECTORS)
        .map(|k| {
            let pts: [FixedPoint3; 5] = std::array::from_fn(|_| point(&mut rng, k));
            (pts, std::array::from_fn(|_| point(&mut rng, k + 1)))
        })
        .collect();
    let vectors: Vec<_> = points
        .iter()
        .enumerate()
        .map(|(k, &([p, q, r, a, b], other))| {
            // The segment [a, b] among T1's or T2's vertices, its ends at
            // random indices; the other triangle's values are decoys.
            let t1_degenerate = k % 2 == 0;
            let (low, high) = (rng.gen_range(0..3usize), rng.gen_range(0..3usize));
            let mut segment = other;
            segment[low] = a;
            segment[high] = b;
            let side = |t: FixedTriangle| t.map(|v| orient3d_value(p, q, r, v));
            let ends = side(segment);
            let (t1, t2) = if t1_degenerate {
                (ends, side(other))
            } else {
                (side(other), ends)
            };
            // s_b - s_a may pass 74 bits (it is a sum of three orient3d
            // values); its residue is what the unit keeps.
            (
                t1_degenerate,
                low,
                high,
                t1,
                t2,
                wrap_i128(ends[high] - ends[low], 74),
            )
        })
        .collect();
    let mut ends = EndsDifference::<74>::default();
    ends.connect_all();
    ends.advance.next = true;
    assert_stream_matches(
        &mut ends,
        |u| &mut u.clock,
        &vectors,
        ENDS_DIFFERENCE_LATENCY,
        |u, (t1_degenerate, low, high, t1, t2, _)| {
            u.t1_degenerate.next = *t1_degenerate;
            for (segment_low, segment_high) in [
                (&mut u.t1_segment_low, &mut u.t1_segment_high),
                (&mut u.t2_segment_low, &mut u.t2_segment_high),
            ] {
                segment_low.next = (*low as u64).into();
                segment_high.next = (*high as u64).into();
            }
            for v in 0..3 {
                u.t1_distance[v].next = from_i128(t1[v]);
                u.t2_distance[v].next = from_i128(t2[v]);
            }
        },
        |u| to_i128(u.difference.val()),
        |(.., difference)| *difference,
    );
    let determinants: Vec<[i128; 4]> = points
        .iter()
        .map(|&([p, q, r, a, b], _)| {
            [
                wrap_i128(orient3d_value(p, q, r, b) - orient3d_value(p, q, r, a), 74),
                orient3d_value(a, b, p, q),
                orient3d_value(a, b, q, r),
                orient3d_value(a, b, r, p),
            ]
        })
        .collect();
    // Zero determinants too: the unit finds them from its operands.
    assert!(determinants.iter().any(|d| d[3] == 0));
    assert!(determinants.iter().any(|d| d[3] != 0));
    let mut third = ThirdDeterminant::<74>::default();
    third.connect_all();
    third.advance.next = true;
    assert_stream_matches(
        &mut third,
        |u| &mut u.clock,
        &determinants,
        THIRD_DETERMINANT_LATENCY,
        |u, [ends_difference, first, second, _]| {
            u.ends_difference.next = from_i128(*ends_difference);
            u.first.next = from_i128(*first);
            u.second.next = from_i128(*second);
        },
        |u| (u.negative.val(), u.zero.val()),
        |[.., third]| (*third < 0, *third == 0),
    );
}

/// Coplanar triangles (T1 proper) on T1's dominant projection:
/// `coplanar_triangles`.
#[test]
fn coplanar_test_is_the_closed_2d_test() {
    let vectors: Vec<(FixedTriangle, FixedTriangle)> = coplanar_pairs(8)
        .into_iter()
        .filter(|(t1, _)| normal(t1) != [0, 0, 0])
        .collect();
    let hits = vectors
        .iter()
        .filter(|(t1, t2)| coplanar_triangles::<FixedPoint>(*t1, *t2))
        .count();
    assert!(
        hits > vectors.len() / 5 && hits < vectors.len() * 4 / 5,
        "{hits} hits of {}",
        vectors.len()
    );
    let mut uut = CoplanarTest::<24, 25, 49>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &vectors,
        COPLANAR_TEST_LATENCY,
        |u, (t1, t2)| {
            set_vertices(&mut u.t1_vertices, t1);
            set_vertices(&mut u.t2_vertices, t2);
            let (n1, n2) = (normal(t1), normal(t2));
            u.axis.next = (dominant_axis(n1.map(|c| c.unsigned_abs())) as u64).into();
            for k in 0..3 {
                u.t1_normal_negative[k].next = n1[k] < 0;
                u.t1_normal_zero[k].next = n1[k] == 0;
                u.t2_normal_negative[k].next = n2[k] < 0;
                u.t2_normal_zero[k].next = n2[k] == 0;
            }
        },
        |u| u.hit.val(),
        |(t1, t2)| coplanar_triangles::<FixedPoint>(*t1, *t2),
    );
}

/// Pairs of degenerate triangles (three collinear vertices each) through
/// one point: on one line, crossing lines or skew.
fn degenerate_pairs() -> Vec<(FixedTriangle, FixedTriangle)> {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let mut collinear =
        |o: FixedPoint3, d: [i64; 3]| on_line(o, d, std::array::from_fn(|_| rng.gen_range(-3..4)));
    let mut vectors = Vec::new();
    let mut rng2 = ChaCha8Rng::seed_from_u64(10);
    for k in 0..VECTORS {
        let o = point(&mut rng2, 2);
        let d1: [i64; 3] = std::array::from_fn(|_| rng2.gen_range(-2..3));
        // The second segment on the same line, a crossing line or anywhere.
        let d2: [i64; 3] = if k % 3 == 0 {
            d1
        } else {
            std::array::from_fn(|_| rng2.gen_range(-2..3))
        };
        vectors.push((collinear(o, d1), collinear(o, d2)));
    }
    vectors
}

/// The segments (lexicographic ends) of two degenerate triangles meet in
/// all three axis projections.
fn segments_meet((t1, t2): &(FixedTriangle, FixedTriangle)) -> bool {
    let ((a, b), (c, d)) = (lexicographic_ends(t1), lexicographic_ends(t2));
    (0..3).all(|axis| hulls_intersect_2d::<FixedPoint>(axis, &[t1[a], t1[b]], &[t2[c], t2[d]]))
}

/// Two degenerate triangles: their segments (lexicographic ends) meet in all
/// three axis projections (`degenerate_pair` without its orient3d, which
/// the shared orient3d unit computes).
#[test]
fn degenerate_pair_is_the_three_projection_segment_test() {
    let vectors = degenerate_pairs();
    let model = segments_meet;
    let hits = vectors.iter().filter(|v| model(v)).count();
    assert!(
        hits > 20 && hits < vectors.len() - 20,
        "{hits} hits of {}",
        vectors.len()
    );
    let mut uut = DegeneratePair::<24, 25, 49>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &vectors,
        DEGENERATE_PAIR_LATENCY,
        |u, (t1, t2)| {
            set_vertices(&mut u.t1_vertices, t1);
            set_vertices(&mut u.t2_vertices, t2);
            let ((a, b), (c, d)) = (lexicographic_ends(t1), lexicographic_ends(t2));
            u.t1_segment_low.next = (a as u64).into();
            u.t1_segment_high.next = (b as u64).into();
            u.t2_segment_low.next = (c as u64).into();
            u.t2_segment_high.next = (d as u64).into();
        },
        |u| u.hit.val(),
        model,
    );
}

/// The shared rare-case unit gives the parallel tests' verdicts: coplanar
/// pairs and degenerate pairs interleaved, offered with gaps and back to
/// back, each verdict in order and exactly its kind's latency after the
/// job was taken; jobs offered back to back are taken a job's steps apart.
#[test]
fn shared_rare_cases_equal_the_parallel_tests() {
    let coplanar = coplanar_pairs(8)
        .into_iter()
        .filter(|(t1, _)| normal(t1) != [0, 0, 0]);
    let segments = degenerate_pairs();
    // (segments?, t1, t2), alternating in runs.
    let mut jobs: Vec<(bool, FixedTriangle, FixedTriangle)> = Vec::new();
    for (i, (c, d)) in coplanar.zip(segments).enumerate() {
        let first_segments = i % 3 == 0;
        jobs.push((
            first_segments,
            if first_segments { d.0 } else { c.0 },
            if first_segments { d.1 } else { c.1 },
        ));
        jobs.push((
            !first_segments,
            if first_segments { c.0 } else { d.0 },
            if first_segments { c.1 } else { d.1 },
        ));
    }
    let expected: Vec<bool> = jobs
        .iter()
        .map(|&(is_segments, t1, t2)| {
            if is_segments {
                segments_meet(&(t1, t2))
            } else {
                coplanar_triangles::<FixedPoint>(t1, t2)
            }
        })
        .collect();
    let mut uut = SharedRareCases::<24, 25, 49>::default();
    uut.connect_all();
    reset_one_clock(&mut uut, |u| &mut u.reset, |u| &mut u.clock);
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let (mut next, mut cycle) = (0usize, 0u64);
    let mut taken_at: Vec<u64> = Vec::new();
    let mut offered_since: Option<u64> = None;
    let mut back_to_back = 0;
    let mut verdicts: Vec<(bool, u64)> = Vec::new();
    while verdicts.len() < jobs.len() {
        assert!(
            cycle < 20 * jobs.len() as u64 + 100,
            "no verdicts after {cycle} clocks"
        );
        // Offer the next job, now and then after a gap.
        let offer = next < jobs.len() && (offered_since.is_some() || rng.gen_bool(0.7));
        uut.in_valid.next = offer;
        for copy in uut.in_valid_copies.iter_mut() {
            copy.next = offer;
        }
        if offer {
            let (is_segments, t1, t2) = &jobs[next];
            uut.in_segments.next = *is_segments;
            set_vertices(&mut uut.t1_vertices, t1);
            set_vertices(&mut uut.t2_vertices, t2);
            let (n1, n2) = (normal(t1), normal(t2));
            uut.axis.next = (dominant_axis(n1.map(|c| c.unsigned_abs())) as u64).into();
            for k in 0..3 {
                uut.t1_normal_negative[k].next = n1[k] < 0;
                uut.t1_normal_zero[k].next = n1[k] == 0;
                uut.t2_normal_negative[k].next = n2[k] < 0;
                uut.t2_normal_zero[k].next = n2[k] == 0;
            }
            let ((a, b), (c, d)) = (lexicographic_ends(t1), lexicographic_ends(t2));
            uut.t1_segment_low.next = (a as u64).into();
            uut.t1_segment_high.next = (b as u64).into();
            uut.t2_segment_low.next = (c as u64).into();
            uut.t2_segment_high.next = (d as u64).into();
            offered_since.get_or_insert(cycle);
        }
        uut.update_all();
        let taken = offer && uut.ready.val();
        clock_cycle(&mut uut, |u| &mut u.clock);
        cycle += 1;
        if taken {
            // Offered since the previous job was taken: taken exactly
            // that job's steps after it.
            if let (Some(&previous), Some(since)) = (taken_at.last(), offered_since) {
                if since < previous + 1 {
                    let steps = if jobs[next - 1].0 {
                        SEGMENTS_STEPS
                    } else {
                        COPLANAR_STEPS
                    };
                    assert_eq!(
                        cycle - previous,
                        steps as u64,
                        "job {next} taken back to back"
                    );
                    back_to_back += 1;
                }
            }
            taken_at.push(cycle);
            offered_since = None;
            next += 1;
        }
        if uut.done.val() {
            verdicts.push((uut.hit.val(), cycle));
        }
    }
    assert!(
        back_to_back > jobs.len() / 4,
        "{back_to_back} jobs back to back"
    );
    for (j, ((hit, at), expected)) in verdicts.iter().zip(&expected).enumerate() {
        assert_eq!(*hit, *expected, "job {j}: {:?}", jobs[j]);
        let latency = if jobs[j].0 {
            SHARED_RARE_CASES_LATENCY - (COPLANAR_STEPS - SEGMENTS_STEPS)
        } else {
            SHARED_RARE_CASES_LATENCY
        };
        assert_eq!(at - taken_at[j], latency as u64, "job {j}'s latency");
    }
}

/// The sign triples alignment sees: not all zero (a triangle in the
/// other's plane goes to the coplanar test) and not all of one sign (a
/// triangle strictly on one side is rejected before), 24 of 27.
fn sign_triples() -> Vec<[Sign; 3]> {
    let signs = [Sign::Negative, Sign::Zero, Sign::Positive];
    let all: Vec<[Sign; 3]> = (0..27)
        .map(|k| [signs[k % 3], signs[k / 3 % 3], signs[k / 9]])
        .collect();
    all.into_iter()
        .filter(|s| !(s[0] == s[1] && s[1] == s[2]))
        .collect()
}

fn set_signs(negative: &mut [Signal<In, Bit>; 3], zero: &mut [Signal<In, Bit>; 3], s: &[Sign; 3]) {
    for k in 0..3 {
        negative[k].next = s[k] == Sign::Negative;
        zero[k].next = s[k] == Sign::Zero;
    }
}

/// Steps (5) and (6) against `align_t1` and `align_t2` on labelled
/// vertices (T1 = 0, 1, 2; T2 = 3, 4, 5), for every pair of sign triples.
#[test]
fn alignment_units_follow_the_models_sign_tables() {
    let vectors: Vec<([Sign; 3], [Sign; 3])> = sign_triples()
        .into_iter()
        .flat_map(|d1| sign_triples().into_iter().map(move |d2| (d1, d2)))
        .collect();
    let mut uut = AlignT1::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &vectors,
        ALIGN_T1_LATENCY,
        |u, (d1, d2)| {
            set_signs(&mut u.t1_negative, &mut u.t1_zero, d1);
            set_signs(&mut u.t2_negative, &mut u.t2_zero, d2);
        },
        |u| {
            let aligned = std::array::from_fn::<_, 3, _>(|k| {
                (u.t2_aligned_negative[k].val(), u.t2_aligned_zero[k].val())
            });
            (
                u.t1_rotation.val().to_u64() as usize,
                u.t2_swap.val(),
                aligned,
            )
        },
        |(d1, d2)| {
            let (t1, t2, d2) = align_t1([0usize, 1, 2], [3usize, 4, 5], *d1, *d2);
            (
                t1[0],
                t2 != [3, 4, 5],
                d2.map(|s| (s == Sign::Negative, s == Sign::Zero)),
            )
        },
    );
    // Step (6): T2's rotation and T1's swap; step (5)'s pass through.
    let vectors: Vec<([Sign; 3], usize, bool)> = sign_triples()
        .into_iter()
        .enumerate()
        .map(|(k, d2)| (d2, k % 3, k % 2 == 0))
        .collect();
    let mut uut = AlignT2::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &vectors,
        ALIGN_T2_LATENCY,
        |u, (d2, rotation, swap)| {
            set_signs(&mut u.t2_aligned_negative, &mut u.t2_aligned_zero, d2);
            u.t1_rotation_in.next = (*rotation as u64).into();
            u.t2_swap_in.next = *swap;
        },
        |u| {
            (
                u.t2_rotation.val().to_u64() as usize,
                u.t1_swap.val(),
                u.t1_rotation.val().to_u64() as usize,
                u.t2_swap.val(),
            )
        },
        |(d2, rotation, swap)| {
            let aligned = align_t2([0usize, 1, 2], *d2);
            (aligned.t2[0], aligned.swap_t1, *rotation, *swap)
        },
    );
}

/// Step (7)'s vertex indices: with T1 rotated (and its last two swapped)
/// and T2 swapped then rotated, the determinants `[q1, p2, p1, q2]` and
/// `[p1, p2, r1, r2]` of `interval_overlap`, for every rotation and swap.
#[test]
fn interval_overlap_names_the_models_determinants() {
    let vectors: Vec<(usize, bool, usize, bool)> = (0..36)
        .map(|k| (k % 3, k / 3 % 2 == 1, k / 6 % 3, k / 18 == 1))
        .collect();
    let mut uut = IntervalOverlap::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &vectors,
        INTERVAL_OVERLAP_LATENCY,
        |u, (r1, s2, r2, s1)| {
            u.t1_rotation.next = (*r1 as u64).into();
            u.t2_swap.next = *s2;
            u.t2_rotation.next = (*r2 as u64).into();
            u.t1_swap.next = *s1;
        },
        |u| {
            (
                u.first.each_ref().map(|i| i.val().to_u64()),
                u.second.each_ref().map(|i| i.val().to_u64()),
            )
        },
        |(r1, s2, r2, s1)| {
            let rotate = |t: [u64; 3], k: usize| [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
            let [p1, mut q1, mut r1v] = rotate([0, 1, 2], *r1);
            if *s1 {
                std::mem::swap(&mut q1, &mut r1v);
            }
            let t2 = if *s2 { [3, 5, 4] } else { [3, 4, 5] };
            let [p2, q2, r2v] = rotate(t2, *r2);
            ([q1, p2, p1, q2], [p1, p2, r1v, r2v])
        },
    );
}

/// The degenerate triangle `o + s_k d`, `k = 0, 1, 2`.
fn on_line(o: FixedPoint3, d: [i64; 3], steps: [i64; 3]) -> FixedTriangle {
    steps.map(|s| std::array::from_fn(|i| o[i] + s * d[i]))
}

/// Random triangles, and degenerate ones (collinear vertices, repeated
/// vertices, points) whose segment ends matter.
fn triangles_and_degenerate_ones(seed: u64) -> Vec<FixedTriangle> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = triangles(seed);
    for k in 0..VECTORS {
        let o = point(&mut rng, 2);
        let d: [i64; 3] = std::array::from_fn(|_| rng.gen_range(-2..3));
        let s = [
            rng.gen_range(-3..4),
            rng.gen_range(-3..4),
            if k % 4 == 0 { 0 } else { rng.gen_range(-3..4) },
        ];
        out.push(on_line(o, d, s));
    }
    out
}

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

/// The base polygon latches a record when `load_ahead` was high at the
/// enabled edge before, and holds it otherwise.
#[test]
fn base_polygon_holds_the_last_loaded_record() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let records: Vec<(u32, FixedTriangle)> =
        triangles(13).into_iter().map(|t| (rng.gen(), t)).collect();
    let loads: Vec<bool> = (0..records.len())
        .map(|k| k == 0 || rng.gen_bool(0.2))
        .collect();
    // (the next record's load, offered record, the record held after the clock)
    let mut held = records[0];
    let vectors: Vec<(bool, (u32, FixedTriangle), (u32, FixedTriangle))> = records
        .iter()
        .enumerate()
        .map(|(k, r)| {
            if loads[k] {
                held = *r;
            }
            (loads.get(k + 1).copied().unwrap_or(false), *r, held)
        })
        .collect();
    let mut uut = BasePolygon::<24, 25, 49>::default();
    uut.connect_all();
    // The first record's load, an edge ahead.
    uut.advance.next = true;
    uut.load_ahead.next = loads[0];
    tritri_rtl::sim_drive::clock_cycle(&mut uut, |u| &mut u.clock);
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &vectors,
        1,
        |u, (load_next, (id, t), _)| {
            u.advance.next = true;
            u.load_ahead.next = *load_next;
            u.id_in.next = (*id as u64).into();
            set_vertices(&mut u.vertices_in, t);
            for (k, c) in normal(t).iter().enumerate() {
                u.normal_in[k].next = from_i128(*c);
            }
            u.edges_bits_in.next = edges_bits(t).into();
        },
        |u| {
            let t: FixedTriangle = std::array::from_fn(|v| {
                std::array::from_fn(|i| to_i128(u.vertices[3 * v + i].val()) as i64)
            });
            (
                u.id.val().to_u64() as u32,
                t,
                u.normal.each_ref().map(|n| to_i128(n.val())),
                u.edges_bits.val().to_u64(),
            )
        },
        |(_, _, (id, t))| (*id, *t, normal(t), edges_bits(t)),
    );
}
