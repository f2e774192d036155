//! Möller's triangle–triangle test (T. Möller, "A Fast Triangle-Triangle
//! Intersection Test", JGT 2(2), 1997), the division-free version
//! `NoDivTriTriIsect` of the published code, in f64 with its published
//! epsilon test (`USE_EPSILON_TEST`, `EPSILON = 0.000001`): plane distances
//! whose magnitude is below `EPSILON` are set to zero.
//!
//! The classic baseline. It computes intervals on the intersection line from
//! rounded plane distances, uses an absolute (scale-dependent) epsilon and
//! tests point containment strictly, so it is neither exact nor closed; the
//! project reports how often it disagrees with the exact answer.
//!
//! ```
//! use tritri_geom::moller;
//! let t1 = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! let t2 = [[0.2, 0.2, -1.0], [0.2, 0.2, 1.0], [0.9, 0.9, 0.5]];
//! assert!(moller::intersects(&t1, &t2));
//! ```

use crate::triangle::Triangle;

/// The published epsilon: `|d| < EPSILON` counts as on the plane.
pub const EPSILON: f64 = 0.000001;

type V3 = [f64; 3];

#[inline(always)]
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `NoDivTriTriIsect(V0,V1,V2,U0,U1,U2)` on `t1 = V`, `t2 = U`.
pub fn intersects(t1: &Triangle, t2: &Triangle) -> bool {
    let [v0, v1, v2] = *t1;
    let [u0, u1, u2] = *t2;
    no_div_tri_tri_isect(v0, v1, v2, u0, u1, u2)
}

/// The result of the macro `NEWCOMPUTE_INTERVALS`: `(A, B, C, X0, X1)`, or
/// the coplanar case.
enum Interval {
    Projected {
        a: f64,
        b: f64,
        c: f64,
        x0: f64,
        x1: f64,
    },
    Coplanar,
}

/// The macro `NEWCOMPUTE_INTERVALS(VV0,VV1,VV2,D0,D1,D2,D0D1,D0D2,...)`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn new_compute_intervals(
    vv0: f64,
    vv1: f64,
    vv2: f64,
    d0: f64,
    d1: f64,
    d2: f64,
    d0d1: f64,
    d0d2: f64,
) -> Interval {
    let (a, b, c, x0, x1);
    if d0d1 > 0.0 {
        // D0, D1 on the same side, D2 on the other or on the plane.
        a = vv2;
        b = (vv0 - vv2) * d2;
        c = (vv1 - vv2) * d2;
        x0 = d2 - d0;
        x1 = d2 - d1;
    } else if d0d2 > 0.0 {
        a = vv1;
        b = (vv0 - vv1) * d1;
        c = (vv2 - vv1) * d1;
        x0 = d1 - d0;
        x1 = d1 - d2;
    } else if d1 * d2 > 0.0 || d0 != 0.0 {
        a = vv0;
        b = (vv1 - vv0) * d0;
        c = (vv2 - vv0) * d0;
        x0 = d0 - d1;
        x1 = d0 - d2;
    } else if d1 != 0.0 {
        a = vv1;
        b = (vv0 - vv1) * d1;
        c = (vv2 - vv1) * d1;
        x0 = d1 - d0;
        x1 = d1 - d2;
    } else if d2 != 0.0 {
        a = vv2;
        b = (vv0 - vv2) * d2;
        c = (vv1 - vv2) * d2;
        x0 = d2 - d0;
        x1 = d2 - d1;
    } else {
        return Interval::Coplanar;
    }
    Interval::Projected { a, b, c, x0, x1 }
}

