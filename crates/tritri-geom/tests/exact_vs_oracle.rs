//! Verification step 1: the exact software model (Devillers–Guigue on exact
//! f64 predicates) gives the same answer as an independent exact oracle
//! (separating axes in exact integer arithmetic, `tests/oracle`), on random
//! pairs, near-degenerate random pairs and every hard case in all 72
//! orderings; and the exact model does not depend on the ordering.

mod oracle;
mod support;

use num_bigint::BigInt;
use num_rational::BigRational;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use support::{failures, Timer};
use tritri_geom::hard_cases::{
    hard_case_suite, random_near_degenerate_pairs, random_pairs, HardCase,
};
use tritri_geom::triangle::all_orderings;
use tritri_geom::{exact_f64, TrianglePair};

fn model(p: &TrianglePair) -> bool {
    exact_f64::intersects(&p.t1, &p.t2)
}

fn oracle(p: &TrianglePair) -> bool {
    oracle::intersects(&p.t1, &p.t2)
}

fn report_pairs(what: &str, pairs: &[TrianglePair], bad: &[usize]) {
    for &i in bad.iter().take(10) {
        let p = &pairs[i];
        eprintln!(
            "  {what} #{i}: t1 = {:?}, t2 = {:?}: model {}, oracle {}",
            p.t1,
            p.t2,
            model(p),
            oracle(p)
        );
    }
}

/// The oracle's f64 -> (mantissa, exponent) split is exact: it equals the
/// exact rational value of the f64, subnormals and signed zeros included.
#[test]
fn oracle_decomposes_f64_exactly() {
    let mut values = vec![
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.1,
        1e-310,
        -5e-324,
        f64::MIN_POSITIVE,
        f64::MAX,
        -f64::MAX,
        1e9 + 0.5,
    ];
    values.extend(
        random_pairs(200, 99)
            .iter()
            .flat_map(|p| p.coordinates().collect::<Vec<_>>()),
    );
    for x in values {
        let (m, e) = oracle::decompose(x);
        let two = BigRational::from_integer(BigInt::from(2));
        let value = BigRational::from_integer(BigInt::from(m)) * num_traits::pow::Pow::pow(&two, e);
        assert_eq!(
            value,
            BigRational::from_float(x).unwrap(),
            "decompose({x:e}) = {m} * 2^{e}"
        );
    }
}

/// The oracle answers hand-checked cases, one per kind of contact.
#[test]
fn oracle_answers_hand_made_cases() {
    let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let cases: Vec<(&str, [[f64; 3]; 3], bool)> = vec![
        ("identical", t, true),
        (
            "shared vertex, other plane",
            [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [-1.0, -1.0, 1.0]],
            true,
        ),
        (
            "above",
            [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]],
            false,
        ),
        (
            "piercing",
            [[0.2, 0.2, -1.0], [0.2, 0.2, 1.0], [0.3, 0.25, 1.0]],
            true,
        ),
        (
            "coplanar, beyond hypotenuse",
            [[1.0, 1.0, 0.0], [2.0, 1.0, 0.0], [1.0, 2.0, 0.0]],
            false,
        ),
        (
            "coplanar, touching hypotenuse",
            [[0.5, 0.5, 0.0], [2.0, 1.0, 0.0], [1.0, 2.0, 0.0]],
            true,
        ),
        (
            "edge touching an edge from above",
            [[0.5, -1.0, 0.0], [0.5, 1.0, 0.0], [0.5, 0.0, 1.0]],
            true,
        ),
        (
            "edge passing over an edge",
            [[0.5, -1.0, 1e-300], [0.5, 1.0, 1e-300], [0.5, 0.0, 1.0]],
            false,
        ),
        ("point inside", [[0.25, 0.25, 0.0]; 3], true),
        ("point 1 ulp above", [[0.25, 0.25, 5e-324]; 3], false),
        (
            "segment through the hypotenuse",
            [[0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [0.5, 0.5, 0.0]],
            true,
        ),
        (
            "segment along the x axis beyond",
            [[2.0, 0.0, 0.0], [3.0, 0.0, 0.0], [2.5, 0.0, 0.0]],
            false,
        ),
        (
            "segment overlapping an edge",
            [[-1.0, 0.0, 0.0], [0.5, 0.0, 0.0], [0.0, 0.0, 0.0]],
            true,
        ),
    ];
    for (name, other, expected) in cases {
        for (a, b) in [(t, other), (other, t)] {
            assert_eq!(oracle::intersects(&a, &b), expected, "{name}");
            assert_eq!(
                oracle::intersects_exact_only(&a, &b),
                expected,
                "{name} (no filter)"
            );
        }
    }
    let p = [[1.0, 2.0, 3.0]; 3];
    let q = [[1.0, 2.0, 3.0f64.next_up()]; 3];
    assert!(oracle::intersects(&p, &p));
    assert!(!oracle::intersects(&p, &q));
    let s1 = [[0.0, 0.0, 0.0], [2.0, 2.0, 2.0], [0.0, 0.0, 0.0]];
    let s2 = [[0.0, 2.0, 0.0], [2.0, 0.0, 2.0], [1.0, 1.0, 1.0]];
    let s3 = [
        [0.0, 2.0, 0.0],
        [2.0, 0.0, 2.0f64.next_up()],
        [2.0, 0.0, 2.0f64.next_up()],
    ];
    assert!(oracle::intersects(&s1, &s2), "crossing segments");
    assert!(!oracle::intersects(&s1, &s3), "skew by one ulp");
}

