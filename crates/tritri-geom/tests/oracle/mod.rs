//! An independent exact oracle for "do the closed triangles intersect?",
//! for tests only. It shares no code with `devillers_guigue.rs` and does not
//! use the `robust` crate: it is a separating-axis test on the Minkowski
//! difference, decided in exact integer arithmetic (f64 -> BigInt at a common
//! power-of-two scale), behind a floating-point filter with rigorous error
//! bounds that only answers when the sign is certain.
//!
//! # Why the axis set is complete
//!
//! Let `A = conv{a0,a1,a2}` and `B = conv{b0,b1,b2}` (either may be a segment
//! or a point). `A ∩ B = ∅` iff `0 ∉ P = A - B = conv{ai - bj}` (nine points
//! `V`). `P` is a compact convex polytope, so `0 ∉ P` iff some direction `n`
//! has `n·v > 0` for all `v ∈ V` or `n·v < 0` for all `v ∈ V` (strict
//! separation), and any such `n` proves disjointness: a superset of axes is
//! always sound. Let `E` be the six vertex differences `ai - aj`, `bi - bj`
//! (zero vectors allowed). Every edge of a Minkowski sum is parallel to an
//! edge of a summand, so every edge of `P` is parallel to a non-zero element
//! of `E`, and the direction space of `aff(P)` is `span(E)`; let
//! `d = dim span(E) = dim P`.
//!
//! * `d = 3`: if `0 ∉ P`, a facet's supporting half-space excludes it; the
//!   facet is spanned by two non-parallel edges of `P`, so its normal is
//!   parallel to `e × f` for some `e, f ∈ E`.
//! * `d = 2`: `P` lies in a plane with normal `m = e × f` (`e, f ∈ E` not
//!   parallel). If `0` is off that plane, `m` separates. Otherwise the plane
//!   goes through `0` and holds every `v ∈ V`, and `0` lies outside the
//!   polygon `P`, so the in-plane normal of one of its edges, parallel to
//!   some `g ∈ E`, separates. Not all of `V` is parallel to `g` (`P` would
//!   lie on a line), and for a `v` that is not, `g × (v × g)` is a non-zero
//!   in-plane vector perpendicular to `g`: that normal.
//! * `d = 1`: `P` is a segment along some `e ∈ E`, through `v ∈ V`. If `0` is
//!   on that line, `e` separates; otherwise `n = e × (v × e) = |e|² v - (e·v) e`
//!   is perpendicular to `e`, so `n·x = n·v = |e|²|v|² - (e·v)² > 0` for
//!   every `x ∈ P` (Cauchy–Schwarz, `v` not parallel to `e`).
//! * `d = 0`: `P = {v}`, and `v` itself separates when it is not zero.
//!
//! So the 84 axes `e × f` (15), `e` (6), `e × (v × e)` (54) and `v` (9) are
//! complete for every input (not minimal: in the `d = 1` case with `0` on the
//! line, every `v` separates as well as `e`). When the filter proves `d = 3` (some
//! `(e × f)·g` certainly non-zero), the 15 cross products suffice.

#![allow(dead_code)]

pub mod voxels;

use num_bigint::BigInt;
use num_traits::Zero;
use std::cell::OnceCell;
use std::cmp::Ordering;

pub type Point = [f64; 3];
pub type Triangle = [Point; 3];

/// Do the closed triangles intersect? Exact for all finite f64 input.
pub fn intersects(t1: &Triangle, t2: &Triangle) -> bool {
    Oracle::new(t1, t2, true).intersects()
}

/// The same answer without the floating-point filter: every axis decided in
/// BigInt arithmetic. Slow; used to check the filter.
pub fn intersects_exact_only(t1: &Triangle, t2: &Triangle) -> bool {
    Oracle::new(t1, t2, false).intersects()
}

/// The answer, and on how many axes the filter could not decide and the
/// exact BigInt computation ran (for reports).
pub fn intersects_counting_fallbacks(t1: &Triangle, t2: &Triangle) -> (bool, usize) {
    let o = Oracle::new(t1, t2, true);
    let answer = o.intersects();
    (answer, o.fallbacks.get())
}

// ---------------------------------------------------------------------------
// The separating-axis test, generic over the arithmetic.
// ---------------------------------------------------------------------------

/// The few operations the axis computation needs.
trait Arith: Clone {
    fn add(&self, o: &Self) -> Self;
    fn sub(&self, o: &Self) -> Self;
    fn mul(&self, o: &Self) -> Self;
}