/// `NoDivTriTriIsect`.
pub fn no_div_tri_tri_isect(v0: V3, v1: V3, v2: V3, u0: V3, u1: V3, u2: V3) -> bool {
    let epsilon_test = |d: f64| if d.abs() < EPSILON { 0.0 } else { d };

    // Plane of triangle (V0,V1,V2): N1.X + d1 = 0.
    let n1 = cross(sub(v1, v0), sub(v2, v0));
    let d1 = -dot(n1, v0);
    // Signed distances of U0, U1, U2 to plane 1, with the coplanarity epsilon.
    let du0 = epsilon_test(dot(n1, u0) + d1);
    let du1 = epsilon_test(dot(n1, u1) + d1);
    let du2 = epsilon_test(dot(n1, u2) + d1);
    let du0du1 = du0 * du1;
    let du0du2 = du0 * du2;
    if du0du1 > 0.0 && du0du2 > 0.0 {
        return false;
    }

    // Plane of triangle (U0,U1,U2).
    let n2 = cross(sub(u1, u0), sub(u2, u0));
    let d2 = -dot(n2, u0);
    let dv0 = epsilon_test(dot(n2, v0) + d2);
    let dv1 = epsilon_test(dot(n2, v1) + d2);
    let dv2 = epsilon_test(dot(n2, v2) + d2);
    let dv0dv1 = dv0 * dv1;
    let dv0dv2 = dv0 * dv2;
    if dv0dv1 > 0.0 && dv0dv2 > 0.0 {
        return false;
    }

    // Direction of the intersection line and its largest component.
    let d = cross(n1, n2);
    let mut max = d[0].abs();
    let mut index = 0;
    let bb = d[1].abs();
    let cc = d[2].abs();
    if bb > max {
        max = bb;
        index = 1;
    }
    if cc > max {
        index = 2;
    }

    // The simplified projection onto the line.
    let (vp0, vp1, vp2) = (v0[index], v1[index], v2[index]);
    let (up0, up1, up2) = (u0[index], u1[index], u2[index]);

    let (a, b, c, x0, x1) =
        match new_compute_intervals(vp0, vp1, vp2, dv0, dv1, dv2, dv0dv1, dv0dv2) {
            Interval::Projected { a, b, c, x0, x1 } => (a, b, c, x0, x1),
            Interval::Coplanar => return coplanar_tri_tri(n1, v0, v1, v2, u0, u1, u2),
        };
    let (d, e, f, y0, y1) =
        match new_compute_intervals(up0, up1, up2, du0, du1, du2, du0du1, du0du2) {
            Interval::Projected { a, b, c, x0, x1 } => (a, b, c, x0, x1),
            Interval::Coplanar => return coplanar_tri_tri(n1, v0, v1, v2, u0, u1, u2),
        };

    let xx = x0 * x1;
    let yy = y0 * y1;
    let xxyy = xx * yy;

    let tmp = a * xxyy;
    let mut isect1 = [tmp + b * x1 * yy, tmp + c * x0 * yy];
    let tmp = d * xxyy;
    let mut isect2 = [tmp + e * xx * y1, tmp + f * xx * y0];

    sort(&mut isect1);
    sort(&mut isect2);
    !(isect1[1] < isect2[0] || isect2[1] < isect1[0])
}

/// The macro `SORT(a,b)`: so that `a <= b`.
#[inline(always)]
fn sort(v: &mut [f64; 2]) {
    if v[0] > v[1] {
        v.swap(0, 1);
    }
}

/// `coplanar_tri_tri(N,V0,V1,V2,U0,U1,U2)`: project onto the axis plane
/// that maximizes the area, test every edge pair, then strict containment of
/// one vertex of each triangle in the other.
#[inline(never)]
pub fn coplanar_tri_tri(n: V3, v0: V3, v1: V3, v2: V3, u0: V3, u1: V3, u2: V3) -> bool {
    let a = [n[0].abs(), n[1].abs(), n[2].abs()];
    let (i0, i1) = if a[0] > a[1] {
        if a[0] > a[2] {
            (1, 2) // a[0] is greatest
        } else {
            (0, 1) // a[2] is greatest
        }
    } else if a[2] > a[1] {
        (0, 1) // a[2] is greatest
    } else {
        (0, 2) // a[1] is greatest
    };

    // Test all edges of triangle 1 against the edges of triangle 2.
    if edge_against_tri_edges(i0, i1, v0, v1, u0, u1, u2)
        || edge_against_tri_edges(i0, i1, v1, v2, u0, u1, u2)
        || edge_against_tri_edges(i0, i1, v2, v0, u0, u1, u2)
    {
        return true;
    }
    // Finally, is one triangle totally contained in the other?
    point_in_tri(i0, i1, v0, u0, u1, u2) || point_in_tri(i0, i1, u0, v0, v1, v2)
}

