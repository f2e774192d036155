//! The published Guigue–Devillers code (JGT 8(1), 2003, "Updated December
//! 2003" version of `tri_tri_overlap_test_3d`) translated to Rust as it is,
//! in plain floating point, generic over f64 and f32.
//!
//! This is the fast, non-robust reference whose errors the project measures:
//! predicate values are rounded, and the code decides on *products* of them
//! (`dp1 * dq1 > 0`, a degree-6 polynomial that can round, underflow or
//! overflow where the signs themselves are clear). Degenerate triangles get
//! whatever answer the arithmetic happens to give. The exact algorithm is
//! [`crate::devillers_guigue`]; do not fix this module, it models the C code.
//!
//! Each C macro is one function with the macro's name in snake case; the
//! macros' `return` statements become the function's result.
//!
//! ```
//! use tritri_geom::published_float;
//! let t1 = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! let t2 = [[0.2, 0.2, -1.0], [0.2, 0.2, 1.0], [0.9, 0.9, 0.5]];
//! assert!(published_float::intersects_f64(&t1, &t2));
//! assert!(published_float::intersects_f32(&t1, &t2));
//! ```

use crate::triangle::Triangle;
use std::fmt::Debug;
use std::ops::{Add, Mul, Neg, Sub};

/// The floating-point operations the published code uses.
pub trait Float:
    Copy
    + PartialOrd
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Neg<Output = Self>
{
    const ZERO: Self;
    /// Rounds an f64 to this type (round to nearest).
    fn from_f64(v: f64) -> Self;
}

impl Float for f64 {
    const ZERO: f64 = 0.0;
    #[inline(always)]
    fn from_f64(v: f64) -> f64 {
        v
    }
}

impl Float for f32 {
    const ZERO: f32 = 0.0;
    #[inline(always)]
    fn from_f64(v: f64) -> f32 {
        v as f32
    }
}

type V3<F> = [F; 3];
type V2<F> = [F; 2];

