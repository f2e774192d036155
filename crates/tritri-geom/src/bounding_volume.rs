//! Axis-aligned bounding boxes, the common bounding volume of two objects
//! (the overlap of their boxes), and the exact triangle–box test that
//! decides which triangles reach the hardware (thesis, chapter 4).
//!
//! Any point where a triangle of A meets a triangle of B lies in both
//! objects' boxes, hence in the common box: a pair whose triangles do not
//! both touch the common box cannot intersect, so filtering loses nothing.

use crate::fixed_point::FixedTriangle;
use crate::octree::triangle_cell::TriangleCellTest;
use crate::triangle::Triangle;

/// A closed axis-aligned box `lo <= p <= hi` (componentwise).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb<T> {
    pub lo: [T; 3],
    pub hi: [T; 3],
}

impl<T: Copy + PartialOrd> Aabb<T> {
    /// The smallest box holding every vertex; `None` for no triangles.
    pub fn of_triangles<'a>(triangles: impl IntoIterator<Item = &'a [[T; 3]; 3]>) -> Option<Aabb<T>>
    where
        T: 'a,
    {
        let mut it = triangles.into_iter().flat_map(|t| t.iter());
        let first = *it.next()?;
        let mut b = Aabb {
            lo: first,
            hi: first,
        };
        for p in it {
            for k in 0..3 {
                if p[k] < b.lo[k] {
                    b.lo[k] = p[k];
                }
                if p[k] > b.hi[k] {
                    b.hi[k] = p[k];
                }
            }
        }
        Some(b)
    }

    /// The common bounding volume: the overlap of two boxes, `None` if they
    /// do not meet (touching boxes give a flat or empty-interior overlap).
    pub fn overlap(&self, other: &Aabb<T>) -> Option<Aabb<T>> {
        let mut b = *self;
        for k in 0..3 {
            if other.lo[k] > b.lo[k] {
                b.lo[k] = other.lo[k];
            }
            if other.hi[k] < b.hi[k] {
                b.hi[k] = other.hi[k];
            }
            if b.lo[k] > b.hi[k] {
                return None;
            }
        }
        Some(b)
    }
}

impl Aabb<f64> {
    /// The box grown by `margin` on every side.
    pub fn expanded(&self, margin: f64) -> Aabb<f64> {
        Aabb {
            lo: self.lo.map(|v| v - margin),
            hi: self.hi.map(|v| v + margin),
        }
    }

    /// Largest side length.
    pub fn extent(&self) -> f64 {
        (0..3).map(|k| self.hi[k] - self.lo[k]).fold(0.0, f64::max)
    }
}

/// Does the closed triangle touch the closed box? A conservative f64 test
/// (boxes only): it may keep a triangle that misses the box, never drops one
/// that touches it. Used to pick what gets quantized; the exact decision is
/// [`triangle_touches_box`] in the integer frame.
pub fn triangle_box_overlap_conservative(t: &Triangle, b: &Aabb<f64>) -> bool {
    let tb = Aabb::of_triangles(std::iter::once(t)).expect("one triangle");
    tb.overlap(b).is_some()
}

/// Does the closed integer triangle touch the closed integer box? Exact:
/// the octree engine's triangle classifier
/// ([`crate::octree::triangle_cell`]), the one place this rule lives.
pub fn triangle_touches_box(t: &FixedTriangle, b: &Aabb<i64>) -> bool {
    TriangleCellTest::new(t).touches_box(b)
}

/// Does the integer triangle grown by `margin` grid steps in every
/// direction touch the box? Conservative (see
/// [`TriangleCellTest::widened`]): never false when the grown triangle
/// touches it.
///
/// The host runs this on every triangle near the common box, so the two
/// answers the triangle's grown box settles come first, and they are the
/// full test's: the grown box is the full test's three axis-aligned
/// intervals, so a grown box apart from `b` is its "no"; a grown box inside
/// `b` puts the grown triangle inside it, where the conservative test
/// never says no. Only triangles across the box's boundary take the
/// thirteen-axis test (a fifth of the time the host spent preparing a
/// scene went to it on triangles far inside).
pub fn grown_triangle_touches_box(t: &FixedTriangle, margin: i128, b: &Aabb<i64>) -> bool {
    // In i64, saturating: a grid coordinate is far inside it (i128 here
    // cost a third of the host's preparation), and a grown bound that
    // saturates is still beyond every box.
    let step = margin.clamp(-(i64::MAX as i128), i64::MAX as i128) as i64;
    let mut inside = true;
    for k in 0..3 {
        let [x, y, z] = [t[0][k], t[1][k], t[2][k]];
        let lo = x.min(y).min(z).saturating_sub(step);
        let hi = x.max(y).max(z).saturating_add(step);
        if hi < b.lo[k] || lo > b.hi[k] {
            return false;
        }
        inside &= b.lo[k] <= lo && hi <= b.hi[k];
    }
    inside || TriangleCellTest::widened(t, margin).touches_box(b)
}