/// The macro `EDGE_AGAINST_TRI_EDGES(V0,V1,U0,U1,U2)`.
#[inline(always)]
fn edge_against_tri_edges(i0: usize, i1: usize, v0: V3, v1: V3, u0: V3, u1: V3, u2: V3) -> bool {
    let ax = v1[i0] - v0[i0];
    let ay = v1[i1] - v0[i1];
    edge_edge_test(i0, i1, ax, ay, v0, u0, u1)
        || edge_edge_test(i0, i1, ax, ay, v0, u1, u2)
        || edge_edge_test(i0, i1, ax, ay, v0, u2, u0)
}

/// The macro `EDGE_EDGE_TEST(V0,U0,U1)` (Franklin Antonio's test, Graphics
/// Gems III).
#[inline(always)]
fn edge_edge_test(i0: usize, i1: usize, ax: f64, ay: f64, v0: V3, u0: V3, u1: V3) -> bool {
    let bx = u0[i0] - u1[i0];
    let by = u0[i1] - u1[i1];
    let cx = v0[i0] - u0[i0];
    let cy = v0[i1] - u0[i1];
    let f = ay * bx - ax * by;
    let d = by * cx - bx * cy;
    if (f > 0.0 && d >= 0.0 && d <= f) || (f < 0.0 && d <= 0.0 && d >= f) {
        let e = ax * cy - ay * cx;
        if f > 0.0 {
            if e >= 0.0 && e <= f {
                return true;
            }
        } else if e <= 0.0 && e >= f {
            return true;
        }
    }
    false
}

/// The macro `POINT_IN_TRI(V0,U0,U1,U2)`: is V0 strictly inside?
#[inline(always)]
fn point_in_tri(i0: usize, i1: usize, v0: V3, u0: V3, u1: V3, u2: V3) -> bool {
    let side = |p: V3, q: V3| {
        let a = q[i1] - p[i1];
        let b = -(q[i0] - p[i0]);
        let c = -a * p[i0] - b * p[i1];
        a * v0[i0] + b * v0[i1] + c
    };
    let d0 = side(u0, u1);
    let d1 = side(u1, u2);
    let d2 = side(u2, u0);
    d0 * d1 > 0.0 && d0 * d2 > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact_f64;

    const T1: Triangle = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

    /// Clear-cut cases get the exact answer, in both argument orders.
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
            assert_eq!(intersects(&T1, &t2), want, "{t2:?}");
            assert_eq!(intersects(&t2, &T1), want, "swapped {t2:?}");
        }
    }

    /// A small triangle coplanar with and strictly inside a large one: the
    /// containment test (not the edge tests) finds it.
    #[test]
    fn coplanar_containment() {
        let inner: Triangle = [[0.1, 0.1, 0.0], [0.2, 0.1, 0.0], [0.1, 0.2, 0.0]];
        assert!(intersects(&T1, &inner));
        assert!(intersects(&inner, &T1));
    }

    /// The absolute epsilon makes a clearly separated but small-scale pair
    /// count as coplanar: a small triangle hovering 1e-7 above another
    /// (about a tenth of its size) is reported as touching.
    #[test]
    fn absolute_epsilon_merges_close_planes() {
        let a: Triangle = [[0.0, 0.0, 0.0], [1e-6, 0.0, 0.0], [0.0, 1e-6, 0.0]];
        let b: Triangle = [[0.0, 0.0, 1e-7], [1e-6, 0.0, 1e-7], [0.0, 1e-6, 1e-7]];
        assert!(!exact_f64::intersects(&a, &b));
        assert!(
            intersects(&a, &b),
            "Möller's epsilon test treats these as coplanar"
        );
    }
}
