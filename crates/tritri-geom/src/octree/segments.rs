//! Display data (`octree_engine.txt`, function 4): the edges of a voxel
//! model's boundary as line segments, and segments clipped against a view
//! box, exactly.
//!
//! **Edges.** Every edge of a boundary face (a face between a full voxel and
//! an empty one or the outside), once, as two voxel corners.
//!
//! **Clipping** ([`clip_segment`]) is Liang–Barsky on integers: the part of
//! the segment `a + t (b - a)`, `0 <= t <= 1`, inside the closed box is
//! `t0 <= t <= t1` with each end a ratio of integers, found by comparing
//! fractions with cross-multiplication (no rounding). A segment that only
//! touches the box gives `t0 == t1`; one parallel to a face and outside its
//! slab gives nothing. The ends become floating point only when they are
//! written out.

use super::voxels::VoxelGrid;
use std::cmp::Ordering;
use std::collections::HashSet;

/// A segment between two integer points.
pub type Segment = [[i64; 3]; 2];

/// An exact fraction `num / den` with `den > 0`, compared by value.
#[derive(Clone, Copy, Debug)]
pub struct Fraction {
    pub num: i128,
    pub den: i128,
}

impl Fraction {
    fn new(num: i128, den: i128) -> Fraction {
        if den < 0 {
            Fraction {
                num: -num,
                den: -den,
            }
        } else {
            Fraction { num, den }
        }
    }

    pub fn value(self) -> f64 {
        self.num as f64 / self.den as f64
    }
}

impl PartialEq for Fraction {
    fn eq(&self, other: &Fraction) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Fraction {}

impl PartialOrd for Fraction {
    fn partial_cmp(&self, other: &Fraction) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Fraction {
    fn cmp(&self, other: &Fraction) -> Ordering {
        (self.num * other.den).cmp(&(other.num * self.den))
    }
}

/// The part of a segment inside a box: parameters `t0 <= t1` in `[0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Clipped {
    pub t0: Fraction,
    pub t1: Fraction,
}

impl Clipped {
    /// The whole segment is inside.
    pub fn is_whole(&self) -> bool {
        self.t0.num == 0 && self.t1.num == self.t1.den
    }

    /// The clipped ends in floating point.
    pub fn ends(&self, s: &Segment) -> [[f64; 3]; 2] {
        [self.t0, self.t1]
            .map(|t| [0, 1, 2].map(|k| s[0][k] as f64 + t.value() * (s[1][k] - s[0][k]) as f64))
    }
}

/// The part of `s` inside the closed box `[lo, hi]`, or `None` when they do
/// not meet. Coordinates up to `2^40` in size keep every product exact.
pub fn clip_segment(s: &Segment, lo: [i64; 3], hi: [i64; 3]) -> Option<Clipped> {
    let mut t0 = Fraction::new(0, 1);
    let mut t1 = Fraction::new(1, 1);
    for k in 0..3 {
        let (a, d) = (s[0][k] as i128, (s[1][k] - s[0][k]) as i128);
        let (l, h) = (lo[k] as i128, hi[k] as i128);
        if d == 0 {
            if a < l || a > h {
                return None;
            }
            continue;
        }
        // Where the line crosses the slab's two planes, in order along it.
        let (at_lo, at_hi) = (Fraction::new(l - a, d), Fraction::new(h - a, d));
        let (enter, exit) = if d > 0 {
            (at_lo, at_hi)
        } else {
            (at_hi, at_lo)
        };
        t0 = t0.max(enter);
        t1 = t1.min(exit);
        if t0 > t1 {
            return None;
        }
    }
    Some(Clipped { t0, t1 })
}

/// Every edge of the model's boundary faces, once, in voxel corners.
pub fn boundary_edges(grid: &VoxelGrid) -> Vec<Segment> {
    let n = grid.side() as i64;
    let occupied =
        |p: [i64; 3]| p.iter().all(|&c| (0..n).contains(&c)) && grid.get(p.map(|c| c as usize));
    let mut seen = HashSet::new();
    let mut edges = Vec::new();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let p = [x, y, z];
                if !occupied(p) {
                    continue;
                }
                for axis in 0..3 {
                    for upper in [0, 1] {
                        let mut q = p;
                        q[axis] += 2 * upper - 1;
                        if occupied(q) {
                            continue;
                        }
                        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
                        let corner = |da: i64, db: i64| {
                            let mut c = p;
                            c[axis] += upper;
                            c[a] += da;
                            c[b] += db;
                            c
                        };
                        let quad = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
                        for i in 0..4 {
                            let (u, v) = (quad[i], quad[(i + 1) % 4]);
                            let edge = if u < v { [u, v] } else { [v, u] };
                            if seen.insert(edge) {
                                edges.push(edge);
                            }
                        }
                    }
                }
            }
        }
    }
    edges
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Against a brute-force oracle: the segment's points at t = i / 840
    /// (840 is divisible by every denominator up to 8, so the clipped ends
    /// of these small segments are among them when they are such
    /// fractions) are inside the box exactly when t0 <= t <= t1.
    #[test]
    fn clipped_parameters_hold_exactly_the_inside_points() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let steps = 840i128;
        for _ in 0..3000 {
            let point = |rng: &mut ChaCha8Rng| [0; 3].map(|_: i64| rng.gen_range(-6..=6));
            let s = [point(&mut rng), point(&mut rng)];
            let lo = [0; 3].map(|_: i64| rng.gen_range(-4..=2));
            let hi = lo.map(|l| l + rng.gen_range(0..=4));
            let clipped = clip_segment(&s, lo, hi);
            for i in 0..=steps {
                // The point at t = i / steps, scaled by `steps`: inside iff
                // every coordinate is within the scaled box.
                let inside = (0..3).all(|k| {
                    let c = s[0][k] as i128 * steps + i * (s[1][k] - s[0][k]) as i128;
                    lo[k] as i128 * steps <= c && c <= hi[k] as i128 * steps
                });
                let t = Fraction::new(i, steps);
                let within = clipped.is_some_and(|c| c.t0 <= t && t <= c.t1);
                assert_eq!(
                    inside, within,
                    "{s:?} in {lo:?}..{hi:?} at t = {i}/{steps}: {clipped:?}"
                );
            }
        }
    }

    /// A segment touching the box at a corner, one along a face, one
    /// parallel outside it.
    #[test]
    fn touching_and_parallel_segments() {
        let (lo, hi) = ([0; 3], [4; 3]);
        let corner = clip_segment(&[[4, 4, 4], [8, 9, 5]], lo, hi).unwrap();
        assert_eq!(
            (corner.t0, corner.t1),
            (Fraction::new(0, 1), Fraction::new(0, 1))
        );
        assert!(clip_segment(&[[-1, 0, 4], [5, 4, 4]], lo, hi).is_some());
        assert!(clip_segment(&[[-1, 0, 5], [5, 4, 5]], lo, hi).is_none());
        assert!(clip_segment(&[[1, 1, 1], [2, 3, 1]], lo, hi)
            .unwrap()
            .is_whole());
    }

    /// One voxel has 12 edges; two voxels side by side, 20.
    #[test]
    fn boundary_edges_of_small_models() {
        let mut g = VoxelGrid::empty(2);
        g.set([1, 1, 1]);
        assert_eq!(boundary_edges(&g).len(), 12);
        g.set([2, 1, 1]);
        assert_eq!(boundary_edges(&g).len(), 20);
    }
}