#[inline(always)]
fn sub<F: Float>(a: V3<F>, b: V3<F>) -> V3<F> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
fn cross<F: Float>(a: V3<F>, b: V3<F>) -> V3<F> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
fn dot<F: Float>(a: V3<F>, b: V3<F>) -> F {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `tri_tri_overlap_test_3d` on triangles given in f64, computed in `F`
/// (the coordinates are rounded to `F` first).
#[inline]
pub fn intersects<F: Float>(t1: &Triangle, t2: &Triangle) -> bool {
    // Written out: `t.map(..)` is not always optimized away for f64.
    let v = |p: &[f64; 3]| [F::from_f64(p[0]), F::from_f64(p[1]), F::from_f64(p[2])];
    let c = |t: &Triangle| [v(&t[0]), v(&t[1]), v(&t[2])];
    let [p1, q1, r1] = c(t1);
    let [p2, q2, r2] = c(t2);
    tri_tri_overlap_test_3d(p1, q1, r1, p2, q2, r2)
}

/// The published code in double precision.
pub fn intersects_f64(t1: &Triangle, t2: &Triangle) -> bool {
    intersects::<f64>(t1, t2)
}

/// The published code in single precision, on the inputs rounded to f32.
pub fn intersects_f32(t1: &Triangle, t2: &Triangle) -> bool {
    intersects::<f32>(t1, t2)
}

/// `tri_tri_overlap_test_3d(p1,q1,r1,p2,q2,r2)`: 1 if the closed triangles
/// overlap (in exact arithmetic; here in `F`).
#[inline]
pub fn tri_tri_overlap_test_3d<F: Float>(
    p1: V3<F>,
    q1: V3<F>,
    r1: V3<F>,
    p2: V3<F>,
    q2: V3<F>,
    r2: V3<F>,
) -> bool {
    let zero = F::ZERO;

    // Distance signs of p1, q1, r1 to the plane of (p2, q2, r2).
    let n2 = cross(sub(p2, r2), sub(q2, r2));
    let dp1 = dot(sub(p1, r2), n2);
    let dq1 = dot(sub(q1, r2), n2);
    let dr1 = dot(sub(r1, r2), n2);
    if dp1 * dq1 > zero && dp1 * dr1 > zero {
        return false;
    }

    // Distance signs of p2, q2, r2 to the plane of (p1, q1, r1).
    let n1 = cross(sub(q1, p1), sub(r1, p1));
    let dp2 = dot(sub(p2, r1), n1);
    let dq2 = dot(sub(q2, r1), n1);
    let dr2 = dot(sub(r2, r1), n1);
    if dp2 * dq2 > zero && dp2 * dr2 > zero {
        return false;
    }

    // Permutation in a canonical form of T1's vertices.
    let t = |a, b, c, d, e, f, g, h, i| tri_tri_3d(a, b, c, d, e, f, g, h, i, n1, n2);
    if dp1 > zero {
        if dq1 > zero {
            t(r1, p1, q1, p2, r2, q2, dp2, dr2, dq2)
        } else if dr1 > zero {
            t(q1, r1, p1, p2, r2, q2, dp2, dr2, dq2)
        } else {
            t(p1, q1, r1, p2, q2, r2, dp2, dq2, dr2)
        }
    } else if dp1 < zero {
        if dq1 < zero {
            t(r1, p1, q1, p2, q2, r2, dp2, dq2, dr2)
        } else if dr1 < zero {
            t(q1, r1, p1, p2, q2, r2, dp2, dq2, dr2)
        } else {
            t(p1, q1, r1, p2, r2, q2, dp2, dr2, dq2)
        }
    } else if dq1 < zero {
        if dr1 >= zero {
            t(q1, r1, p1, p2, r2, q2, dp2, dr2, dq2)
        } else {
            t(p1, q1, r1, p2, q2, r2, dp2, dq2, dr2)
        }
    } else if dq1 > zero {
        if dr1 > zero {
            t(p1, q1, r1, p2, r2, q2, dp2, dr2, dq2)
        } else {
            t(q1, r1, p1, p2, q2, r2, dp2, dq2, dr2)
        }
    } else if dr1 > zero {
        t(r1, p1, q1, p2, q2, r2, dp2, dq2, dr2)
    } else if dr1 < zero {
        t(r1, p1, q1, p2, r2, q2, dp2, dr2, dq2)
    } else {
        coplanar_tri_tri3d(p1, q1, r1, p2, q2, r2, n1, n2)
    }
}

/// The macro `TRI_TRI_3D`: permutation of T2's vertices into canonical form,
/// then `CHECK_MIN_MAX`. As in the C macro, the coplanar fall-back receives
/// the macro's (permuted) arguments.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn tri_tri_3d<F: Float>(
    p1: V3<F>,
    q1: V3<F>,
    r1: V3<F>,
    p2: V3<F>,
    q2: V3<F>,
    r2: V3<F>,
    dp2: F,
    dq2: F,
    dr2: F,
    n1: V3<F>,
    n2: V3<F>,
) -> bool {
    let zero = F::ZERO;
    if dp2 > zero {
        if dq2 > zero {
            check_min_max(p1, r1, q1, r2, p2, q2)
        } else if dr2 > zero {
            check_min_max(p1, r1, q1, q2, r2, p2)
        } else {
            check_min_max(p1, q1, r1, p2, q2, r2)
        }
    } else if dp2 < zero {
        if dq2 < zero {
            check_min_max(p1, q1, r1, r2, p2, q2)
        } else if dr2 < zero {
            check_min_max(p1, q1, r1, q2, r2, p2)
        } else {
            check_min_max(p1, r1, q1, p2, q2, r2)
        }
    } else if dq2 < zero {
        if dr2 >= zero {
            check_min_max(p1, r1, q1, q2, r2, p2)
        } else {
            check_min_max(p1, q1, r1, p2, q2, r2)
        }
    } else if dq2 > zero {
        if dr2 > zero {
            check_min_max(p1, r1, q1, p2, q2, r2)
        } else {
            check_min_max(p1, q1, r1, q2, r2, p2)
        }
    } else if dr2 > zero {
        check_min_max(p1, q1, r1, r2, p2, q2)
    } else if dr2 < zero {
        check_min_max(p1, r1, q1, r2, p2, q2)
    } else {
        coplanar_tri_tri3d(p1, q1, r1, p2, q2, r2, n1, n2)
    }
}

/// The macro `CHECK_MIN_MAX`: the two interval determinants.
#[inline(always)]
fn check_min_max<F: Float>(
    p1: V3<F>,
    q1: V3<F>,
    r1: V3<F>,
    p2: V3<F>,
    q2: V3<F>,
    r2: V3<F>,
) -> bool {
    let zero = F::ZERO;
    let n1 = cross(sub(p2, q1), sub(p1, q1));
    if dot(sub(q2, q1), n1) > zero {
        return false;
    }
    let n1 = cross(sub(p2, p1), sub(r1, p1));
    dot(sub(r2, p1), n1) <= zero
}

