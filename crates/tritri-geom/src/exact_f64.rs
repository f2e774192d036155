//! The ground truth: Devillers–Guigue on exact predicates over the f64
//! coordinates as given (Shewchuk's adaptive orient2d / orient3d from the
//! `robust` crate, which are exact for every finite f64 input whose
//! intermediate products neither overflow nor underflow).

use crate::devillers_guigue;
use crate::kernel::ExactKernel;
use crate::sign::Sign;
use crate::triangle::{Point, Triangle};
use robust::{Coord, Coord3D};
use std::cmp::Ordering;

/// Exact predicates on f64 points.
pub struct ExactF64;

#[inline]
fn c3(p: Point) -> Coord3D<f64> {
    Coord3D { x: p[0], y: p[1], z: p[2] }
}

impl ExactKernel for ExactF64 {
    type Point = Point;

    #[inline]
    fn orient3d(a: Point, b: Point, c: Point, d: Point) -> Sign {
        // robust::orient3d is det[a-d, b-d, c-d], which is -[a,b,c,d].
        Sign::of_f64(robust::orient3d(c3(a), c3(b), c3(c), c3(d))).flip()
    }

    #[inline]
    fn orient2d(axis: usize, a: Point, b: Point, c: Point) -> Sign {
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        let p = |v: Point| Coord { x: v[i], y: v[j] };
        Sign::of_f64(robust::orient2d(p(a), p(b), p(c)))
    }

    #[inline]
    fn compare_coordinate(axis: usize, a: Point, b: Point) -> Ordering {
        a[axis].total_cmp(&b[axis])
    }

    fn dominant_normal_axis(a: Point, b: Point, c: Point) -> usize {
        // The float normal picks the largest component; the exact sign makes
        // sure the chosen component is really non-zero.
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        (0..3)
            .filter(|&k| !Self::orient2d(k, a, b, c).is_zero())
            .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()).then(j.cmp(&i)))
            .expect("dominant_normal_axis is called on non-degenerate triangles only")
    }
}

/// Do the closed triangles intersect? Exact on the f64 coordinates.
pub fn intersects(t1: &Triangle, t2: &Triangle) -> bool {
    devillers_guigue::intersects::<ExactF64>(*t1, *t2)
}