/// The filtered oracle and the all-BigInt oracle agree (the filter only
/// answers when it is sure).
#[test]
fn oracle_filter_agrees_with_unfiltered_oracle() {
    let timer = Timer::start();
    let mut pairs = random_pairs(2000, 11);
    pairs.extend(random_near_degenerate_pairs(5000, 12));
    pairs.extend(hard_case_suite().iter().map(|c| c.pair));
    let needed_exact = AtomicUsize::new(0);
    let bad = failures(&pairs, |p| {
        let (answer, fallbacks) = oracle::intersects_counting_fallbacks(&p.t1, &p.t2);
        needed_exact.fetch_add((fallbacks > 0) as usize, Relaxed);
        answer == oracle::intersects_exact_only(&p.t1, &p.t2)
    });
    eprintln!(
        "oracle filter vs unfiltered: {} pairs ({} used the exact fallback), {} disagreements, {:.1} s",
        pairs.len(),
        needed_exact.into_inner(),
        bad.len(),
        timer.seconds()
    );
    assert!(
        bad.is_empty(),
        "filtered and unfiltered oracle disagree on {} pairs, first: {:?}",
        bad.len(),
        pairs[bad[0]]
    );
}

/// Exact model == oracle on 1,000,000 random pairs: 500,000 uniform in the
/// unit cube and 500,000 near-degenerate by construction.
#[test]
fn exact_model_equals_oracle_on_a_million_random_pairs() {
    let mut total_bad = 0;
    for (kind, pairs) in [
        ("uniform", random_pairs(500_000, 2024)),
        (
            "near-degenerate",
            random_near_degenerate_pairs(500_000, 2025),
        ),
    ] {
        let timer = Timer::start();
        let needed_exact = AtomicUsize::new(0);
        let bad = failures(&pairs, |p| {
            let (answer, fallbacks) = oracle::intersects_counting_fallbacks(&p.t1, &p.t2);
            if fallbacks > 0 {
                needed_exact.fetch_add(1, Relaxed);
            }
            model(p) == answer
        });
        let intersecting = pairs.len() - failures(&pairs, model).len();
        eprintln!(
            "exact model vs oracle, {kind} random pairs: {} pairs ({intersecting} intersecting, {} needed the oracle's \
             exact path), {} disagreements, {:.1} s",
            pairs.len(),
            needed_exact.into_inner(),
            bad.len(),
            timer.seconds()
        );
        report_pairs(kind, &pairs, &bad);
        total_bad += bad.len();
    }
    assert_eq!(
        total_bad, 0,
        "disagreements between the exact model and the oracle"
    );
}

fn category(case: &HardCase) -> String {
    let parts: Vec<&str> = case.name.split(['/', '#']).collect();
    match parts[0] {
        "degenerate" | "vertex_on_plane" | "shared_edge" => format!("{}/{}", parts[0], parts[1]),
        "near_miss" => format!("{}/{}", parts[0], parts[3]),
        _ => parts[0].to_string(),
    }
}

/// Exact model == oracle on every hard case in all 72 orderings. The oracle
/// is run on every ordering too (it must not depend on it either).
#[test]
fn exact_model_equals_oracle_on_hard_cases_in_all_orderings() {
    let timer = Timer::start();
    let cases = hard_case_suite();
    let mut per_category: BTreeMap<String, [usize; 2]> = BTreeMap::new();
    let bad = failures(&cases, |case| {
        let expected = oracle(&case.pair);
        all_orderings(&case.pair).all(|p| model(&p) == expected && oracle(&p) == expected)
    });
    for case in &cases {
        per_category.entry(category(case)).or_default()[oracle(&case.pair) as usize] += 1;
    }
    eprintln!(
        "exact model vs oracle, hard cases: {} cases x 72 orderings = {} pairs, {} cases with a disagreement, {:.1} s",
        cases.len(),
        cases.len() * 72,
        bad.len(),
        timer.seconds()
    );
    for (name, [disjoint, intersecting]) in &per_category {
        eprintln!("  {name:45} {intersecting:5} intersecting {disjoint:5} disjoint");
    }
    for &i in bad.iter().take(20) {
        let c = &cases[i];
        let wrong = all_orderings(&c.pair)
            .filter(|p| model(p) != oracle(&c.pair))
            .count();
        eprintln!(
            "  {}: oracle {}, model wrong in {wrong} of 72: {:?}",
            c.name,
            oracle(&c.pair),
            c.pair
        );
    }
    assert!(bad.is_empty(), "{} hard cases disagree", bad.len());
}

