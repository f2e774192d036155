//! The rust-hdl simulation of the triangle pipeline agrees bit for bit with
//! the fixed-point model (`tritri_geom::fixed_point::intersects`), pair ids
//! and cycle counts included, at several coordinate widths; `advance = 0`
//! holds the whole pipeline; `reset` clears the valid bits.
//!
//! Scale: `TRITRI_PAIRS` random pairs per width (default 20 000) and every
//! N-th case of the hard-case suite in all 72 orderings
//! (`suites::hard_case_step`, `TRITRI_HARD_CASES=N`, default 8). What
//! issue #3 asked to be shown, 100 000 pairs and the whole suite (340 128
//! pairs per width, about 9 minutes on 2 cores), is `scripts/test-long.sh`.
//! Throughput: `tritri bench`.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use tritri_cosim::rusthdl_harness::{run_schedule_on, HarnessOptions};
use tritri_cosim::stream::{
    all_orderings, group_schedule, shared_path_cost, PairGroup, TriangleStream,
};
use tritri_cosim::suites::{hard_case_count, hard_case_groups, hard_case_step};
use tritri_geom::certificate::certified_intersects;
use tritri_geom::devillers_guigue::{shape, Shape};
use tritri_geom::fixed_point::{intersects, orient3d_value, FixedPoint, FixedTriangle};
use tritri_geom::hard_cases::{random_near_degenerate_pairs, random_pairs};
use tritri_geom::quantize::Frame;
use tritri_rtl::pipeline::pipeline_for_width::{
    pipeline_for_width, pipeline_with, PipelineInput, PipelineSimulation,
};
use tritri_rtl::pipeline::triangle_pipeline::latency;
use tritri_rtl::pipeline::RareCasePath;

fn env_usize(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Which branch of the algorithm a pair exercises (for coverage reports).
fn category(t1: &FixedTriangle, t2: &FixedTriangle) -> &'static str {
    let proper = |t: &FixedTriangle| matches!(shape::<FixedPoint>(*t), Shape::Triangle(_));
    match (proper(t1), proper(t2)) {
        (true, true) => {
            let [p, q, r] = *t2;
            if t1.iter().all(|&v| orient3d_value(p, q, r, v) == 0) {
                "coplanar"
            } else {
                "general"
            }
        }
        (false, false) => "two degenerate",
        _ => "one degenerate",
    }
}

/// Groups of (base, streamed triangles) checked against the model.
#[derive(Default)]
struct Check {
    pairs: usize,
    mismatches: usize,
    hits: usize,
    categories: BTreeMap<&'static str, usize>,
    failures: Vec<String>,
}

impl Check {
    fn run(&mut self, pipeline: &mut dyn PipelineSimulation, groups: &[PairGroup]) {
        for (base, streamed) in groups {
            for t in streamed {
                *self.categories.entry(category(base, t)).or_default() += 1;
            }
        }
        let (schedule, expected) = group_schedule(groups, certified_intersects);
        let result = run_schedule_on(pipeline, &schedule, &HarnessOptions::default())
            .expect("simulation run");
        assert_eq!(result.verdicts.len(), expected.len());
        for (v, e) in result.verdicts.iter().zip(&expected) {
            assert_eq!(
                (v.base_id, v.stream_id),
                (e.base_id, e.stream_id),
                "pair ids"
            );
            self.pairs += 1;
            self.hits += e.hit as usize;
            if v.hit != e.hit {
                self.mismatches += 1;
                if self.failures.len() < 10 {
                    let (base, streamed) = &groups[e.base_id as usize];
                    let t = streamed[e.stream_id as usize];
                    self.failures.push(format!(
                        "{base:?} vs {t:?}: model {}, rust-hdl {}",
                        e.hit, v.hit
                    ));
                }
            }
        }
    }

    fn report_and_assert(&self, what: &str) {
        eprintln!(
            "{what}: {} pairs, {} hits, {} mismatches, by case {:?}",
            self.pairs, self.hits, self.mismatches, self.categories
        );
        assert!(
            self.mismatches == 0,
            "{what}: {} mismatches, e.g.\n{}",
            self.mismatches,
            self.failures.join("\n")
        );
    }
}

