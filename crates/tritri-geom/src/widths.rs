//! The one place that derives the bit widths of the fixed-point datapath.
//!
//! Coordinates are W-bit two's-complement integers, so every coordinate lies
//! in `[-2^(W-1), 2^(W-1) - 1]` and a difference of two is at most
//! `M = 2^W - 1` in magnitude. The tight bounds (docs/ARCHITECTURE.md, conventions):
//!
//! * a difference needs `W + 1` bits;
//! * a cross-product component of two edge vectors from a common vertex is
//!   twice the area of a projected triangle inside a square of side `M`, so
//!   `|.| <= M^2` and it needs `2W + 1` bits; orient2d is the same quantity;
//! * orient3d `[a,b,c,d] = (d-a)·((b-a)×(c-a))` is six times the volume of a
//!   tetrahedron inside a cube of side `M`, so `|.| <= 2 M^3` and it needs
//!   `3W + 2` bits.
//!
//! Because the final orient3d value fits in `3W + 2` bits, the hardware may
//! let intermediate sums wrap modulo `2^(3W+2)`: the wrapped result is exact.
//! The software fixed-point model and the hardware generator both read these
//! numbers from [`FixedWidths`].

/// Width of a coordinate difference for W-bit coordinates: `W + 1`.
pub const fn difference_bits(coordinate: usize) -> usize {
    coordinate + 1
}

/// Width of a cross-product component or orient2d value: `2W + 1`.
pub const fn cross_bits(coordinate: usize) -> usize {
    2 * coordinate + 1
}

/// Width of an orient3d value: `3W + 2`.
pub const fn orient3d_bits(coordinate: usize) -> usize {
    3 * coordinate + 2
}

/// Smallest and largest coordinate width the project supports.
pub const MIN_WIDTH: u32 = 8;
pub const MAX_WIDTH: u32 = 32;

/// Bit widths of every stage of the W-bit datapath.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FixedWidths {
    /// Coordinate width W.
    pub coordinate: u32,
    /// Width of a coordinate difference: W + 1.
    pub difference: u32,
    /// Width of a cross-product component or an orient2d value: 2W + 1.
    pub cross: u32,
    /// Width of an orient3d value (plane distance, interval determinant): 3W + 2.
    pub orient3d: u32,
}

/// Error for a width outside `MIN_WIDTH..=MAX_WIDTH`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "coordinate width {0} is out of range: supported widths are {MIN_WIDTH} to {MAX_WIDTH} bits"
)]
pub struct WidthOutOfRange(pub u32);

impl FixedWidths {
    /// Widths for W-bit coordinates; errors outside `MIN_WIDTH..=MAX_WIDTH`.
    pub fn new(coordinate: u32) -> Result<Self, WidthOutOfRange> {
        if !(MIN_WIDTH..=MAX_WIDTH).contains(&coordinate) {
            return Err(WidthOutOfRange(coordinate));
        }
        Ok(FixedWidths {
            coordinate,
            difference: difference_bits(coordinate as usize) as u32,
            cross: cross_bits(coordinate as usize) as u32,
            orient3d: orient3d_bits(coordinate as usize) as u32,
        })
    }

    /// Smallest representable coordinate, `-2^(W-1)`.
    pub fn min_coordinate(&self) -> i64 {
        -(1i64 << (self.coordinate - 1))
    }

    /// Largest representable coordinate, `2^(W-1) - 1`.
    pub fn max_coordinate(&self) -> i64 {
        (1i64 << (self.coordinate - 1)) - 1
    }

    /// Bits of one triangle on the bus: nine coordinates.
    pub fn triangle_bits(&self) -> u32 {
        9 * self.coordinate
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thesis_width_24_gives_25_49_74() {
        let w = FixedWidths::new(24).unwrap();
        assert_eq!((w.difference, w.cross, w.orient3d), (25, 49, 74));
        assert_eq!(
            w.triangle_bits(),
            216,
            "the thesis's bus carries 216 bits per triangle"
        );
    }

    #[test]
    fn widths_outside_8_to_32_are_refused() {
        assert_eq!(FixedWidths::new(7), Err(WidthOutOfRange(7)));
        assert_eq!(FixedWidths::new(33), Err(WidthOutOfRange(33)));
        assert!(FixedWidths::new(8).is_ok() && FixedWidths::new(32).is_ok());
    }

    /// The bounds are tight: the extreme configurations reach M^2 and 2M^3 - ish
    /// magnitudes that need every bit.
    #[test]
    fn extreme_values_fit_their_widths() {
        for w in MIN_WIDTH..=MAX_WIDTH {
            let f = FixedWidths::new(w).unwrap();
            let m = (1i128 << w) - 1;
            let fits =
                |v: i128, bits: u32| v < (1i128 << (bits - 1)) && -v >= -(1i128 << (bits - 1));
            assert!(fits(m, f.difference));
            assert!(!fits(m, f.difference - 1));
            assert!(fits(m * m, f.cross));
            assert!(!fits(m * m, f.cross - 1));
            assert!(fits(2 * m * m * m, f.orient3d));
            assert!(!fits(2 * m * m * m, f.orient3d - 1));
        }
    }
}