/// `coplanar_tri_tri3d`: projection onto the axis plane that maximizes the
/// projected area of T1 (by its float normal), then the 2D test.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub fn coplanar_tri_tri3d<F: Float>(
    p1: V3<F>,
    q1: V3<F>,
    r1: V3<F>,
    p2: V3<F>,
    q2: V3<F>,
    r2: V3<F>,
    normal_1: V3<F>,
    _normal_2: V3<F>,
) -> bool {
    let abs = |v: F| if v < F::ZERO { -v } else { v };
    let (n_x, n_y, n_z) = (abs(normal_1[0]), abs(normal_1[1]), abs(normal_1[2]));
    // Kept coordinates (first, second); the first two projections swap p
    // and q, as the C code does.
    let (i, j, swap) = if n_x > n_z && n_x >= n_y {
        (2, 1, true) // Project onto plane YZ.
    } else if n_y > n_z && n_y >= n_x {
        (0, 2, true) // Project onto plane XZ.
    } else {
        (0, 1, false) // Project onto plane XY.
    };
    let proj = |v: V3<F>| [v[i], v[j]];
    let (p1, q1, p2, q2) = if swap {
        (q1, p1, q2, p2)
    } else {
        (p1, q1, p2, q2)
    };
    tri_tri_overlap_test_2d(proj(p1), proj(q1), proj(r1), proj(p2), proj(q2), proj(r2))
}

/// The macro `ORIENT_2D(a, b, c)`.
#[inline(always)]
fn orient_2d<F: Float>(a: V2<F>, b: V2<F>, c: V2<F>) -> F {
    (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0])
}

/// The macro `INTERSECTION_TEST_VERTEX`.
fn intersection_test_vertex<F: Float>(
    p1: V2<F>,
    q1: V2<F>,
    r1: V2<F>,
    p2: V2<F>,
    q2: V2<F>,
    r2: V2<F>,
) -> bool {
    let zero = F::ZERO;
    if orient_2d(r2, p2, q1) >= zero {
        if orient_2d(r2, q2, q1) <= zero {
            if orient_2d(p1, p2, q1) > zero {
                orient_2d(p1, q2, q1) <= zero
            } else if orient_2d(p1, p2, r1) >= zero {
                orient_2d(q1, r1, p2) >= zero
            } else {
                false
            }
        } else if orient_2d(p1, q2, q1) <= zero {
            if orient_2d(r2, q2, r1) <= zero {
                orient_2d(q1, r1, q2) >= zero
            } else {
                false
            }
        } else {
            false
        }
    } else if orient_2d(r2, p2, r1) >= zero {
        if orient_2d(q1, r1, r2) >= zero {
            orient_2d(p1, p2, r1) >= zero
        } else if orient_2d(q1, r1, q2) >= zero {
            orient_2d(r2, r1, q2) >= zero
        } else {
            false
        }
    } else {
        false
    }
}

/// The macro `INTERSECTION_TEST_EDGE`.
fn intersection_test_edge<F: Float>(
    p1: V2<F>,
    q1: V2<F>,
    r1: V2<F>,
    p2: V2<F>,
    _q2: V2<F>,
    r2: V2<F>,
) -> bool {
    let zero = F::ZERO;
    if orient_2d(r2, p2, q1) >= zero {
        if orient_2d(p1, p2, q1) >= zero {
            orient_2d(p1, q1, r2) >= zero
        } else if orient_2d(q1, r1, p2) >= zero {
            orient_2d(r1, p1, p2) >= zero
        } else {
            false
        }
    } else if orient_2d(r2, p2, r1) >= zero {
        if orient_2d(p1, p2, r1) >= zero {
            orient_2d(p1, r1, r2) >= zero || orient_2d(q1, r1, r2) >= zero
        } else {
            false
        }
    } else {
        false
    }
}