impl Aabb<i64> {
    /// The box grown by `margin` on every side.
    pub fn grown(&self, margin: i64) -> Aabb<i64> {
        Aabb {
            lo: self.lo.map(|v| v - margin),
            hi: self.hi.map(|v| v + margin),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grown box's shortcuts give the thirteen-axis test's answer on
    /// triangles inside, across and outside a box, at margins 0 to 2.
    #[test]
    fn grown_triangle_shortcuts_are_the_full_test() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let b = unit_box();
        let (mut answers, mut shortcut_inside) = ([0usize; 2], 0);
        for _ in 0..20_000 {
            // Half near the box's middle (inside, or across at margin 2).
            let (lo, hi) = if rng.gen_bool(0.5) { (1, 9) } else { (-6, 16) };
            let mut corner = || -> [i64; 3] { std::array::from_fn(|_| rng.gen_range(lo..=hi)) };
            let t = [corner(), corner(), corner()];
            let margin = rng.gen_range(0..=2);
            let full = TriangleCellTest::widened(&t, margin).touches_box(&b);
            assert_eq!(
                grown_triangle_touches_box(&t, margin, &b),
                full,
                "{t:?}, margin {margin}"
            );
            answers[full as usize] += 1;
            let inside = t
                .iter()
                .flatten()
                .all(|&c| c - margin as i64 >= 0 && c + margin as i64 <= 10);
            shortcut_inside += inside as usize;
        }
        assert!(answers.iter().all(|&n| n > 1000), "{answers:?}");
        assert!(shortcut_inside > 1000, "{shortcut_inside} inside");
    }

    fn unit_box() -> Aabb<i64> {
        Aabb {
            lo: [0, 0, 0],
            hi: [10, 10, 10],
        }
    }

    #[test]
    fn overlap_of_boxes_is_their_intersection_or_none() {
        let a = Aabb {
            lo: [0.0, 0.0, 0.0],
            hi: [2.0, 2.0, 2.0],
        };
        let b = Aabb {
            lo: [1.0, -1.0, 2.0],
            hi: [3.0, 1.0, 5.0],
        };
        assert_eq!(
            a.overlap(&b),
            Some(Aabb {
                lo: [1.0, 0.0, 2.0],
                hi: [2.0, 1.0, 2.0]
            })
        );
        let c = Aabb {
            lo: [2.5, 0.0, 0.0],
            hi: [3.0, 1.0, 1.0],
        };
        assert_eq!(a.overlap(&c), None);
    }

    #[test]
    fn triangle_touching_a_box_face_counts() {
        assert!(triangle_touches_box(
            &[[10, 0, 0], [20, 0, 0], [20, 5, 5]],
            &unit_box()
        ));
        assert!(!triangle_touches_box(
            &[[11, 0, 0], [20, 0, 0], [20, 5, 5]],
            &unit_box()
        ));
    }

    #[test]
    fn triangle_cutting_a_corner_whose_box_overlaps_is_decided_by_its_plane() {
        // The plane x + y + z = 31 passes the corner (10,10,10) at distance; x+y+z = 30 touches it.
        assert!(!triangle_touches_box(
            &[[31, 0, 0], [0, 31, 0], [0, 0, 31]],
            &unit_box()
        ));
        assert!(triangle_touches_box(
            &[[30, 0, 0], [0, 30, 0], [0, 0, 30]],
            &unit_box()
        ));
    }

    #[test]
    fn degenerate_triangles_are_segments_and_points() {
        assert!(triangle_touches_box(
            &[[5, 5, 5], [5, 5, 5], [5, 5, 5]],
            &unit_box()
        ));
        assert!(!triangle_touches_box(
            &[[5, 5, 11], [5, 5, 11], [5, 5, 11]],
            &unit_box()
        ));
        // A segment passing beside an edge of the box: x + y = 21 misses, x + y = 20 touches.
        assert!(!triangle_touches_box(
            &[[21, 0, 5], [0, 21, 5], [0, 21, 5]],
            &unit_box()
        ));
        assert!(triangle_touches_box(
            &[[20, 0, 5], [0, 20, 5], [10, 10, 5]],
            &unit_box()
        ));
    }
}
