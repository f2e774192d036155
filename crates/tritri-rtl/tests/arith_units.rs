//! Each arithmetic primitive alone, by direct drive: random operands
//! (and the ends of their ranges) streamed one per clock, the outputs
//! against the exact integer value and the latency constant asserted
//! (`sim_drive::assert_stream_matches`). Widths are the W = 24 pipeline's:
//! W = 24, D = 25, C = 49, O = 74.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rust_hdl::prelude::*;
use tritri_geom::fixed_point::cross;
use tritri_rtl::arith::adder::{
    RegisteredDifference, RegisteredDifferenceSign, RegisteredSum3, ADDER_LATENCY, SUM3_LATENCY,
};
use tritri_rtl::arith::compare::{
    CoordinateCompare, SplitCompare, COMPARE_LATENCY, SPLIT_COMPARE_LATENCY,
};
use tritri_rtl::arith::convert::{from_i128, to_i128, wrap_i128};
use tritri_rtl::arith::cross_product::{
    CrossProduct, CrossProduct2d, TwoWayCrossProduct, CROSS_PRODUCT_LATENCY,
};
use tritri_rtl::arith::delay_line::DelayLine;
use tritri_rtl::arith::dot_product::{DotProduct, DOT_PRODUCT_LATENCY};
use tritri_rtl::arith::multiplier::{Multiplier, MULTIPLIER_LATENCY};
use tritri_rtl::arith::sign::{SignOf, SIGN_LATENCY};
use tritri_rtl::arith::subtractor::{Subtractor, VectorSubtractor, SUBTRACTOR_LATENCY};
use tritri_rtl::arith::valid_line::ValidLine;
use tritri_rtl::sim_drive::{assert_stream_matches, clock_cycle};

const VECTORS: usize = 400;

/// `n` values of `bits`-bit two's complement: uniform, the two ends of the
/// range, and small values, in turn.
fn values(rng: &mut ChaCha8Rng, bits: u32, n: usize) -> Vec<i128> {
    let lim = 1i128 << (bits - 1);
    (0..n)
        .map(|k| match k % 3 {
            0 => rng.gen_range(-lim..lim),
            1 => {
                if rng.gen_bool(0.5) {
                    -lim
                } else {
                    lim - 1
                }
            }
            _ => rng.gen_range(-2..3),
        })
        .collect()
}

/// Difference vectors `b - a` and `c - a` of random W = 24 points `a`, `b`,
/// `c`, and `d - a` for a fourth: the operands the products see in the
/// pipeline. (Their widths C = 2W + 1 and O = 3W + 2 hold for these, not
/// for any 25-bit vectors: a cross product is twice a triangle's area.)
fn edge_vectors(seed: u64) -> Vec<[[i128; 3]; 3]> {
    tuples::<12>(seed, 24)
        .into_iter()
        .map(|p| {
            let edge = |k: usize| std::array::from_fn(|i| p[3 * k + i] - p[i]);
            [edge(1), edge(2), edge(3)]
        })
        .collect()
}

fn narrow(v: [i128; 3]) -> [i64; 3] {
    v.map(|x| x as i64)
}

fn tuples<const K: usize>(seed: u64, bits: u32) -> Vec<[i128; K]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let columns: Vec<Vec<i128>> = (0..K).map(|_| values(&mut rng, bits, VECTORS)).collect();
    (0..VECTORS)
        .map(|i| std::array::from_fn(|k| columns[k][(i + 7 * k) % VECTORS]))
        .collect()
}

#[test]
fn multiplier_is_the_exact_product() {
    let mut uut = Multiplier::<25, 49, 74>::default();
    uut.connect_all();
    uut.advance.next = true;
    let a = tuples::<1>(1, 25);
    let b = tuples::<1>(2, 49);
    let pairs: Vec<(i128, i128)> = a.iter().zip(&b).map(|(a, b)| (a[0], b[0])).collect();
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &pairs,
        MULTIPLIER_LATENCY,
        |u, (a, b)| {
            u.a.next = from_i128(*a);
            u.b.next = from_i128(*b);
        },
        |u| to_i128(u.product.val()),
        |(a, b)| a * b,
    );
}

