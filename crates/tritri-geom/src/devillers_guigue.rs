//! The Devillers–Guigue triangle–triangle overlap test on exact predicates,
//! with closed-triangle semantics (touching counts as intersecting), the full
//! coplanar branch and a defined answer for degenerate triangles.
//!
//! The steps are the thesis's seven (chapter 2):
//! (1) normal of T2, (2) signs of T1's vertices against T2's plane,
//! (3) normal of T1, (4) signs of T2's vertices against T1's plane,
//! (5) [`align_t1`]: rotate T1 so its lone vertex comes first, and swap T2's
//! orientation when that vertex lies below the plane,
//! (6) [`align_t2`]: the same for T2, (7) [`interval_overlap`]: two
//! orientation determinants that must both be `<= 0`.
//!
//! Degenerate triangles (three collinear vertices) are the segment between
//! their two extreme vertices, or a point; they are tested by
//! [`segment_triangle`] and [`degenerate_pair`] with the same exact
//! predicates, so every input gets the exact answer for closed sets.

use crate::kernel::ExactKernel;
use crate::sign::Sign;

/// What the closed convex hull of a triangle's three vertices is.
#[derive(Clone, Copy, Debug)]
pub enum Shape<P> {
    Triangle([P; 3]),
    /// The two extreme vertices of three collinear, not all equal, vertices.
    Segment(P, P),
    Point(P),
}

/// Classifies a triangle exactly: degenerate when its normal is zero.
#[inline(always)]
pub fn shape<K: ExactKernel>(t: [K::Point; 3]) -> Shape<K::Point> {
    let [a, b, c] = t;
    let normal_is_zero = (0..3).all(|axis| K::orient2d(axis, a, b, c).is_zero());
    if !normal_is_zero {
        return Shape::Triangle(t);
    }
    let mut lo = a;
    let mut hi = a;
    for p in [b, c] {
        if K::compare_lexicographic(p, lo).is_lt() {
            lo = p;
        }
        if K::compare_lexicographic(p, hi).is_gt() {
            hi = p;
        }
    }
    if K::compare_lexicographic(lo, hi).is_eq() {
        Shape::Point(lo)
    } else {
        Shape::Segment(lo, hi)
    }
}

/// Do the closed triangles `t1` and `t2` intersect? Exact for any input the
/// kernel represents exactly, degenerate triangles included.
pub fn intersects<K: ExactKernel>(t1: [K::Point; 3], t2: [K::Point; 3]) -> bool {
    match (shape::<K>(t1), shape::<K>(t2)) {
        (Shape::Triangle(t1), Shape::Triangle(t2)) => triangles_intersect::<K>(t1, t2),
        (Shape::Triangle(t), other) | (other, Shape::Triangle(t)) => {
            let (a, b) = segment_ends(other);
            segment_triangle::<K>(a, b, t)
        }
        (s1, s2) => {
            let (a, b) = segment_ends(s1);
            let (c, d) = segment_ends(s2);
            degenerate_pair::<K>(a, b, c, d)
        }
    }
}

/// A point is the zero-length segment from itself to itself.
fn segment_ends<P: Copy>(s: Shape<P>) -> (P, P) {
    match s {
        Shape::Segment(a, b) => (a, b),
        Shape::Point(a) => (a, a),
        Shape::Triangle(_) => unreachable!("called on degenerate shapes only"),
    }
}

/// Signs of the three vertices of `t` against the plane of `plane`.
#[inline(always)]
fn plane_side<K: ExactKernel>(plane: [K::Point; 3], t: [K::Point; 3]) -> [Sign; 3] {
    let [p, q, r] = plane;
    // Written out (not `t.map`) so that the three calls inline side by side
    // and the plane's normal is computed once.
    [
        K::orient3d(p, q, r, t[0]),
        K::orient3d(p, q, r, t[1]),
        K::orient3d(p, q, r, t[2]),
    ]
}