type Vec3<T> = [T; 3];

fn vsub<T: Arith>(a: &Vec3<T>, b: &Vec3<T>) -> Vec3<T> {
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}

fn cross<T: Arith>(u: &Vec3<T>, v: &Vec3<T>) -> Vec3<T> {
    [
        u[1].mul(&v[2]).sub(&u[2].mul(&v[1])),
        u[2].mul(&v[0]).sub(&u[0].mul(&v[2])),
        u[0].mul(&v[1]).sub(&u[1].mul(&v[0])),
    ]
}

fn dot<T: Arith>(u: &Vec3<T>, v: &Vec3<T>) -> T {
    u[0].mul(&v[0]).add(&u[1].mul(&v[1])).add(&u[2].mul(&v[2]))
}

/// The edge differences `E` and the Minkowski-difference points `V`.
struct Vectors<T> {
    edges: [Vec3<T>; 6],
    differences: [Vec3<T>; 9],
}

fn vectors<T: Arith>(a: &[Vec3<T>; 3], b: &[Vec3<T>; 3]) -> Vectors<T> {
    let edges = [
        vsub(&a[1], &a[0]),
        vsub(&a[2], &a[0]),
        vsub(&a[2], &a[1]),
        vsub(&b[1], &b[0]),
        vsub(&b[2], &b[0]),
        vsub(&b[2], &b[1]),
    ];
    let differences = std::array::from_fn(|k| vsub(&a[k / 3], &b[k % 3]));
    Vectors { edges, differences }
}

/// A candidate separating direction, by how it is built from `E` and `V`.
#[derive(Clone, Copy, Debug)]
enum Axis {
    Cross(usize, usize),
    Edge(usize),
    EdgePerpendicular(usize, usize),
    Difference(usize),
}

fn axis_vector<T: Arith>(axis: Axis, v: &Vectors<T>) -> Vec3<T> {
    match axis {
        Axis::Cross(e, f) => cross(&v.edges[e], &v.edges[f]),
        Axis::Edge(e) => v.edges[e].clone(),
        Axis::EdgePerpendicular(e, d) => cross(&v.edges[e], &cross(&v.differences[d], &v.edges[e])),
        Axis::Difference(d) => v.differences[d].clone(),
    }
}

/// The 15 cross products of pairs of `E`.
fn cross_axes() -> impl Iterator<Item = Axis> {
    (0..6).flat_map(|e| (e + 1..6).map(move |f| Axis::Cross(e, f)))
}

/// The axes needed when `dim span(E) < 3` (see the module documentation).
fn lower_dimensional_axes() -> impl Iterator<Item = Axis> {
    let edges = (0..6).map(Axis::Edge);
    let perpendicular = (0..6).flat_map(|e| (0..9).map(move |d| Axis::EdgePerpendicular(e, d)));
    let differences = (0..9).map(Axis::Difference);
    edges.chain(perpendicular).chain(differences)
}

/// Does direction `n` separate, given the signs of `n·v` for the nine `v`?
fn separates(signs: &[Ordering; 9]) -> bool {
    signs.iter().all(|&s| s == Ordering::Greater) || signs.iter().all(|&s| s == Ordering::Less)
}

struct Oracle {
    approx: Vectors<Bounded>,
    points: ([Point; 3], [Point; 3]),
    exact: OnceCell<Vectors<BigInt>>,
    use_filter: bool,
    fallbacks: std::cell::Cell<usize>,
}

impl Oracle {
    fn new(t1: &Triangle, t2: &Triangle, use_filter: bool) -> Self {
        assert!(
            t1.iter().chain(t2.iter()).flatten().all(|x| x.is_finite()),
            "the oracle takes finite coordinates"
        );
        let lift = |t: &Triangle| t.map(|p| p.map(Bounded::exact));
        Oracle {
            approx: vectors(&lift(t1), &lift(t2)),
            points: (*t1, *t2),
            exact: OnceCell::new(),
            use_filter,
            fallbacks: std::cell::Cell::new(0),
        }
    }

    fn exact_vectors(&self) -> &Vectors<BigInt> {
        self.exact.get_or_init(|| {
            let (a, b) = to_common_scale_integers(&self.points.0, &self.points.1);
            vectors(&a, &b)
        })
    }

    fn intersects(&self) -> bool {
        if cross_axes().any(|axis| self.axis_separates(axis)) {
            return false;
        }
        if self.span_is_certainly_3d() {
            return true;
        }
        !lower_dimensional_axes().any(|axis| self.axis_separates(axis))
    }