fn random_triangle(rng: &mut ChaCha8Rng, lo: i64, hi: i64) -> FixedTriangle {
    [0; 3].map(|_| [0; 3].map(|_| rng.gen_range(lo..=hi)))
}

/// Small integer coordinates: coplanar, collinear, repeated and touching
/// configurations are frequent, so every branch of the algorithm runs.
fn small_integer_groups(seed: u64, range: i64, bases: usize, streamed: usize) -> Vec<PairGroup> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..bases)
        .map(|_| {
            (
                random_triangle(&mut rng, -range, range),
                (0..streamed)
                    .map(|_| random_triangle(&mut rng, -range, range))
                    .collect(),
            )
        })
        .collect()
}

/// Coordinates at the ends of the W-bit range: the widest intermediate
/// values, to catch any width that is one bit short.
fn extreme_groups(width: usize, seed: u64, bases: usize, streamed: usize) -> Vec<PairGroup> {
    let max = (1i64 << (width - 1)) - 1;
    let min = -(1i64 << (width - 1));
    let values = [min, max, 0, 1, -1, min + 1, max - 1, max / 2, min / 2];
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let pick = |rng: &mut ChaCha8Rng| {
        [0; 3].map(|_| [0; 3].map(|_| values[rng.gen_range(0..values.len())]))
    };
    (0..bases)
        .map(|_| {
            (
                pick(&mut rng),
                (0..streamed).map(|_| pick(&mut rng)).collect(),
            )
        })
        .collect()
}

/// Triangles on one integer plane per group, `h = a u + b v + c` with the
/// height `h` along a random axis and small slopes: coplanar pairs with
/// every dominant axis (ties included), touching and overlapping often.
fn coplanar_integer_groups(seed: u64, bases: usize, streamed: usize) -> Vec<PairGroup> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..bases)
        .map(|_| {
            let (a, b, c, h) = (
                rng.gen_range(-2..=2),
                rng.gen_range(-2..=2),
                rng.gen_range(-2..=2),
                rng.gen_range(0..3),
            );
            let on_plane = |rng: &mut ChaCha8Rng| -> FixedTriangle {
                [0; 3].map(|_| {
                    let (u, v) = (rng.gen_range(-3i64..=3), rng.gen_range(-3i64..=3));
                    let mut p = [0; 3];
                    p[(h + 1) % 3] = u;
                    p[(h + 2) % 3] = v;
                    p[h] = a * u + b * v + c;
                    p
                })
            };
            let base = on_plane(&mut rng);
            (base, (0..streamed).map(|_| on_plane(&mut rng)).collect())
        })
        .collect()
}