fn all_strictly_same_side(s: [Sign; 3]) -> bool {
    (s[0] == s[1] && s[1] == s[2]) && !s[0].is_zero()
}

/// Devillers–Guigue on two non-degenerate triangles.
#[inline]
pub fn triangles_intersect<K: ExactKernel>(t1: [K::Point; 3], t2: [K::Point; 3]) -> bool {
    // Steps (1)-(2): T1 against the plane of T2.
    let d1 = plane_side::<K>(t2, t1);
    if all_strictly_same_side(d1) {
        return false;
    }
    // Steps (3)-(4): T2 against the plane of T1.
    let d2 = plane_side::<K>(t1, t2);
    if all_strictly_same_side(d2) {
        return false;
    }
    if d1.iter().all(|s| s.is_zero()) {
        return coplanar_triangles::<K>(t1, t2);
    }
    // Steps (5)-(6)-(7).
    let (t1, t2, d2) = align_t1(t1, t2, d1, d2);
    let t2 = align_t2(t2, d2);
    interval_overlap::<K>(t1, t2)
}

/// Step (5): rotate T1 so that the vertex alone on its side of T2's plane
/// comes first and lies on the positive side or on the plane, with the two
/// others on the non-positive side; when T1's lone vertex is below, T2's
/// orientation is swapped (q2 <-> r2) instead of flipping signs. Returns T1,
/// T2 and T2's signs permuted alike. This is the sign table of the reference
/// C code (`tri_tri_overlap_test_3d`), decided on signs only.
#[inline(always)]
pub fn align_t1<P: Copy>(
    t1: [P; 3],
    t2: [P; 3],
    d1: [Sign; 3],
    d2: [Sign; 3],
) -> ([P; 3], [P; 3], [Sign; 3]) {
    use Sign::*;
    let [p1, q1, r1] = t1;
    let [p2, q2, r2] = t2;
    let [dp2, dq2, dr2] = d2;
    let keep = [p2, q2, r2];
    let keep_d = [dp2, dq2, dr2];
    let swap = [p2, r2, q2];
    let swap_d = [dp2, dr2, dq2];
    match (d1[0], d1[1], d1[2]) {
        (Positive, Positive, _) => ([r1, p1, q1], swap, swap_d),
        (Positive, _, Positive) => ([q1, r1, p1], swap, swap_d),
        (Positive, _, _) => ([p1, q1, r1], keep, keep_d),
        (Negative, Negative, _) => ([r1, p1, q1], keep, keep_d),
        (Negative, _, Negative) => ([q1, r1, p1], keep, keep_d),
        (Negative, _, _) => ([p1, q1, r1], swap, swap_d),
        (Zero, Negative, Positive | Zero) => ([q1, r1, p1], swap, swap_d),
        (Zero, Negative, Negative) => ([p1, q1, r1], keep, keep_d),
        (Zero, Positive, Positive) => ([p1, q1, r1], swap, swap_d),
        (Zero, Positive, Negative | Zero) => ([q1, r1, p1], keep, keep_d),
        (Zero, Zero, Positive) => ([r1, p1, q1], keep, keep_d),
        (Zero, Zero, Negative) => ([r1, p1, q1], swap, swap_d),
        (Zero, Zero, Zero) => unreachable!("the coplanar case is handled before alignment"),
    }
}

