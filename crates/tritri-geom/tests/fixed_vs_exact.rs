//! Verification step 2: the fixed-point model (exact i128 predicates on W-bit
//! coordinates, the hardware's arithmetic) gives the same answer as the exact
//! model run on the same quantized coordinates, for W = 8, 24 and 32. Each
//! pair is quantized into its own frame (`quantize_pair`: `Frame::fit` over its two
//! triangles); the integer coordinates are converted to f64 exactly
//! (|q| < 2^53). Any difference is a bug in one of the two kernels.
//!
//! The summaries also report how often quantization changes the verdict
//! against the exact answer on the original coordinates (not asserted: that
//! is the quantization error the project measures).

mod support;

use support::{failures, Timer};
use tritri_geom::fixed_point::{self, FixedTriangle};
use tritri_geom::hard_cases::{hard_case_suite, random_near_degenerate_pairs, random_pairs};
use tritri_geom::quantize::quantize_pair;
use tritri_geom::triangle::all_orderings;
use tritri_geom::{exact_f64, Triangle, TrianglePair};

const WIDTHS: [u32; 3] = [8, 24, 32];

fn quantized(pair: &TrianglePair, width: u32) -> (FixedTriangle, FixedTriangle) {
    quantize_pair(pair, width).expect("finite coordinates, supported width")
}

/// Integer coordinates as f64: exact, since they are below 2^32 in magnitude.
fn as_f64(t: &FixedTriangle) -> Triangle {
    t.map(|p| p.map(|c| c as f64))
}

fn as_integers(t: &Triangle) -> FixedTriangle {
    t.map(|p| {
        p.map(|c| {
            assert_eq!(c, c.trunc());
            c as i64
        })
    })
}

/// Fixed model == exact model on the quantized pair.
fn agrees(pair: &TrianglePair, width: u32) -> bool {
    let (q1, q2) = quantized(pair, width);
    fixed_point::intersects(&q1, &q2) == exact_f64::intersects(&as_f64(&q1), &as_f64(&q2))
}

/// Does quantization change the verdict? (For the report only.)
fn verdict_changed(pair: &TrianglePair, width: u32) -> bool {
    let (q1, q2) = quantized(pair, width);
    fixed_point::intersects(&q1, &q2) != exact_f64::intersects(&pair.t1, &pair.t2)
}

/// On 1,000,000 random pairs (half uniform, half near-degenerate), at each width.
#[test]
fn fixed_point_equals_exact_on_quantized_random_pairs() {
    let sets = [
        ("uniform", random_pairs(500_000, 2024)),
        (
            "near-degenerate",
            random_near_degenerate_pairs(500_000, 2025),
        ),
    ];
    let mut total_bad = 0;
    for width in WIDTHS {
        for (kind, pairs) in &sets {
            let timer = Timer::start();
            let bad = failures(pairs, |p| agrees(p, width));
            let changed = failures(pairs, |p| !verdict_changed(p, width)).len();
            eprintln!(
                "fixed W={width} vs exact on quantized coordinates, {kind} random pairs: {} pairs, {} disagreements, \
                 {:.1} s (quantization changed the verdict of {changed} pairs)",
                pairs.len(),
                bad.len(),
                timer.seconds()
            );
            for &i in bad.iter().take(5) {
                eprintln!("  W={width} #{i}: {:?}", pairs[i]);
            }
            total_bad += bad.len();
        }
    }
    assert_eq!(total_bad, 0);
}

/// On every hard case in all 72 orderings (of the quantized integer pair),
/// at each width.
#[test]
fn fixed_point_equals_exact_on_quantized_hard_cases_in_all_orderings() {
    let cases = hard_case_suite();
    let mut total_bad = 0;
    for width in WIDTHS {
        let timer = Timer::start();
        let bad = failures(&cases, |case| {
            let (q1, q2) = quantized(&case.pair, width);
            let integer_pair = TrianglePair::new(as_f64(&q1), as_f64(&q2));
            let all_agree = all_orderings(&integer_pair).all(|p| {
                fixed_point::intersects(&as_integers(&p.t1), &as_integers(&p.t2))
                    == exact_f64::intersects(&p.t1, &p.t2)
            });
            all_agree
        });
        let changed = failures(&cases, |c| !verdict_changed(&c.pair, width)).len();
        eprintln!(
            "fixed W={width} vs exact on quantized coordinates, hard cases: {} cases x 72 orderings, {} cases with a \
             disagreement, {:.1} s (quantization changed the verdict of {changed} cases)",
            cases.len(),
            bad.len(),
            timer.seconds()
        );
        for &i in bad.iter().take(5) {
            eprintln!("  W={width} {}: {:?}", cases[i].name, cases[i].pair);
        }
        total_bad += bad.len();
    }
    assert_eq!(total_bad, 0);
}