/// Integer cases made by hand, one per configuration of the algorithm.
fn hand_made_cases() -> Vec<(&'static str, FixedTriangle, FixedTriangle)> {
    let t = [[0, 0, 0], [8, 0, 0], [0, 8, 0]];
    vec![
        ("general crossing", t, [[1, 1, -4], [1, 1, 4], [5, 1, 4]]),
        ("general apart", t, [[1, 1, 1], [1, 1, 4], [5, 1, 4]]),
        (
            "vertex on the other's interior",
            t,
            [[1, 1, 0], [1, 1, 4], [5, 1, 4]],
        ),
        (
            "vertex touching vertex",
            t,
            [[8, 0, 0], [9, 0, 4], [9, 3, 4]],
        ),
        (
            "edge crossing edge",
            t,
            [[4, -1, -2], [4, 2, 2], [4, -3, 2]],
        ),
        (
            "planes meet, intervals disjoint",
            t,
            [[9, 9, -3], [9, 12, 3], [12, 9, 3]],
        ),
        (
            "intervals touch at a point",
            t,
            [[4, 4, -2], [4, 4, 2], [8, 8, 0]],
        ),
        (
            "coplanar overlapping",
            t,
            [[2, 2, 0], [10, 2, 0], [2, 10, 0]],
        ),
        ("coplanar contained", t, [[1, 1, 0], [2, 1, 0], [1, 2, 0]]),
        (
            "coplanar containing",
            t,
            [[-4, -4, 0], [20, -4, 0], [-4, 20, 0]],
        ),
        (
            "coplanar sharing an edge",
            t,
            [[8, 0, 0], [0, 8, 0], [8, 8, 0]],
        ),
        (
            "coplanar touching at a vertex",
            t,
            [[8, 0, 0], [12, 0, 0], [12, 4, 0]],
        ),
        (
            "coplanar vertex on an edge",
            t,
            [[4, 4, 0], [8, 8, 0], [12, 2, 0]],
        ),
        ("coplanar apart", t, [[5, 5, 0], [9, 5, 0], [5, 9, 0]]),
        (
            "coplanar collinear edges apart",
            t,
            [[9, 0, 0], [12, 0, 0], [10, -3, 0]],
        ),
        (
            "coplanar collinear edges overlapping",
            t,
            [[4, 0, 0], [12, 0, 0], [10, -3, 0]],
        ),
        (
            "coplanar tilted",
            [[0, 0, 0], [6, 0, 3], [0, 6, 3]],
            [[2, 2, 2], [6, 6, 6], [-2, 4, 1]],
        ),
        (
            "segment through the interior",
            t,
            [[2, 2, -3], [2, 2, 3], [2, 2, 0]],
        ),
        ("segment missing", t, [[9, 9, -3], [9, 9, 3], [9, 9, 1]]),
        (
            "segment ending on the plane inside",
            t,
            [[2, 2, 0], [2, 2, 3], [2, 2, 6]],
        ),
        (
            "segment ending on the plane outside",
            t,
            [[9, 9, 0], [9, 9, 3], [9, 9, 6]],
        ),
        (
            "segment above the plane",
            t,
            [[2, 2, 1], [2, 2, 3], [2, 2, 2]],
        ),
        (
            "segment in the plane crossing",
            t,
            [[-2, 2, 0], [10, 2, 0], [4, 2, 0]],
        ),
        (
            "segment in the plane inside",
            t,
            [[1, 1, 0], [3, 1, 0], [2, 1, 0]],
        ),
        (
            "segment in the plane apart",
            t,
            [[9, 9, 0], [12, 9, 0], [10, 9, 0]],
        ),
        (
            "segment in the plane touching a vertex",
            t,
            [[8, 0, 0], [12, 0, 0], [10, 0, 0]],
        ),
        (
            "segment with a repeated vertex",
            t,
            [[2, 2, -3], [2, 2, -3], [2, 2, 3]],
        ),
        (
            "segment through an edge",
            t,
            [[4, -2, 2], [4, 2, -2], [4, 0, 0]],
        ),
        (
            "segment through a vertex",
            t,
            [[-1, -1, -1], [1, 1, 1], [0, 0, 0]],
        ),
        ("point inside", t, [[2, 2, 0], [2, 2, 0], [2, 2, 0]]),
        ("point on an edge", t, [[4, 0, 0], [4, 0, 0], [4, 0, 0]]),
        ("point at a vertex", t, [[8, 0, 0], [8, 0, 0], [8, 0, 0]]),
        (
            "point outside in the plane",
            t,
            [[9, 9, 0], [9, 9, 0], [9, 9, 0]],
        ),
        ("point off the plane", t, [[2, 2, 1], [2, 2, 1], [2, 2, 1]]),
        (
            "segments crossing",
            [[0, 0, 0], [4, 4, 0], [2, 2, 0]],
            [[0, 4, 0], [4, 0, 0], [1, 3, 0]],
        ),
        (
            "segments skew",
            [[0, 0, 0], [4, 4, 0], [2, 2, 0]],
            [[0, 4, 1], [4, 0, 1], [1, 3, 1]],
        ),
        (
            "segments parallel",
            [[0, 0, 0], [4, 4, 0], [2, 2, 0]],
            [[1, 0, 0], [5, 4, 0], [3, 2, 0]],
        ),
        (
            "segments collinear overlapping",
            [[0, 0, 0], [4, 4, 4], [2, 2, 2]],
            [[3, 3, 3], [6, 6, 6], [5, 5, 5]],
        ),
        (
            "segments collinear touching",
            [[0, 0, 0], [4, 4, 4], [2, 2, 2]],
            [[4, 4, 4], [6, 6, 6], [5, 5, 5]],
        ),
        (
            "segments collinear apart",
            [[0, 0, 0], [4, 4, 4], [2, 2, 2]],
            [[5, 5, 5], [6, 6, 6], [7, 7, 7]],
        ),
        (
            "segments meeting at an end",
            [[0, 0, 0], [4, 0, 0], [2, 0, 0]],
            [[4, 0, 0], [4, 5, 2], [4, 5, 2]],
        ),
        (
            "segment T-junction",
            [[0, 0, 0], [4, 0, 0], [2, 0, 0]],
            [[2, 0, 0], [2, 3, 0], [2, 1, 0]],
        ),
        (
            "segments coplanar, projections cross in one axis only",
            [[0, 0, 0], [2, 2, 2], [1, 1, 1]],
            [[0, 2, 0], [2, 0, 2], [1, 1, 1]],
        ),
        (
            "segments, crossing in x-y only",
            [[0, 0, 0], [2, 2, 0], [1, 1, 0]],
            [[0, 2, 5], [2, 0, 5], [1, 1, 5]],
        ),
        (
            "point on a segment",
            [[0, 0, 0], [4, 4, 4], [2, 2, 2]],
            [[1, 1, 1], [1, 1, 1], [1, 1, 1]],
        ),
        (
            "point off a segment",
            [[0, 0, 0], [4, 4, 4], [2, 2, 2]],
            [[1, 1, 2], [1, 1, 2], [1, 1, 2]],
        ),
        (
            "points equal",
            [[3, 1, 2], [3, 1, 2], [3, 1, 2]],
            [[3, 1, 2], [3, 1, 2], [3, 1, 2]],
        ),
        (
            "points apart",
            [[3, 1, 2], [3, 1, 2], [3, 1, 2]],
            [[3, 1, 3], [3, 1, 3], [3, 1, 3]],
        ),
    ]
}