/// Step (6): rotate T2 (already oriented by step 5) so that its lone vertex
/// comes first, and swap T1's roles in the final test accordingly. Returns
/// the permuted T2; the permutation of T1 that the reference code applies
/// here is `p1, r1, q1` or `p1, q1, r1`, folded into the returned flag.
#[inline(always)]
pub fn align_t2<P: Copy>(t2: [P; 3], d2: [Sign; 3]) -> AlignedT2<P> {
    use Sign::*;
    let [p2, q2, r2] = t2;
    // (T2 rotation, whether T1's q1 and r1 swap) from the reference macro TRI_TRI_3D.
    let (t2, swap_t1) = match (d2[0], d2[1], d2[2]) {
        (Positive, Positive, _) => ([r2, p2, q2], true),
        (Positive, _, Positive) => ([q2, r2, p2], true),
        (Positive, _, _) => ([p2, q2, r2], false),
        (Negative, Negative, _) => ([r2, p2, q2], false),
        (Negative, _, Negative) => ([q2, r2, p2], false),
        (Negative, _, _) => ([p2, q2, r2], true),
        (Zero, Negative, Positive | Zero) => ([q2, r2, p2], true),
        (Zero, Negative, Negative) => ([p2, q2, r2], false),
        (Zero, Positive, Positive) => ([p2, q2, r2], true),
        (Zero, Positive, Negative | Zero) => ([q2, r2, p2], false),
        (Zero, Zero, Positive) => ([r2, p2, q2], false),
        (Zero, Zero, Negative) => ([r2, p2, q2], true),
        (Zero, Zero, Zero) => {
            unreachable!("T1 is not coplanar with T2, so T2 is not on T1's plane")
        }
    };
    AlignedT2 { t2, swap_t1 }
}

/// T2 after step (6), and whether T1's last two vertices trade places.
#[derive(Clone, Copy, Debug)]
pub struct AlignedT2<P> {
    pub t2: [P; 3],
    pub swap_t1: bool,
}

/// Step (7): with both triangles aligned, the segments they cut on the line
/// of the two planes overlap iff `[p1,q1,p2,q2]`-style determinants are both
/// `<= 0` (the reference macro CHECK_MIN_MAX).
#[inline(always)]
pub fn interval_overlap<K: ExactKernel>(t1: [K::Point; 3], aligned: AlignedT2<K::Point>) -> bool {
    let [p1, mut q1, mut r1] = t1;
    if aligned.swap_t1 {
        std::mem::swap(&mut q1, &mut r1);
    }
    let [p2, q2, r2] = aligned.t2;
    // CHECK_MIN_MAX(p1,q1,r1,p2,q2,r2):
    //   (q2-q1)·((p2-q1)×(p1-q1)) > 0  -> no overlap, i.e. [q1,p2,p1,q2] > 0
    //   (r2-p1)·((p2-p1)×(r1-p1)) > 0  -> no overlap, i.e. [p1,p2,r1,r2] > 0
    if K::orient3d(q1, p2, p1, q2).is_positive() {
        return false;
    }
    !K::orient3d(p1, p2, r1, r2).is_positive()
}

/// Coplanar non-degenerate triangles: the exact closed 2D test on the
/// projection that drops the largest component of T1's normal.
pub fn coplanar_triangles<K: ExactKernel>(t1: [K::Point; 3], t2: [K::Point; 3]) -> bool {
    let axis = K::dominant_normal_axis(t1[0], t1[1], t1[2]);
    hulls_intersect_2d::<K>(axis, &t1, &t2)
}

/// A segment `[a, b]` (a point when `a == b`) against a non-degenerate
/// triangle.
pub fn segment_triangle<K: ExactKernel>(a: K::Point, b: K::Point, t: [K::Point; 3]) -> bool {
    let [p, q, r] = t;
    let sa = K::orient3d(p, q, r, a);
    let sb = K::orient3d(p, q, r, b);
    if sa == sb && !sa.is_zero() {
        return false;
    }
    if sa.is_zero() && sb.is_zero() {
        let axis = K::dominant_normal_axis(p, q, r);
        return hulls_intersect_2d::<K>(axis, &[a, b], &t);
    }
    // The segment crosses the plane at exactly one point, which lies in the
    // closed triangle iff the line ab passes on the same side of all three
    // edges (zero allowed: through an edge or a vertex).
    let s = [
        K::orient3d(a, b, p, q),
        K::orient3d(a, b, q, r),
        K::orient3d(a, b, r, p),
    ];
    !(s.contains(&Sign::Positive) && s.contains(&Sign::Negative))
}

