//! An affine function over a box, tracked the way the octree engine's
//! classifier does: by its value at the box's low corner and its increments
//! along the three edges.
//!
//! For `f(p) = g · p` and the box `[lo, lo + e]`, the value at the corner
//! picking the upper end on the axes in `octant` is
//! `at_lo + Σ_{k in octant} along[k]` with `along[k] = g_k · e_k`. Its range
//! over the closed box is reached at corners (f is affine), so
//! `min = at_lo + Σ min(0, along[k])` and likewise the max.
//!
//! A child of a cube halves every edge: `along' = along / 2` and
//! `at_lo' = at_lo + Σ_{k in octant} along'[k]`. For a cell of side >= 2 on
//! the integer grid every `along[k] = g_k · 2^level` is even, so the halving
//! is an exact shift. Only a root's values take multiplications.

use super::cell::Cell;
use crate::bounding_volume::Aabb;

/// `g · p` over a box: value at the low corner, increments along the edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AffineOverBox {
    pub at_lo: i128,
    pub along: [i128; 3],
}

impl AffineOverBox {
    /// The values of `g · p` over the closed box `b` (multiplications: the
    /// root's only).
    pub fn over_box(gradient: [i128; 3], b: &Aabb<i64>) -> AffineOverBox {
        let at_lo = (0..3).map(|k| gradient[k] * b.lo[k] as i128).sum();
        let along = [0, 1, 2].map(|k| gradient[k] * (b.hi[k] - b.lo[k]) as i128);
        AffineOverBox { at_lo, along }
    }

    pub fn over_cell(gradient: [i128; 3], cell: &Cell) -> AffineOverBox {
        Self::over_box(gradient, &cell.as_box())
    }

    /// The values over child `octant` of a cube of side >= 2: adds and shifts.
    #[inline]
    pub fn child(&self, octant: usize) -> AffineOverBox {
        debug_assert!(
            self.along.iter().all(|a| a % 2 == 0),
            "halving is exact only on a cell of side >= 2"
        );
        let along = self.along.map(|a| a >> 1);
        let mut at_lo = self.at_lo;
        for (k, a) in along.iter().enumerate() {
            if octant >> k & 1 == 1 {
                at_lo += a;
            }
        }
        AffineOverBox { at_lo, along }
    }

    /// `(min, max)` of the function over the closed box.
    #[inline]
    pub fn range(&self) -> (i128, i128) {
        let mut lo = self.at_lo;
        let mut hi = self.at_lo;
        for a in self.along {
            if a < 0 {
                lo += a;
            } else {
                hi += a;
            }
        }
        (lo, hi)
    }

    /// Does the function take a value in the closed interval `[low, high]`
    /// somewhere on the box? (It is continuous on a connected box, so: do
    /// the two ranges meet.)
    #[inline]
    pub fn meets(&self, low: i128, high: i128) -> bool {
        let (lo, hi) = self.range();
        lo <= high && low <= hi
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Interpolated children equal the function evaluated directly on the
    /// child's box, for every octant down to side 1.
    #[test]
    fn interpolation_is_exact_down_to_unit_cells() {
        let g = [7i128, -3, 11];
        let mut cells = vec![Cell {
            lo: [-5, 2, 9],
            level: 4,
        }];
        while let Some(c) = cells.pop() {
            let values = AffineOverBox::over_cell(g, &c);
            if !c.splittable() {
                continue;
            }
            for o in 0..8 {
                let child = c.child(o);
                assert_eq!(
                    values.child(o),
                    AffineOverBox::over_cell(g, &child),
                    "{c:?} octant {o}"
                );
                cells.push(child);
            }
        }
    }

    #[test]
    fn range_is_the_extreme_corners() {
        let b = Aabb {
            lo: [0, 0, 0],
            hi: [2, 3, 4],
        };
        let f = AffineOverBox::over_box([1, -2, 3], &b);
        assert_eq!(f.range(), (-6, 14));
        assert!(f.meets(14, 20) && f.meets(-10, -6) && !f.meets(15, 20));
    }
}