/// Hand-made configurations (coplanar, touching, degenerate) in all 72
/// orderings give the model's verdict, at the thesis's width and at 8 bits.
#[test]
fn hand_made_cases_in_all_orderings() {
    for width in [24, 8] {
        let mut pipeline = pipeline_for_width(width).unwrap();
        let mut check = Check::default();
        for (_, t1, t2) in hand_made_cases() {
            check.run(pipeline.as_mut(), &all_orderings(t1, t2));
        }
        check.report_and_assert(&format!("hand-made cases, W = {width}"));
    }
}

/// Small random integer triangles (every branch, many ties), triangles on
/// common integer planes, and triangles at the extremes of the coordinate
/// range (widest intermediate values).
#[test]
fn small_coplanar_and_extreme_integer_triangles() {
    for width in [8, 24, 32] {
        let mut pipeline = pipeline_for_width(width).unwrap();
        let mut check = Check::default();
        for (seed, range) in [(1, 1), (2, 2), (3, 3)] {
            check.run(
                pipeline.as_mut(),
                &small_integer_groups(seed + width as u64, range, 8, 250),
            );
        }
        check.run(
            pipeline.as_mut(),
            &coplanar_integer_groups(40 + width as u64, 8, 250),
        );
        check.run(pipeline.as_mut(), &extreme_groups(width, 7, 8, 250));
        check.report_and_assert(&format!(
            "small, coplanar and extreme integers, W = {width}"
        ));
    }
}