/// The exact model gives one answer for all 72 orderings of a pair (vertex
/// rotations and reflections of both triangles, and the swap), on the hard
/// cases and on 100,000 random pairs.
#[test]
fn exact_model_is_invariant_under_the_72_orderings() {
    let timer = Timer::start();
    let mut pairs: Vec<TrianglePair> = hard_case_suite().iter().map(|c| c.pair).collect();
    pairs.extend(random_pairs(50_000, 7));
    pairs.extend(random_near_degenerate_pairs(50_000, 8));
    let bad = failures(&pairs, |p| {
        let first = model(p);
        all_orderings(p).all(|q| model(&q) == first)
    });
    eprintln!(
        "exact model ordering invariance: {} pairs x 72 orderings, {} pairs not invariant, {:.1} s",
        pairs.len(),
        bad.len(),
        timer.seconds()
    );
    report_pairs("not invariant", &pairs, &bad);
    assert!(bad.is_empty());
}

/// Exact model == oracle at the ends of the f64 range, where the products
/// inside Shewchuk's predicates overflow or underflow: every hard case and
/// 2,000 random and near-degenerate pairs, scaled by powers of two from
/// 2^-1070 to 2^1020 (exact unless the scaling itself underflows, so the
/// answer of the unscaled pair must come back too wherever no coordinate
/// lost bits), plus pairs that span more than f64::MAX.
#[test]
fn exact_model_equals_oracle_at_extreme_magnitudes() {
    let timer = Timer::start();
    let mut base: Vec<TrianglePair> = hard_case_suite().iter().map(|c| c.pair).collect();
    base.extend(random_pairs(1_000, 31));
    base.extend(random_near_degenerate_pairs(1_000, 32));
    let scale_pair = |p: &TrianglePair, s: f64| {
        TrianglePair::new(
            p.t1.map(|v| v.map(|x| x * s)),
            p.t2.map(|v| v.map(|x| x * s)),
        )
    };
    let mut pairs = Vec::new();
    let mut unscaled_answer = Vec::new();
    for exponent in [-1070, -1000, -700, -400, 300, 600, 900, 1000, 1020] {
        let s = 2f64.powi(exponent);
        for p in &base {
            let q = scale_pair(p, s);
            // Scaling is exact when every coordinate comes back.
            let exact_scaling = q
                .coordinates()
                .zip(p.coordinates())
                .all(|(a, b)| a.is_finite() && a / s == b);
            if q.coordinates().all(f64::is_finite) {
                pairs.push(q);
                unscaled_answer.push(exact_scaling.then(|| model(p)));
            }
        }
    }
    // Spans beyond f64::MAX: copies of a pair moved far apart to either
    // side of the origin (disjoint), and pairs straddling the origin at
    // full scale (not an exact scaling: compared with the oracle only).
    let max = f64::MAX;
    for p in base.iter().take(2_000) {
        let far = |t: tritri_geom::Triangle, side: f64| {
            t.map(|v| {
                [
                    side * max * (0.5 + 0.25 * v[0].clamp(0.0, 1.0)),
                    v[1].clamp(-1.0, 1.0) * 1e300,
                    v[2].clamp(-1.0, 1.0) * 1e300,
                ]
            })
        };
        pairs.push(TrianglePair::new(far(p.t1, -1.0), far(p.t2, 1.0)));
        unscaled_answer.push(Some(false));
        let full = |t: tritri_geom::Triangle| {
            t.map(|v| v.map(|x| (x.clamp(-1.0, 1.0) - 0.5) * (max / 2.0)))
        };
        pairs.push(TrianglePair::new(full(p.t1), full(p.t2)));
        unscaled_answer.push(None);
    }
    let bad = failures(&pairs, |p| model(p) == oracle(p));
    let lost = (0..pairs.len())
        .filter(|&i| unscaled_answer[i].is_some_and(|a| oracle(&pairs[i]) != a))
        .count();
    eprintln!(
        "exact model vs oracle at extreme magnitudes: {} pairs, {} disagreements, {lost} exactly scaled pairs whose \
         answer changed, {:.1} s",
        pairs.len(),
        bad.len(),
        timer.seconds()
    );
    report_pairs("extreme", &pairs, &bad);
    assert!(
        bad.is_empty(),
        "{} disagreements at extreme magnitudes",
        bad.len()
    );
    assert_eq!(lost, 0, "scaling by a power of two changed an exact answer");
}