    /// True only when the filter proves some `(e × f)·g` non-zero.
    fn span_is_certainly_3d(&self) -> bool {
        if !self.use_filter {
            return false; // then the full axis set is used, which is always complete
        }
        cross_axes().any(|axis| {
            let n = axis_vector(axis, &self.approx);
            self.approx
                .edges
                .iter()
                .any(|g| matches!(dot(&n, g).sign(), Some(s) if s != Ordering::Equal))
        })
    }

    fn axis_separates(&self, axis: Axis) -> bool {
        if self.use_filter {
            let n = axis_vector(axis, &self.approx);
            let signs = self.approx.differences.map(|v| dot(&n, &v).sign());
            if let Some(answer) = filtered_decision(&signs) {
                return answer;
            }
            self.fallbacks.set(self.fallbacks.get() + 1);
        }
        let exact = self.exact_vectors();
        let n = axis_vector(axis, exact);
        let signs: [Ordering; 9] =
            std::array::from_fn(|k| dot(&n, &exact.differences[k]).cmp(&BigInt::zero()));
        separates(&signs)
    }
}

/// With some signs unknown: decided when all are known, or when a known
/// `>= 0` and a known `<= 0` already rule separation out.
fn filtered_decision(signs: &[Option<Ordering>; 9]) -> Option<bool> {
    if signs.iter().all(Option::is_some) {
        return Some(separates(&signs.map(Option::unwrap)));
    }
    let non_negative = signs
        .iter()
        .any(|s| matches!(s, Some(Ordering::Greater | Ordering::Equal)));
    let non_positive = signs
        .iter()
        .any(|s| matches!(s, Some(Ordering::Less | Ordering::Equal)));
    if non_negative && non_positive {
        return Some(false);
    }
    None
}

// ---------------------------------------------------------------------------
// Exact arithmetic: f64 -> integers at a common power-of-two scale.
// ---------------------------------------------------------------------------

impl Arith for BigInt {
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
}

/// `x = mantissa * 2^exponent` exactly, with an integer mantissa.
pub fn decompose(x: f64) -> (i64, i32) {
    let bits = x.to_bits();
    let sign = if bits >> 63 == 1 { -1 } else { 1 };
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let fraction = (bits & ((1u64 << 52) - 1)) as i64;
    assert!(biased != 0x7ff, "not finite");
    if biased == 0 {
        (sign * fraction, -1074) // subnormal (or zero)
    } else {
        (sign * (fraction | (1i64 << 52)), biased - 1075)
    }
}

/// The 18 coordinates as integers `X` with `x = X * 2^s` for one common `s`
/// (the smallest exponent present). Scaling by a positive constant changes
/// no sign of any homogeneous polynomial the test evaluates.
fn to_common_scale_integers(
    t1: &Triangle,
    t2: &Triangle,
) -> ([Vec3<BigInt>; 3], [Vec3<BigInt>; 3]) {
    let all: Vec<(i64, i32)> = t1
        .iter()
        .chain(t2.iter())
        .flatten()
        .map(|&x| decompose(x))
        .collect();
    let scale = all
        .iter()
        .filter(|(m, _)| *m != 0)
        .map(|&(_, e)| e)
        .min()
        .unwrap_or(0);
    let int = |k: usize| {
        let (m, e) = all[k];
        if m == 0 {
            BigInt::zero()
        } else {
            BigInt::from(m) << ((e - scale) as usize)
        }
    };
    let point = |p: usize| [int(3 * p), int(3 * p + 1), int(3 * p + 2)];
    (
        [point(0), point(1), point(2)],
        [point(3), point(4), point(5)],
    )
}

// ---------------------------------------------------------------------------
// The filter: f64 values with a rigorous bound on their distance to the exact
// value.
// ---------------------------------------------------------------------------

/// The exact value lies in `[v - e, v + e]`; `e == 0` means `v` is exact.
///
/// Soundness (round to nearest, IEEE binary64, u = 2^-53):
/// * a sum is checked for exactness with TwoSum (exact for finite input); a
///   product with an FMA residual, trusted only when |product| >= 2^-900 (no
///   underflow, so the residual is exact);
/// * otherwise the rounding error of `fl(x)` is at most `u·|fl(x)|` in the
///   normal range (and sums are exact in the subnormal range); products may
///   underflow, covered by the absolute term `TINY = 2^-900`, vastly larger
///   than any underflow error;
/// * propagated bounds: `|AB - ab| <= |a| eB + |b| eA + eA eB`,
///   `|(A ± B) - (a ± b)| <= eA + eB`;
/// * the bound itself is computed in f64 with a few rounding steps, each
///   losing at most a factor (1 - u); the factor `1 + 16u` and `TINY` cover
///   them with a wide margin;
/// * any infinity or NaN makes the value unknown.
#[derive(Clone, Copy, Debug)]
struct Bounded {
    v: f64,
    e: f64,
}