/// Quantized random pairs: random triangles in the unit cube and
/// near-degenerate ones, quantized into one frame per batch.
fn quantized_random(width: usize) {
    let pairs = env_usize("TRITRI_PAIRS", 20_000);
    let mut pipeline = pipeline_for_width(width).unwrap();
    let mut check = Check::default();
    let start = std::time::Instant::now();
    for raw in [
        random_pairs(pairs / 40 + 1, 11),
        random_near_degenerate_pairs(pairs / 40 + 1, 12),
    ] {
        let frame = Frame::fit(raw.iter().flat_map(|p| [&p.t1, &p.t2]), width as u32).unwrap();
        let n1 = 20;
        let groups: Vec<_> = raw
            .iter()
            .take(n1)
            .map(|b| {
                (
                    frame.quantize(&b.t1),
                    raw.iter()
                        .map(|p| frame.quantize(&p.t2))
                        .collect::<Vec<_>>(),
                )
            })
            .collect();
        check.run(pipeline.as_mut(), &groups);
    }
    let elapsed = start.elapsed().as_secs_f64();
    check.report_and_assert(&format!("quantized random pairs, W = {width}"));
    eprintln!("W = {width}: {:.0} pairs/s", check.pairs as f64 / elapsed);
}

#[test]
fn quantized_random_pairs_w24() {
    quantized_random(24);
}

#[test]
fn quantized_random_pairs_w16() {
    quantized_random(16);
}

#[test]
fn quantized_random_pairs_w32() {
    quantized_random(32);
}

/// The hard case suite (tritri_cosim::suites::hard_case_groups), each case
/// quantized in its own frame, in all 72 orderings: every case by default,
/// every N-th with `TRITRI_HARD_CASES=N`.
fn hard_case_suite_in_all_orderings(width: usize) {
    let step = hard_case_step();
    let mut pipeline = pipeline_for_width(width).unwrap();
    let mut check = Check::default();
    check.run(pipeline.as_mut(), &hard_case_groups(width as u32, step));
    let which = if step == 1 {
        "all".to_string()
    } else {
        format!("every {step}-th of")
    };
    check.report_and_assert(&format!(
        "hard cases ({which} {}) x 72 orderings, W = {width}",
        hard_case_count()
    ));
}

#[test]
fn hard_case_suite_in_all_orderings_w24() {
    hard_case_suite_in_all_orderings(24);
}

#[test]
fn hard_case_suite_in_all_orderings_w16() {
    hard_case_suite_in_all_orderings(16);
}

#[test]
fn hard_case_suite_in_all_orderings_w32() {
    hard_case_suite_in_all_orderings(32);
}

/// Measured cycles are `N1 + N1 N2 + L` (thesis, equation 3.2).
#[test]
fn cycles_are_n1_plus_n1_n2_plus_latency() {
    assert_eq!(
        latency(),
        43,
        "rtl-out/README.md and examples/cocotb/README.md state the latency"
    );
    let mut pipeline = pipeline_for_width(24).unwrap();
    assert_eq!(pipeline.latency(), latency());
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for (n1, n2) in [(1, 1), (1, 2), (2, 3), (5, 17), (3, 40)] {
        let bases: Vec<_> = (0..n1)
            .map(|_| random_triangle(&mut rng, -1000, 1000))
            .collect();
        let streamed: Vec<_> = (0..n2)
            .map(|_| random_triangle(&mut rng, -1000, 1000))
            .collect();
        let stream = TriangleStream::from_triangles(&bases, &streamed);
        let schedule: Vec<_> = stream.schedule().collect();
        let result =
            run_schedule_on(pipeline.as_mut(), &schedule, &HarnessOptions::default()).unwrap();
        assert_eq!(
            result.cycles,
            (n1 + n1 * n2 + latency()) as u64,
            "N1 = {n1}, N2 = {n2}"
        );
        assert_eq!(result.mismatches(&stream.expected(certified_intersects)), 0);
    }
}

