//! Quantization of a batch of triangles into one W-bit frame.
//!
//! One frame for the whole batch: the same step `h` on every axis (so the
//! geometry is only scaled, never sheared), the frame's centre at the centre
//! of the batch's bounding box, round to nearest. The step is chosen with a
//! one-unit margin so that every rounded coordinate lies in
//! `[-2^(W-1) + 1, 2^(W-1) - 1]`: overflow cannot happen.

use crate::fixed_point::{FixedPoint3, FixedTriangle};
use crate::triangle::{Point, Triangle, TrianglePair};
use crate::widths::{FixedWidths, WidthOutOfRange};

/// `x.round() as i64` (half away from zero) for `|x| < 2^62`, without the
/// call to libm's `round` (the baseline x86-64 target has no rounding
/// instruction): add the largest double below one half, with x's sign, and
/// truncate. Below 2^52 the sum lands on the next integer exactly when the
/// fraction is at least one half (the sum of a half-integer rounds up to the
/// integer: ties go to even and the even neighbour is the integer); from
/// 2^52 on, x is an integer and the sum rounds back to it.
#[inline(always)]
fn round_half_away_from_zero(x: f64) -> i64 {
    const JUST_BELOW_HALF: f64 = 0.49999999999999994;
    (x + JUST_BELOW_HALF.copysign(x)) as i64
}

/// The map from f64 coordinates to W-bit integers: `q = round((x - centre) / step)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub widths: FixedWidths,
    pub centre: [f64; 3],
    /// The grid step h: the quantization error of a coordinate is at most h/2.
    pub step: f64,
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QuantizeError {
    #[error(transparent)]
    Width(#[from] WidthOutOfRange),
    #[error("coordinate {value} of triangle {triangle} is not finite")]
    NotFinite { triangle: usize, value: f64 },
}

impl Frame {
    /// The frame that holds every vertex of `triangles` at width `width`.
    pub fn fit<'a>(
        triangles: impl IntoIterator<Item = &'a Triangle>,
        width: u32,
    ) -> Result<Frame, QuantizeError> {
        let widths = FixedWidths::new(width)?;
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for (i, t) in triangles.into_iter().enumerate() {
            // Branch-free per triangle (plain comparisons, one finiteness
            // test): this loop runs over every vertex of every batch.
            let mut finite = true;
            for p in t {
                for k in 0..3 {
                    let v = p[k];
                    finite &= v.is_finite();
                    lo[k] = if v < lo[k] { v } else { lo[k] };
                    hi[k] = if v > hi[k] { v } else { hi[k] };
                }
            }
            if !finite {
                let value = t
                    .iter()
                    .flatten()
                    .copied()
                    .find(|v| !v.is_finite())
                    .unwrap_or(f64::NAN);
                return Err(QuantizeError::NotFinite { triangle: i, value });
            }
        }
        Ok(Frame::of_bounds(widths, lo, hi))
    }

    /// The frame [`Frame::fit`] gives for triangles whose vertices span
    /// `lo ..= hi` (finite), from the bounds alone: a caller that has the
    /// bounds saves the pass over the vertices. `lo[0] > hi[0]` stands for
    /// no triangles.
    pub fn fit_bounds(lo: [f64; 3], hi: [f64; 3], width: u32) -> Result<Frame, QuantizeError> {
        Ok(Frame::of_bounds(FixedWidths::new(width)?, lo, hi))
    }

    fn of_bounds(widths: FixedWidths, lo: [f64; 3], hi: [f64; 3]) -> Frame {
        let width = widths.coordinate;
        if lo[0] > hi[0] {
            // No triangles: any frame will do.
            return Frame {
                widths,
                centre: [0.0; 3],
                step: 1.0,
            };
        }
        // A batch with coordinates of both signs near ±1e308 spans more than
        // f64::MAX: `hi - lo` overflows to infinity, its halves do not (and
        // halving a normal number is exact, so the step below is the same
        // quotient).
        let centre = [0, 1, 2].map(|k| {
            let span = hi[k] - lo[k];
            if span.is_finite() {
                lo[k] + span / 2.0
            } else {
                lo[k] / 2.0 + hi[k] / 2.0
            }
        });
        let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        // 2^W - 4 steps across the extent leave more than one unit of margin
        // at each end for rounding of the centre and the division.
        let steps = ((1u64 << width) - 4) as f64;
        let extent_per_step = if extent.is_finite() {
            extent / steps
        } else {
            (0..3)
                .map(|k| hi[k] / 2.0 - lo[k] / 2.0)
                .fold(0.0, f64::max)
                / (steps / 2.0)
        };
        // The centre is off by up to half an ulp of the largest magnitude M
        // present: a step of at least 2·EPSILON·M keeps that under a quarter
        // step, inside the margin, even when the extent is only a few ulps
        // wide (e.g. 1e9 and its next f64). A normal, not subnormal, step
        // keeps the division accurate for tiny extents.
        let magnitude = (0..3)
            .map(|k| lo[k].abs().max(hi[k].abs()))
            .fold(0.0, f64::max);
        let step = if extent > 0.0 {
            extent_per_step
                .max(2.0 * f64::EPSILON * magnitude)
                .max(f64::MIN_POSITIVE)
        } else {
            1.0
        };
        Frame {
            widths,
            centre,
            step,
        }
    }

    /// The integer grid point nearest to `p`.
    #[inline]
    pub fn quantize_point(&self, p: Point) -> FixedPoint3 {
        let q = [0, 1, 2].map(|k| round_half_away_from_zero((p[k] - self.centre[k]) / self.step));
        debug_assert!(q
            .iter()
            .all(|&v| v >= self.widths.min_coordinate() && v <= self.widths.max_coordinate()));
        q
    }

    /// `[quantize_point(v) for v in t]`, written over the nine coordinates
    /// at once so that the divisions vectorize.
    #[inline]
    pub fn quantize(&self, t: &Triangle) -> FixedTriangle {
        let mut scaled = [0.0f64; 9];
        for (k, s) in scaled.iter_mut().enumerate() {
            *s = (t[k / 3][k % 3] - self.centre[k % 3]) / self.step;
        }
        let q = scaled.map(round_half_away_from_zero);
        let out = [[q[0], q[1], q[2]], [q[3], q[4], q[5]], [q[6], q[7], q[8]]];
        debug_assert_eq!(out, t.map(|p| self.quantize_point(p)));
        out
    }

    /// The f64 point a grid point stands for.
    pub fn dequantize_point(&self, q: FixedPoint3) -> Point {
        [0, 1, 2].map(|k| self.centre[k] + q[k] as f64 * self.step)
    }
}

