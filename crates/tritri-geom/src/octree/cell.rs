//! Cubic cells of an octree on the integer grid.

use crate::bounding_volume::Aabb;

/// The closed cube `lo <= p <= lo + 2^level` (componentwise) on the integer
/// grid. `level` is the cell's side as a power of two, so a cell of level
/// `k >= 1` has eight children of level `k - 1` whose corners are grid points.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Cell {
    pub lo: [i64; 3],
    pub level: u32,
}

impl Cell {
    /// The side length `2^level`.
    pub fn size(&self) -> i64 {
        1i64 << self.level
    }

    /// The smallest cell with its low corner at `b.lo` that holds `b`.
    pub fn covering(b: &Aabb<i64>) -> Cell {
        let extent = (0..3).map(|k| b.hi[k] - b.lo[k]).max().unwrap_or(0).max(1) as u64;
        Cell {
            lo: b.lo,
            level: extent.next_power_of_two().trailing_zeros(),
        }
    }

    /// Can the cell be split into eight children on the grid?
    pub fn splittable(&self) -> bool {
        self.level >= 1
    }

    /// Child `octant` (bit `k` set: the upper half along axis `k`).
    pub fn child(&self, octant: usize) -> Cell {
        debug_assert!(self.splittable() && octant < 8);
        let half = self.size() / 2;
        let lo = [0, 1, 2].map(|k| self.lo[k] + if octant >> k & 1 == 1 { half } else { 0 });
        Cell {
            lo,
            level: self.level - 1,
        }
    }

    /// The closed box of the cell.
    pub fn as_box(&self) -> Aabb<i64> {
        Aabb {
            lo: self.lo,
            hi: self.lo.map(|v| v + self.size()),
        }
    }

    /// Is `p` in the half-open cell `lo <= p < lo + size`? Half-open cells
    /// of one level tile space, so every point is in exactly one.
    pub fn contains_half_open(&self, p: [i64; 3]) -> bool {
        (0..3).all(|k| self.lo[k] <= p[k] && p[k] < self.lo[k] + self.size())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn covering_cell_holds_the_box_with_a_power_of_two_side() {
        let b = Aabb {
            lo: [-3, 0, 5],
            hi: [2, 9, 5],
        };
        let c = Cell::covering(&b);
        assert_eq!(
            c,
            Cell {
                lo: [-3, 0, 5],
                level: 4
            }
        );
        // A single point still gets a splittable-or-not cell of side 1.
        assert_eq!(
            Cell::covering(&Aabb {
                lo: [1, 1, 1],
                hi: [1, 1, 1]
            })
            .level,
            0
        );
    }

    #[test]
    fn children_tile_the_parent_half_open() {
        let parent = Cell {
            lo: [4, -8, 0],
            level: 3,
        };
        for x in 4..12 {
            for y in -8..0 {
                for z in 0..8 {
                    let owners = (0..8)
                        .filter(|&o| parent.child(o).contains_half_open([x, y, z]))
                        .count();
                    assert_eq!(owners, 1, "({x},{y},{z})");
                }
            }
        }
    }
}
