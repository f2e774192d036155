//! A voxel model: an `n^3` grid of occupied / empty unit cells, `n = 2^k`,
//! stored one bit per voxel in x-fastest order (the engine's memory holds
//! the same bits a word at a time).

use super::tree::SetOperation;

/// Voxel `(x, y, z)` is the unit cell `[x, x+1] × [y, y+1] × [z, z+1]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VoxelGrid {
    level: u32,
    bits: Vec<u64>,
}

impl VoxelGrid {
    /// An empty grid of side `2^level` (level 0 to 10: up to 1024^3).
    pub fn empty(level: u32) -> VoxelGrid {
        assert!(
            level <= 10,
            "a voxel grid of side 2^{level} is larger than this model keeps in memory"
        );
        let voxels = 1usize << (3 * level);
        VoxelGrid {
            level,
            bits: vec![0; voxels.div_ceil(64)],
        }
    }

    /// The side `n`.
    pub fn side(&self) -> usize {
        1 << self.level
    }

    pub fn level(&self) -> u32 {
        self.level
    }

    fn index(&self, p: [usize; 3]) -> usize {
        let n = self.side();
        debug_assert!(p.iter().all(|&c| c < n));
        (p[2] * n + p[1]) * n + p[0]
    }

    pub fn get(&self, p: [usize; 3]) -> bool {
        let i = self.index(p);
        self.bits[i / 64] >> (i % 64) & 1 == 1
    }

    pub fn set(&mut self, p: [usize; 3]) {
        let i = self.index(p);
        self.bits[i / 64] |= 1 << (i % 64);
    }

    /// Marks every voxel of the cube at `lo` with side `2^level`, a row of
    /// x at a time (whole words where the row covers them).
    pub fn fill_cube(&mut self, lo: [usize; 3], level: u32) {
        let s = 1usize << level;
        for z in lo[2]..lo[2] + s {
            for y in lo[1]..lo[1] + s {
                let start = self.index([lo[0], y, z]);
                fill_bit_range(&mut self.bits, start, start + s);
            }
        }
    }

    /// The voxels 64 to a word, voxel `i` (x fastest) in bit `i % 64` of
    /// word `i / 64`: the voxel memory's words.
    pub fn words(&self) -> &[u64] {
        &self.bits
    }

    /// A grid from [`Self::words`]; `None` if the count does not fit the
    /// level or a bit beyond the last voxel is set.
    pub fn from_words(level: u32, words: Vec<u64>) -> Option<VoxelGrid> {
        let grid = VoxelGrid { level, bits: words };
        let voxels = 1usize << (3 * level);
        let fits = level <= 10 && grid.bits.len() == voxels.div_ceil(64);
        (fits && (voxels % 64 == 0 || grid.bits[voxels / 64] >> (voxels % 64) == 0)).then_some(grid)
    }

    /// Occupied voxels.
    pub fn count(&self) -> u64 {
        self.bits.iter().map(|w| w.count_ones() as u64).sum()
    }

    /// A set operation, 64 voxels a word (the engine's memory-side unit
    /// streams words the same way). Both grids must have one level.
    pub fn combine(&self, op: SetOperation, other: &VoxelGrid) -> VoxelGrid {
        assert_eq!(
            self.level, other.level,
            "set operations need models of one grid"
        );
        let word = |a: u64, b: u64| match op {
            SetOperation::Union => a | b,
            SetOperation::Intersection => a & b,
            SetOperation::Difference => a & !b,
        };
        VoxelGrid {
            level: self.level,
            bits: self
                .bits
                .iter()
                .zip(&other.bits)
                .map(|(&a, &b)| word(a, b))
                .collect(),
        }
    }

    /// The voxels not in the model.
    pub fn complement(&self) -> VoxelGrid {
        let mut bits: Vec<u64> = self.bits.iter().map(|w| !w).collect();
        // A grid of fewer than 64 voxels (level 1) keeps its unused bits clear.
        let voxels = 1usize << (3 * self.level);
        if voxels % 64 != 0 {
            bits[voxels / 64] &= (1u64 << (voxels % 64)) - 1;
        }
        VoxelGrid {
            level: self.level,
            bits,
        }
    }
}

/// Sets bits `start..end`.
fn fill_bit_range(bits: &mut [u64], start: usize, end: usize) {
    let mut i = start;
    while i < end {
        let (word, bit) = (i / 64, i % 64);
        let run = (64 - bit).min(end - i);
        let mask = if run == 64 {
            u64::MAX
        } else {
            ((1u64 << run) - 1) << bit
        };
        bits[word] |= mask;
        i += run;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filled_cubes_are_exactly_their_voxels() {
        let mut g = VoxelGrid::empty(4);
        g.fill_cube([8, 4, 0], 2);
        g.fill_cube([0, 0, 8], 3);
        assert_eq!(g.count(), 64 + 512);
        assert!(g.get([8, 4, 0]) && g.get([11, 7, 3]) && !g.get([12, 4, 0]) && !g.get([7, 4, 0]));
        assert!(g.get([7, 7, 15]) && !g.get([8, 0, 8]));
    }
}