/// Two segments (either may be a point). They meet only if all four ends are
/// coplanar; then they meet iff their projections meet along each of the
/// three axes (each projection is a necessary condition, and at least one is
/// one-to-one on a plane holding all four points).
pub fn degenerate_pair<K: ExactKernel>(a: K::Point, b: K::Point, c: K::Point, d: K::Point) -> bool {
    if !K::orient3d(a, b, c, d).is_zero() {
        return false;
    }
    (0..3).all(|axis| hulls_intersect_2d::<K>(axis, &[a, b], &[c, d]))
}

/// Do the closed convex hulls of `u` and `v` (2 or 3 points each, possibly
/// collinear or repeated) meet in the projection dropping `axis`?
/// Either two of their edges meet, or one hull holds a vertex of the other.
pub fn hulls_intersect_2d<K: ExactKernel>(axis: usize, u: &[K::Point], v: &[K::Point]) -> bool {
    let edges = |pts: &[K::Point]| -> Vec<(K::Point, K::Point)> {
        match *pts {
            [a, b] => vec![(a, b)],
            [a, b, c] => vec![(a, b), (b, c), (c, a)],
            _ => unreachable!("hulls of two or three points"),
        }
    };
    for &(a, b) in &edges(u) {
        for &(c, d) in &edges(v) {
            if segments_intersect_2d::<K>(axis, a, b, c, d) {
                return true;
            }
        }
    }
    point_in_triangle_2d::<K>(axis, v[0], u) || point_in_triangle_2d::<K>(axis, u[0], v)
}

/// Is `x` inside the closed projected triangle `t`? False when `t` is not a
/// proper triangle in this projection (its boundary cases are covered by the
/// edge tests).
fn point_in_triangle_2d<K: ExactKernel>(axis: usize, x: K::Point, t: &[K::Point]) -> bool {
    let [a, b, c] = match *t {
        [a, b, c] => [a, b, c],
        _ => return false,
    };
    let orientation = K::orient2d(axis, a, b, c);
    if orientation.is_zero() {
        return false;
    }
    [
        K::orient2d(axis, a, b, x),
        K::orient2d(axis, b, c, x),
        K::orient2d(axis, c, a, x),
    ]
    .iter()
    .all(|&s| s.is_zero() || s == orientation)
}

/// Closed segments `[a,b]` and `[c,d]` in the projection dropping `axis`
/// (zero-length segments allowed), the classic orientation test with the
/// collinear cases resolved by coordinate comparisons.
fn segments_intersect_2d<K: ExactKernel>(
    axis: usize,
    a: K::Point,
    b: K::Point,
    c: K::Point,
    d: K::Point,
) -> bool {
    let o1 = K::orient2d(axis, a, b, c);
    let o2 = K::orient2d(axis, a, b, d);
    let o3 = K::orient2d(axis, c, d, a);
    let o4 = K::orient2d(axis, c, d, b);
    let strictly_opposite = |s: Sign, t: Sign| !s.is_zero() && s == t.flip();
    if strictly_opposite(o1, o2) && strictly_opposite(o3, o4) {
        return true;
    }
    (o1.is_zero() && on_segment_2d::<K>(axis, a, b, c))
        || (o2.is_zero() && on_segment_2d::<K>(axis, a, b, d))
        || (o3.is_zero() && on_segment_2d::<K>(axis, c, d, a))
        || (o4.is_zero() && on_segment_2d::<K>(axis, c, d, b))
}

/// For `x` collinear with `[a,b]` in the projection: is it within the
/// segment's bounding box there?
fn on_segment_2d<K: ExactKernel>(axis: usize, a: K::Point, b: K::Point, x: K::Point) -> bool {
    [(axis + 1) % 3, (axis + 2) % 3].iter().all(|&k| {
        let lo_ok =
            K::compare_coordinate(k, a, x).is_le() || K::compare_coordinate(k, b, x).is_le();
        let hi_ok =
            K::compare_coordinate(k, a, x).is_ge() || K::compare_coordinate(k, b, x).is_ge();
        lo_ok && hi_ok
    })
}