const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;
const INFLATE: f64 = 1.0 + 8.0 * f64::EPSILON;
const TINY: f64 = f64::from_bits((1023 - 900) << 52); // 2^-900

impl Bounded {
    fn exact(v: f64) -> Self {
        Bounded { v, e: 0.0 }
    }

    /// The sign of the exact value, when the bound decides it.
    fn sign(&self) -> Option<Ordering> {
        if !self.v.is_finite() || !self.e.is_finite() {
            return None;
        }
        if self.e == 0.0 {
            return self.v.partial_cmp(&0.0);
        }
        if self.v > self.e {
            Some(Ordering::Greater)
        } else if self.v < -self.e {
            Some(Ordering::Less)
        } else {
            None
        }
    }

    fn sum(a: f64, ea: f64, b: f64, eb: f64) -> Self {
        if a == 0.0 && ea == 0.0 {
            return Bounded { v: b, e: eb };
        }
        if b == 0.0 && eb == 0.0 {
            return Bounded { v: a, e: ea };
        }
        let s = a + b;
        if ea == 0.0 && eb == 0.0 {
            // Knuth's TwoSum: the exact rounding error of a + b.
            let bb = s - a;
            let err = (a - (s - bb)) + (b - bb);
            if err == 0.0 {
                return Bounded { v: s, e: 0.0 };
            }
        }
        Bounded {
            v: s,
            e: (ea + eb + UNIT_ROUNDOFF * s.abs()) * INFLATE + TINY,
        }
    }
}

impl Arith for Bounded {
    fn add(&self, o: &Self) -> Self {
        Bounded::sum(self.v, self.e, o.v, o.e)
    }
    fn sub(&self, o: &Self) -> Self {
        Bounded::sum(self.v, self.e, -o.v, o.e)
    }
    fn mul(&self, o: &Self) -> Self {
        if (self.v == 0.0 && self.e == 0.0) || (o.v == 0.0 && o.e == 0.0) {
            return Bounded { v: 0.0, e: 0.0 };
        }
        let p = self.v * o.v;
        // The FMA residual is the exact rounding error when nothing underflows.
        if self.e == 0.0
            && o.e == 0.0
            && p.abs() >= TINY
            && p.is_finite()
            && self.v.mul_add(o.v, -p) == 0.0
        {
            return Bounded { v: p, e: 0.0 };
        }
        let e = (self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + UNIT_ROUNDOFF * p.abs())
            * INFLATE
            + TINY;
        Bounded { v: p, e }
    }
}

/// Does the closed triangle (integer vertices) meet the closed box? It
/// does iff it meets one of the 12 triangles of the box's surface or has a
/// vertex inside the box (a convex set meeting a box either crosses its
/// boundary or lies inside it); the surface test is [`intersects`].
pub fn triangle_touches_box(
    t: &[[i64; 3]; 3],
    b: &tritri_geom::bounding_volume::Aabb<i64>,
) -> bool {
    let inside = |p: &[i64; 3]| (0..3).all(|k| b.lo[k] <= p[k] && p[k] <= b.hi[k]);
    if t.iter().any(inside) {
        return true;
    }
    let corner =
        |o: usize| [0, 1, 2].map(|k| if o >> k & 1 == 1 { b.hi[k] } else { b.lo[k] } as f64);
    let tf = t.map(|p| p.map(|c| c as f64));
    // Each face of the box as two triangles: the four corners with bit k fixed.
    for k in 0..3 {
        for side in 0..2 {
            let corners: Vec<usize> = (0..8).filter(|o| o >> k & 1 == side).collect();
            // corners in the face, ordered around it: 0, 1, 3, 2 of the two free bits.
            let quad = [corners[0], corners[1], corners[3], corners[2]].map(corner);
            if intersects(&tf, &[quad[0], quad[1], quad[2]])
                || intersects(&tf, &[quad[0], quad[2], quad[3]])
            {
                return true;
            }
        }
    }
    false
}