/// With `advance` low the pipeline holds: outputs do not change and no
/// input is taken; with random stalls the verdicts are the same, in the
/// same order, as without.
#[test]
fn advance_low_holds_everything() {
    let mut pipeline = pipeline_for_width(24).unwrap();
    let groups = small_integer_groups(21, 3, 6, 40);
    let mut schedule = Vec::new();
    let mut expected = Vec::new();
    for (g, (base, streamed)) in groups.iter().enumerate() {
        schedule.push(PipelineInput {
            valid: true,
            bset: true,
            id: g as u32,
            vertices: flatten(base),
        });
        for (s, t) in streamed.iter().enumerate() {
            schedule.push(PipelineInput {
                valid: true,
                bset: false,
                id: s as u32,
                vertices: flatten(t),
            });
            expected.push((g as u32, s as u32, intersects(base, t)));
        }
    }
    let p = pipeline.as_mut();
    p.set_reset(true);
    p.set_input(&PipelineInput::default());
    p.clock_cycle();
    p.set_reset(false);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut next = 0;
    let mut got = Vec::new();
    let mut stalls = 0;
    let mut before = p.output();
    for _ in 0..10 * schedule.len() {
        let advance = rng.gen_bool(0.6);
        p.set_advance(advance);
        // A new input is taken only by an advancing edge; while stalled the
        // bus shows garbage, which must be ignored.
        let input = if advance {
            schedule.get(next).copied().unwrap_or_default()
        } else {
            PipelineInput {
                valid: rng.gen(),
                bset: rng.gen(),
                id: rng.gen(),
                vertices: [rng.gen_range(-9..9); 9],
            }
        };
        p.set_input(&input);
        p.clock_cycle();
        let after = p.output();
        if advance {
            next += 1;
            if after.valid {
                got.push((after.base_id, after.stream_id, after.hit));
            }
        } else {
            stalls += 1;
            assert_eq!(after, before, "outputs changed during a stall");
        }
        before = after;
        if got.len() == expected.len() {
            break;
        }
    }
    assert!(stalls > 100);
    assert_eq!(got, expected);
}

/// Runs `groups` on the `width`-bit pipeline with the shared rare-case
/// unit and asserts the model's verdicts, certificates included, and that
/// it held exactly the clocks `system::rare_case_model` counts for one
/// pipeline fed without gaps (`shared_path_cost`): a rare pair waits for
/// the unit, and nothing else. Returns (pairs, rare pairs, clocks held).
fn shared_path_run(width: usize, groups: &[PairGroup]) -> (usize, u64, u64) {
    let mut pipeline = pipeline_with(width, RareCasePath::Shared).unwrap();
    let (schedule, expected) = group_schedule(groups, certified_intersects);
    let result = run_schedule_on(pipeline.as_mut(), &schedule, &HarnessOptions::default()).unwrap();
    assert_eq!(result.verdicts, expected, "W = {width}");
    let cost = shared_path_cost(groups);
    assert_eq!(result.held, cost.stall_cycles, "W = {width}: clocks held");
    assert_eq!(
        result.cycles,
        schedule.len() as u64 + latency() as u64 + result.held,
        "W = {width}: N1 + N1 N2 + L + held"
    );
    let rare = cost.coplanar + cost.segments;
    (expected.len(), rare, result.held)
}

/// The shared rare-case path on the hand-made cases and small, coplanar
/// and extreme integers (most pairs rare, back to back), and on every 9th
/// hard case in all orderings.
#[test]
fn shared_rare_case_path_gives_the_models_verdicts_and_holds() {
    let mut groups = Vec::new();
    for (_, t1, t2) in hand_made_cases() {
        groups.extend(all_orderings(t1, t2));
    }
    groups.extend(small_integer_groups(61, 2, 6, 120));
    groups.extend(coplanar_integer_groups(62, 6, 120));
    for width in [8, 24] {
        let mut groups = groups.clone();
        groups.extend(extreme_groups(width, 63, 4, 60));
        let (pairs, rare, held) = shared_path_run(width, &groups);
        eprintln!("shared path, small integers, W = {width}: {pairs} pairs, {rare} rare, {held} clocks held");
        assert!(rare > pairs as u64 / 4 && held > rare);
    }
    // Every 9th case at most (the rare pairs are many).
    let step = hard_case_step().max(9);
    let (pairs, rare, held) = shared_path_run(16, &hard_case_groups(16, step));
    eprintln!("shared path, every {step}-th hard case x 72 orderings, W = 16: {pairs} pairs, {rare} rare, {held} clocks held");
    assert!(rare > 1000);
}

