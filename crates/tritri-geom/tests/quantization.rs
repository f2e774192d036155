//! Quantization (`Frame::fit` + `Frame::quantize`): for every width 8..=32
//! and extreme inputs (huge offsets, tiny extents, a single point, mixed
//! magnitudes), every quantized coordinate lies in
//! `[min_coordinate, max_coordinate]` and stands for its input within half a
//! step, up to the rounding of the two f64 operations that compute it:
//! `|x - (centre + q * step)| <= step * (1/2 + 2^(W-52))`, measured exactly in
//! rational arithmetic on the frame as stored.
//!
//! Why that slack: `q = round(fl(fl(x - c) / h))`; the two roundings put
//! `fl(fl(x - c) / h)` within a relative `2u(1 + u)` of `(x - c) / h`, whose
//! magnitude is below `2^(W-1)` steps, so at most `2^(W-52)` steps away.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Signed;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_geom::quantize::Frame;
use tritri_geom::widths::{MAX_WIDTH, MIN_WIDTH};
use tritri_geom::Triangle;

fn rational(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite")
}

/// Checks the two properties for one batch at one width; returns the worst
/// error in steps.
fn check_batch(name: &str, triangles: &[Triangle], width: u32) -> f64 {
    let frame = Frame::fit(triangles, width).unwrap_or_else(|e| panic!("{name}: W={width}: {e}"));
    assert!(
        frame.step.is_finite() && frame.step > 0.0,
        "{name}: W={width}: step {}",
        frame.step
    );
    let (lo, hi) = (frame.widths.min_coordinate(), frame.widths.max_coordinate());
    let step = rational(frame.step);
    let slack = rational(0.5 + 2f64.powi(width as i32 - 52));
    let mut worst: f64 = 0.0;
    for t in triangles {
        let q = frame.quantize(t);
        for (p, qp) in t.iter().zip(q.iter()) {
            for k in 0..3 {
                assert!(
                    (lo..=hi).contains(&qp[k]),
                    "{name}: W={width}: coordinate {:e} quantized to {} outside [{lo}, {hi}] (frame {frame:?})",
                    p[k],
                    qp[k]
                );
                let stands_for = rational(frame.centre[k])
                    + BigRational::from_integer(BigInt::from(qp[k])) * &step;
                let error = (rational(p[k]) - stands_for).abs();
                let in_steps = &error / &step;
                assert!(
                    in_steps <= slack,
                    "{name}: W={width}: coordinate {:e} -> {} is {:.6} steps away (frame {frame:?})",
                    p[k],
                    qp[k],
                    num_traits::ToPrimitive::to_f64(&in_steps).unwrap()
                );
                worst = worst.max(num_traits::ToPrimitive::to_f64(&in_steps).unwrap());
            }
        }
    }
    worst
}

fn unit_triangles(rng: &mut ChaCha8Rng, n: usize) -> Vec<Triangle> {
    (0..n)
        .map(|_| [0, 1, 2].map(|_| [rng.gen::<f64>(), rng.gen::<f64>(), rng.gen::<f64>()]))
        .collect()
}

fn transformed(ts: &[Triangle], scale: f64, offset: [f64; 3]) -> Vec<Triangle> {
    ts.iter()
        .map(|t| t.map(|p| [0, 1, 2].map(|k| p[k] * scale + offset[k])))
        .collect()
}