#[test]
fn subtractors_are_exact() {
    let mut uut = Subtractor::<24, 25>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &tuples::<2>(3, 24),
        SUBTRACTOR_LATENCY,
        |u, [a, b]| {
            u.a.next = from_i128(*a);
            u.b.next = from_i128(*b);
        },
        |u| to_i128(u.difference.val()),
        |[a, b]| a - b,
    );
    let mut uut = VectorSubtractor::<24, 25>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &tuples::<6>(4, 24),
        SUBTRACTOR_LATENCY,
        |u, v| {
            for k in 0..3 {
                u.a[k].next = from_i128(v[k]);
                u.b[k].next = from_i128(v[3 + k]);
            }
        },
        |u| u.difference.each_ref().map(|d| to_i128(d.val())),
        |v| std::array::from_fn(|k| v[k] - v[3 + k]),
    );
}

#[test]
fn cross_products_are_exact() {
    let mut uut = CrossProduct::<25, 49>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &edge_vectors(5),
        CROSS_PRODUCT_LATENCY,
        |u, [e1, e2, _]| {
            for k in 0..3 {
                u.u[k].next = from_i128(e1[k]);
                u.v[k].next = from_i128(e2[k]);
            }
        },
        |u| u.product.each_ref().map(|p| to_i128(p.val())),
        |[e1, e2, _]| cross(narrow(*e1), narrow(*e2)),
    );
    // Both ways: the product and its negation from the same stage.
    let mut uut = TwoWayCrossProduct::<25, 49>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &edge_vectors(8),
        CROSS_PRODUCT_LATENCY,
        |u, [e1, e2, _]| {
            for k in 0..3 {
                u.u[k].next = from_i128(e1[k]);
                u.v[k].next = from_i128(e2[k]);
            }
        },
        |u| {
            (
                u.product.each_ref().map(|p| to_i128(p.val())),
                u.negated.each_ref().map(|p| to_i128(p.val())),
            )
        },
        |[e1, e2, _]| {
            let n = cross(narrow(*e1), narrow(*e2));
            (n, n.map(|c| -c))
        },
    );
    let mut uut = CrossProduct2d::<25, 49>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &edge_vectors(6),
        CROSS_PRODUCT_LATENCY,
        |u, [e1, e2, _]| {
            u.u_x.next = from_i128(e1[0]);
            u.u_y.next = from_i128(e1[1]);
            u.w_x.next = from_i128(e2[0]);
            u.w_y.next = from_i128(e2[1]);
        },
        |u| to_i128(u.product.val()),
        |[e1, e2, _]| e1[0] * e2[1] - e1[1] * e2[0],
    );
}

#[test]
fn dot_product_is_exact() {
    let mut uut = DotProduct::<25, 49, 74>::default();
    uut.connect_all();
    uut.advance.next = true;
    let vectors: Vec<([i128; 3], [i128; 3])> = edge_vectors(7)
        .into_iter()
        .map(|[e1, e2, e3]| (e3, cross(narrow(e1), narrow(e2))))
        .collect();
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &vectors,
        DOT_PRODUCT_LATENCY,
        |uut, (u, v)| {
            for k in 0..3 {
                uut.u[k].next = from_i128(u[k]);
                uut.v[k].next = from_i128(v[k]);
            }
        },
        |uut| to_i128(uut.product.val()),
        |(u, v)| (0..3).map(|k| u[k] * v[k]).sum(),
    );
}

#[test]
fn sign_and_comparison() {
    let mut uut = SignOf::<74>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &tuples::<1>(9, 74),
        SIGN_LATENCY,
        |u, [v]| u.value.next = from_i128(*v),
        |u| (u.negative.val(), u.zero.val()),
        |[v]| (*v < 0, *v == 0),
    );
    let mut uut = CoordinateCompare::<24>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &tuples::<2>(10, 24),
        COMPARE_LATENCY,
        |u, [a, b]| {
            u.a.next = from_i128(*a);
            u.b.next = from_i128(*b);
        },
        |u| (u.less.val(), u.equal.val()),
        |[a, b]| (a < b, a == b),
    );
    // Odd widths split unevenly: 11 bits as 6 + 5.
    let mut uut = SplitCompare::<24>::default();
    uut.connect_all();
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &tuples::<2>(10, 24),
        SPLIT_COMPARE_LATENCY,
        |u, [a, b]| {
            u.a.next = from_i128(*a);
            u.b.next = from_i128(*b);
        },
        |u| (u.less.val(), u.equal.val()),
        |[a, b]| (a < b, a == b),
    );
    let mut uut = SplitCompare::<11>::default();
    uut.connect_all();
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &tuples::<2>(11, 11),
        SPLIT_COMPARE_LATENCY,
        |u, [a, b]| {
            u.a.next = from_i128(*a);
            u.b.next = from_i128(*b);
        },
        |u| (u.less.val(), u.equal.val()),
        |[a, b]| (a < b, a == b),
    );
}