/// With the shared path, `advance` low and `hold` together: the driver
/// lowers `advance` at random and offers the next input only on a clock
/// that takes it (advance high, hold low); the verdicts are the model's,
/// in order.
#[test]
fn shared_rare_case_path_under_back_pressure() {
    let mut pipeline = pipeline_with(16, RareCasePath::Shared).unwrap();
    let mut groups = coplanar_integer_groups(71, 4, 50);
    groups.extend(small_integer_groups(72, 1, 4, 50));
    let (schedule, expected) = group_schedule(&groups, certified_intersects);
    let p = pipeline.as_mut();
    p.set_reset(true);
    p.set_input(&PipelineInput::default());
    p.clock_cycle();
    p.set_reset(false);
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    let (mut next, mut held, mut low) = (0, 0, 0);
    let mut got = Vec::new();
    for _ in 0..20 * schedule.len() {
        let advance = rng.gen_bool(0.7);
        p.set_advance(advance);
        p.set_input(&schedule.get(next).copied().unwrap_or_default());
        let hold = p.hold();
        p.clock_cycle();
        if !advance {
            low += 1;
        } else if hold {
            held += 1;
        } else {
            next += 1;
        }
        let out = p.output();
        if out.valid && advance && !hold {
            got.push((out.base_id, out.stream_id, out.hit, out.certain));
        }
        if got.len() == expected.len() {
            break;
        }
    }
    let expected: Vec<_> = expected
        .iter()
        .map(|e| (e.base_id, e.stream_id, e.hit, e.certain))
        .collect();
    eprintln!(
        "shared path under back-pressure: {} pairs, {low} clocks with advance low, {held} held",
        got.len()
    );
    assert!(low > 100 && held > 100);
    assert_eq!(got, expected);
}

/// `reset` clears the valid bits: pairs in flight produce no verdict, and
/// the next run is unaffected.
#[test]
fn reset_clears_valid_bits() {
    let mut pipeline = pipeline_for_width(16).unwrap();
    let p = pipeline.as_mut();
    let t = [[0, 0, 0], [8, 0, 0], [0, 8, 0]];
    p.set_input(&PipelineInput {
        valid: true,
        bset: true,
        id: 1,
        vertices: flatten(&t),
    });
    p.clock_cycle();
    for i in 0..10 {
        p.set_input(&PipelineInput {
            valid: true,
            bset: false,
            id: i,
            vertices: flatten(&t),
        });
        p.clock_cycle();
    }
    p.set_input(&PipelineInput::default());
    p.set_reset(true);
    p.clock_cycle();
    p.set_reset(false);
    for _ in 0..2 * latency() {
        p.clock_cycle();
        assert!(!p.output().valid, "a verdict survived the reset");
    }
    let groups = vec![(t, vec![t, [[1, 1, 1], [2, 2, 2], [1, 2, 3]]])];
    let mut check = Check::default();
    check.run(p, &groups);
    check.report_and_assert("after reset");
}

/// A VCD trace of a small run is written and names the top's ports.
#[test]
fn vcd_trace_of_a_small_run() {
    let path = std::env::temp_dir().join(format!("tritri_rusthdl_{}.vcd", std::process::id()));
    let t = [[0, 0, 0], [8, 0, 0], [0, 8, 0]];
    let stream = TriangleStream::from_triangles(&[t], &[t, [[9, 9, 9], [9, 9, 10], [9, 10, 9]]]);
    let options = HarnessOptions {
        vcd: Some(path.clone()),
    };
    let result = tritri_cosim::rusthdl_harness::run_stream(16, &stream, &options).unwrap();
    assert_eq!(
        result.verdicts.iter().map(|v| v.hit).collect::<Vec<_>>(),
        vec![true, false]
    );
    assert_eq!(result.cycles, 3 + latency() as u64);
    let vcd = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).ok();
    assert!(vcd.contains("$enddefinitions") && vcd.contains("out_hit") && vcd.contains("in_bset"));
    assert!(vcd.lines().filter(|l| l.starts_with('#')).count() >= 2 * result.cycles as usize);
}

fn flatten(t: &FixedTriangle) -> [i64; 9] {
    tritri_rtl::pipeline::pipeline_for_width::flatten(t)
}