/// Extreme batches: name and triangles.
fn extreme_batches() -> Vec<(String, Vec<Triangle>)> {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let base = unit_triangles(&mut rng, 8);
    let mut batches = Vec::new();
    for offset in [1e5, 1e9, 1e15, 1e100, -1e300] {
        for scale in [1.0, 1e-6, 1e-12] {
            batches.push((
                format!("offset {offset:e}, extent {scale:e}"),
                transformed(&base, scale, [offset, -offset, offset / 3.0]),
            ));
        }
    }
    for scale in [1e-12, 1e-100, 1e-300, 1e-305] {
        batches.push((
            format!("tiny extent {scale:e} at the origin"),
            transformed(&base, scale, [0.0; 3]),
        ));
    }
    for scale in [1e100, 1e300] {
        batches.push((
            format!("huge extent {scale:e}"),
            transformed(&base, scale, [0.0; 3]),
        ));
    }
    // Extents beyond f64::MAX: `hi - lo` itself overflows.
    let max = f64::MAX;
    batches.push((
        "extent beyond f64::MAX".into(),
        vec![
            [[-max, -1e308, 0.0], [max, 1e308, 1.0], [0.0, 0.0, -max]],
            [[1e300, -1e300, max]; 3],
        ],
    ));
    batches.push((
        "two points at -f64::MAX and f64::MAX".into(),
        vec![[[-max; 3]; 3], [[max; 3]; 3]],
    ));
    let p = [1e9 + 0.25, -3.5, 7.0];
    batches.push(("single point".into(), vec![[p, p, p]]));
    batches.push(("single point at the origin".into(), vec![[[0.0; 3]; 3]]));
    batches.push((
        "two points one ulp apart".into(),
        vec![[p, p, p], [[p[0].next_up(), p[1], p[2]]; 3]],
    ));
    batches.push((
        "flat in z".into(),
        transformed(&base, 1.0, [0.0; 3])
            .into_iter()
            .map(|t| t.map(|q| [q[0], q[1], 2.0]))
            .collect(),
    ));
    batches.push((
        "mixed magnitudes".into(),
        vec![
            [
                [1e-300, 0.0, 0.0],
                [1.0, 1e-300, -1e-300],
                [0.5, 0.5, 1e-200],
            ],
            [[-1.0, 0.25, 1.0], [1e-20, 1e-10, 0.0], [0.0, 0.0, 0.0]],
        ],
    ));
    for _ in 0..50 {
        let scale = 10f64.powi(rng.gen_range(-250..250));
        let offset =
            [0, 1, 2].map(|_| rng.gen_range(-1.0..1.0) * 10f64.powi(rng.gen_range(-250..250)));
        let n = rng.gen_range(1..10);
        batches.push((
            format!("random scale {scale:e}, offset {offset:?}"),
            transformed(&unit_triangles(&mut rng, n), scale, offset),
        ));
    }
    batches
}

/// Every width 8..=32, every extreme batch: in range and within half a step.
#[test]
fn quantized_coordinates_are_in_range_and_within_half_a_step() {
    let batches = extreme_batches();
    let mut worst: f64 = 0.0;
    let mut checked = 0usize;
    for width in MIN_WIDTH..=MAX_WIDTH {
        for (name, triangles) in &batches {
            worst = worst.max(check_batch(name, triangles, width));
            checked += triangles.len() * 9;
        }
    }
    eprintln!(
        "quantization: {} batches x {} widths, {checked} coordinates, worst error {worst:.9} steps",
        batches.len(),
        MAX_WIDTH - MIN_WIDTH + 1
    );
}

/// The frame reaches the corners of the range: the extreme coordinates of
/// the batch quantize to within one unit of the ends (the step is not
/// wastefully large).
#[test]
fn the_frame_uses_the_range() {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let triangles = unit_triangles(&mut rng, 20);
    for width in MIN_WIDTH..=MAX_WIDTH {
        let frame = Frame::fit(&triangles, width).unwrap();
        let q: Vec<i64> = triangles
            .iter()
            .flat_map(|t| frame.quantize(t))
            .flatten()
            .collect();
        let (lo, hi) = (*q.iter().min().unwrap(), *q.iter().max().unwrap());
        let max = frame.widths.max_coordinate();
        assert!(
            hi >= max - 2 || lo <= -max + 2,
            "W={width}: quantized range [{lo}, {hi}] of [-{max}, {max}]"
        );
    }
}
