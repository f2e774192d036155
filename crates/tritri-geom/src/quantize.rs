//! Quantization of a batch of triangles into one W-bit frame.
//!
//! One frame for the whole batch: the same step `h` on every axis (so the
//! geometry is only scaled, never sheared), the frame's centre at the centre
//! of the batch's bounding box, round to nearest. The step is chosen with a
//! one-unit margin so that every rounded coordinate lies in
//! `[-2^(W-1) + 1, 2^(W-1) - 1]`: overflow cannot happen.

use crate::fixed_point::{FixedPoint3, FixedTriangle};
use crate::triangle::{Point, Triangle};
use crate::widths::{FixedWidths, WidthOutOfRange};

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
    pub fn fit<'a>(triangles: impl IntoIterator<Item = &'a Triangle>, width: u32) -> Result<Frame, QuantizeError> {
        let widths = FixedWidths::new(width)?;
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for (i, t) in triangles.into_iter().enumerate() {
            for p in t {
                for k in 0..3 {
                    if !p[k].is_finite() {
                        return Err(QuantizeError::NotFinite { triangle: i, value: p[k] });
                    }
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        if lo[0] > hi[0] {
            // No triangles: any frame will do.
            return Ok(Frame { widths, centre: [0.0; 3], step: 1.0 });
        }
        let centre = [0, 1, 2].map(|k| lo[k] + (hi[k] - lo[k]) / 2.0);
        let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        // 2^W - 4 steps across the extent leave more than one unit of margin
        // at each end for rounding of the centre and the division.
        let steps = ((1u64 << width) - 4) as f64;
        let step = if extent > 0.0 { extent / steps } else { 1.0 };
        Ok(Frame { widths, centre, step })
    }

    /// The integer grid point nearest to `p`.
    pub fn quantize_point(&self, p: Point) -> FixedPoint3 {
        let q = [0, 1, 2].map(|k| ((p[k] - self.centre[k]) / self.step).round() as i64);
        debug_assert!(q.iter().all(|&v| v >= self.widths.min_coordinate() && v <= self.widths.max_coordinate()));
        q
    }

    pub fn quantize(&self, t: &Triangle) -> FixedTriangle {
        t.map(|p| self.quantize_point(p))
    }

    /// The f64 point a grid point stands for.
    pub fn dequantize_point(&self, q: FixedPoint3) -> Point {
        [0, 1, 2].map(|k| self.centre[k] + q[k] as f64 * self.step)
    }
}