/// A pair quantized in a frame of its own (the frame that fits just its six
/// vertices), so it keeps as much of its geometry as `width` bits allow: how
/// the tests and the hard-case vectors quantize single cases.
pub fn quantize_pair(
    pair: &TrianglePair,
    width: u32,
) -> Result<(FixedTriangle, FixedTriangle), QuantizeError> {
    let frame = Frame::fit([&pair.t1, &pair.t2], width)?;
    Ok((frame.quantize(&pair.t1), frame.quantize(&pair.t2)))
}

#[cfg(test)]
mod rounding_tests {
    use super::round_half_away_from_zero;

    /// The fast rounding is `f64::round` (half away from zero), including
    /// the neighbours of every half-integer and the largest magnitudes used.
    #[test]
    fn agrees_with_f64_round() {
        let mut xs = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            0.49999999999999994,
            -0.49999999999999994,
        ];
        for k in [
            1.0f64,
            3.0,
            1e3,
            4503599627370495.0,
            4503599627370496.0,
            9007199254740993.0,
            2f64.powi(61),
        ] {
            for base in [k, k + 0.5, k - 0.5] {
                let mut v = base;
                for _ in 0..3 {
                    xs.extend([v, -v]);
                    v = f64::from_bits(v.to_bits() + 1);
                }
                let mut v = base;
                for _ in 0..3 {
                    xs.extend([v, -v]);
                    v = f64::from_bits(v.to_bits() - 1);
                }
            }
        }
        // And random values of every magnitude up to 2^62, fractions included.
        let mut state = 0x9e3779b97f4a7c15u64;
        for _ in 0..1_000_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let magnitude = 2f64.powi((state % 63) as i32);
            let unit = (state >> 11) as f64 / (1u64 << 53) as f64;
            xs.push(if state & 1 == 0 {
                unit * magnitude
            } else {
                -unit * magnitude
            });
        }
        for x in xs {
            assert_eq!(round_half_away_from_zero(x), x.round() as i64, "{x:e}");
        }
    }
}
