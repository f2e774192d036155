//! Exact geometric predicates, the only thing the exact Devillers–Guigue
//! algorithm ([`crate::devillers_guigue`]) needs from an arithmetic.
//!
//! Two kernels implement it: [`crate::exact_f64::ExactF64`] (adaptive exact
//! predicates on f64 coordinates, the ground truth) and
//! [`crate::fixed_point::FixedPoint`] (exact integer arithmetic on W-bit
//! coordinates, the model of the hardware).

use crate::sign::Sign;
use std::cmp::Ordering;

/// Exact predicates on points of type `Self::Point`.
///
/// Every method must return the exact sign / order for the exact input
/// values; that is what makes the algorithm built on it exact.
pub trait ExactKernel {
    type Point: Copy;

    /// Sign of `[a,b,c,d] = (d-a)·((b-a)×(c-a))`, the thesis's orientation
    /// determinant: positive when `d` lies on the side the normal
    /// `(b-a)×(c-a)` points to.
    fn orient3d(a: Self::Point, b: Self::Point, c: Self::Point, d: Self::Point) -> Sign;

    /// Sign of component `axis` of `(b-a)×(c-a)`: orient2d of the projection
    /// that drops coordinate `axis`, taken in the coordinate order
    /// `(axis+1, axis+2) mod 3` so that it agrees with the normal's component.
    fn orient2d(axis: usize, a: Self::Point, b: Self::Point, c: Self::Point) -> Sign;

    /// Order of coordinate `axis` of `a` and `b`.
    fn compare_coordinate(axis: usize, a: Self::Point, b: Self::Point) -> Ordering;

    /// An axis along which the normal `(b-a)×(c-a)` has its largest magnitude
    /// component; the caller guarantees the normal is not zero, and the
    /// answer's component must be non-zero (so the projection dropping it is
    /// one-to-one on the triangle's plane).
    fn dominant_normal_axis(a: Self::Point, b: Self::Point, c: Self::Point) -> usize;

    /// Lexicographic (x, y, z) order; on collinear points its minimum and
    /// maximum are the two ends of the segment they span.
    fn compare_lexicographic(a: Self::Point, b: Self::Point) -> Ordering {
        Self::compare_coordinate(0, a, b)
            .then_with(|| Self::compare_coordinate(1, a, b))
            .then_with(|| Self::compare_coordinate(2, a, b))
    }
}