/// `ccw_tri_tri_intersection_2d`: both triangles counter-clockwise.
fn ccw_tri_tri_intersection_2d<F: Float>(
    p1: V2<F>,
    q1: V2<F>,
    r1: V2<F>,
    p2: V2<F>,
    q2: V2<F>,
    r2: V2<F>,
) -> bool {
    let zero = F::ZERO;
    if orient_2d(p2, q2, p1) >= zero {
        if orient_2d(q2, r2, p1) >= zero {
            if orient_2d(r2, p2, p1) >= zero {
                true
            } else {
                intersection_test_edge(p1, q1, r1, p2, q2, r2)
            }
        } else if orient_2d(r2, p2, p1) >= zero {
            intersection_test_edge(p1, q1, r1, r2, p2, q2)
        } else {
            intersection_test_vertex(p1, q1, r1, p2, q2, r2)
        }
    } else if orient_2d(q2, r2, p1) >= zero {
        if orient_2d(r2, p2, p1) >= zero {
            intersection_test_edge(p1, q1, r1, q2, r2, p2)
        } else {
            intersection_test_vertex(p1, q1, r1, q2, r2, p2)
        }
    } else {
        intersection_test_vertex(p1, q1, r1, r2, p2, q2)
    }
}

/// `tri_tri_overlap_test_2d`: orients both triangles counter-clockwise.
pub fn tri_tri_overlap_test_2d<F: Float>(
    p1: V2<F>,
    q1: V2<F>,
    r1: V2<F>,
    p2: V2<F>,
    q2: V2<F>,
    r2: V2<F>,
) -> bool {
    let zero = F::ZERO;
    if orient_2d(p1, q1, r1) < zero {
        if orient_2d(p2, q2, r2) < zero {
            ccw_tri_tri_intersection_2d(p1, r1, q1, p2, r2, q2)
        } else {
            ccw_tri_tri_intersection_2d(p1, r1, q1, p2, q2, r2)
        }
    } else if orient_2d(p2, q2, r2) < zero {
        ccw_tri_tri_intersection_2d(p1, q1, r1, p2, r2, q2)
    } else {
        ccw_tri_tri_intersection_2d(p1, q1, r1, p2, q2, r2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact_f64;

    const T1: Triangle = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

    /// Clear-cut cases (crossing, separated, coplanar overlapping and apart)
    /// get the exact answer in both precisions.
    #[test]
    fn clear_cases_agree_with_exact() {
        let cases: [Triangle; 5] = [
            [[0.2, 0.2, -1.0], [0.2, 0.2, 1.0], [0.9, 0.9, 0.5]],
            [[0.2, 0.2, 1.0], [0.2, 0.3, 2.0], [0.9, 0.9, 1.5]],
            [[0.1, 0.1, 0.0], [2.0, 0.1, 0.0], [0.1, 2.0, 0.0]],
            [[2.0, 2.0, 0.0], [3.0, 2.0, 0.0], [2.0, 3.0, 0.0]],
            [[0.5, -1.0, -1.0], [0.5, 2.0, -1.0], [0.5, 0.5, 1.0]],
        ];
        for t2 in cases {
            let want = exact_f64::intersects(&T1, &t2);
            assert_eq!(intersects_f64(&T1, &t2), want, "{t2:?}");
            assert_eq!(intersects_f32(&T1, &t2), want, "{t2:?}");
            assert_eq!(intersects_f64(&t2, &T1), want, "swapped {t2:?}");
        }
    }

    /// The product test `dp1 * dq1 > 0` underflows to zero when the plane
    /// distances are tiny (here about 1e-180, clearly signed), so a separated
    /// pair from the Shen set, scaled by 2^-200 (exactly, which changes no
    /// sign), passes the early rejection and is then misjudged: the failure
    /// deciding on signs removes.
    #[test]
    fn product_of_distances_underflows() {
        let a: Triangle = [
            [0.393902, 0.191015, 0.232398],
            [0.344035, 0.238807, 0.87286],
            [0.576037, 0.440291, 0.781701],
        ];
        let b: Triangle = [
            [0.423536, 0.603717, 0.931516],
            [0.316111, 0.654317, 0.545549],
            [0.913968, 0.933531, 0.035066],
        ];
        assert!(!exact_f64::intersects(&a, &b));
        assert!(
            !intersects_f64(&a, &b),
            "unscaled, the published code is right"
        );
        let s = 2f64.powi(-200);
        let scale = |t: Triangle| t.map(|p| p.map(|c| c * s));
        let (a, b) = (scale(a), scale(b));
        assert!(!exact_f64::intersects(&a, &b));
        assert!(
            intersects_f64(&a, &b),
            "the published code is expected to fail here"
        );
    }
}