#[test]
fn adders_wrap_modulo_their_width() {
    let mut uut = RegisteredSum3::<50>::default();
    uut.connect_all();
    uut.advance.next = true;
    // Random sums, and sums of 0: `c = -(a + b)`, with and without a wrap.
    let mut sums = tuples::<3>(11, 50);
    let zeros: Vec<[i128; 3]> = sums
        .iter()
        .map(|[a, b, _]| [*a, *b, wrap_i128(-(a + b), 50)])
        .collect();
    assert!(zeros.iter().any(|[a, b, _]| wrap_i128(a + b, 50) != a + b));
    sums.extend(zeros.iter().step_by(3));
    sums.extend([
        [0, 0, 0],
        [1, -1, 0],
        [0, 1, -1],
        [-(1 << 49), -(1 << 49), 0],
    ]);
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &sums,
        SUM3_LATENCY,
        |u, [a, b, c]| {
            u.a.next = from_i128(*a);
            u.b.next = from_i128(*b);
            u.c.next = from_i128(*c);
        },
        |u| (to_i128(u.sum.val()), u.zero_parts.val().all()),
        |[a, b, c]| {
            let sum = wrap_i128(a + b + c, 50);
            (sum, sum == 0)
        },
    );
    let mut uut = RegisteredDifference::<50>::default();
    uut.connect_all();
    uut.advance.next = true;
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &tuples::<2>(12, 50),
        ADDER_LATENCY,
        |u, [a, b]| {
            u.a.next = from_i128(*a);
            u.b.next = from_i128(*b);
        },
        |u| to_i128(u.difference.val()),
        |[a, b]| wrap_i128(a - b, 50),
    );
    // The sign and the equality in parts: random pairs, equal pairs, and
    // pairs that differ in one bit, every bit (each part's test, the sign's
    // borrow from each bit).
    let mut uut = RegisteredDifferenceSign::<50>::default();
    uut.connect_all();
    uut.advance.next = true;
    let mut pairs = tuples::<2>(13, 50);
    let equal: Vec<[i128; 2]> = pairs.iter().map(|[a, _]| [*a, *a]).collect();
    pairs.extend(equal.iter().step_by(4));
    for bit in 0..50 {
        let [a, _] = pairs[bit];
        pairs.push([a, wrap_i128(a ^ (1 << bit), 50)]);
    }
    pairs.extend([
        [0, 0],
        [-(1 << 49), (1 << 49) - 1],
        [(1 << 49) - 1, -(1 << 49)],
    ]);
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &pairs,
        ADDER_LATENCY,
        |u, [a, b]| {
            u.a.next = from_i128(*a);
            u.b.next = from_i128(*b);
        },
        |u| (u.negative.val(), u.equal_parts.val().all()),
        |[a, b]| (wrap_i128(a - b, 50) < 0, a == b),
    );
}

/// A delay line of N stages delays by N enabled edges, and holds while
/// `advance` is low; a valid line does the same for one bit and clears on
/// reset.
#[test]
fn delay_lines_delay_by_their_length_and_hold() {
    let mut uut = DelayLine::<Bits<24>, 5>::default();
    uut.connect_all();
    uut.advance.next = true;
    let words = tuples::<1>(13, 24);
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &words,
        5,
        |u, [w]| u.d.next = from_i128(*w),
        |u| to_i128(u.q.val()),
        |[w]| *w,
    );
    // Held: with `advance` low, the output and the line do not move.
    let before = uut.q.val();
    uut.advance.next = false;
    for k in 0..7 {
        uut.d.next = from_i128::<24>(k);
        clock_cycle(&mut uut, |u| &mut u.clock);
        assert_eq!(uut.q.val(), before);
    }

    let mut uut = ValidLine::<5>::default();
    uut.connect_all();
    uut.advance.next = true;
    let bits: Vec<bool> = (0..VECTORS).map(|k| (k * 7 + k / 3) % 5 < 2).collect();
    assert_stream_matches(
        &mut uut,
        |u| &mut u.clock,
        &bits,
        5,
        |u, b| u.d.next = *b,
        |u| u.q.val(),
        |b| *b,
    );
    for _ in 0..5 {
        uut.d.next = true;
        clock_cycle(&mut uut, |u| &mut u.clock);
    }
    uut.reset.next = true;
    clock_cycle(&mut uut, |u| &mut u.clock);
    uut.reset.next = false;
    uut.d.next = false;
    for _ in 0..6 {
        assert!(!uut.q.val(), "a valid bit survived the reset");
        clock_cycle(&mut uut, |u| &mut u.clock);
    }
}
