//! The binning unit's cost formula: what a cell's pass costs
//! ([`cell_cycles`]), which the broad phase's planner
//! (`tritri_geom::scene::octree`) charges in its split rule, and the
//! whole run's clocks from the plan's totals ([`binning_cycles`]).
//!
//! The unit itself is [`super::binning_unit`], and its clock-exact model
//! [`super::binning_machine`] (whose count adds the clocks this formula
//! leaves out: the frame stack, the leaf-cost queries, the rollbacks). The
//! formula stays for configurations the unit is not built for (a depth or
//! pipeline count that is not a power of two, a grid other than 16, 24 or
//! 32 bits), where `tritri sim` reports it instead.
//!
//! A pass streams a cell's lists through the classifiers,
//! [`LANES_PER_OBJECT`] per clock and object, and after the last entry and
//! the classifier's latency one clock decides: `ceil(max(a, b) / 2) +
//! latency + 1`. The root's pass is the input stream, one triangle per
//! clock. So binning takes `N + setup + Σ_cells (ceil(max(a, b) / 2) +
//! latency + 1)` clocks.

use crate::octree::cell_classifier::CELL_CLASSIFIER_LATENCY;

/// Clocks from a triangle into the setup unit to its root entry (the
/// built unit's latency); paid once per run.
pub const SETUP_LATENCY: u64 = crate::octree::triangle_setup::TRIANGLE_SETUP_LATENCY as u64;

/// Classifiers per object. Two rather than one: classifying is the larger
/// part of the time on real scenes, and with one the split rule stops
/// where a deeper cell costs more to classify than its pairs save, leaving
/// up to 4.2 times the box-overlap pairs (bunny x armadillo); with two,
/// 2.1 to 3.5 times and a third less time first triangle in to last pair
/// out (docs/broad-phase.md).
pub const LANES_PER_OBJECT: u64 = 2;

/// What the plan asks of the binning unit (from the broad phase's schedule).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BinningWork {
    /// Triangles streamed in and binned.
    pub triangles: u64,
    /// Cells classified.
    pub cells: u64,
    /// Entries classified: the sum over classified cells of their entries.
    pub entries: u64,
    /// [`cell_cycles`] summed over the classified cells.
    pub cell_cycles: u64,
}

/// Clocks to classify one cell of `a` A-entries and `b` B-entries,
/// [`LANES_PER_OBJECT`] classifiers per object, and decide it.
pub fn cell_cycles(a: u64, b: u64) -> u64 {
    a.max(b).div_ceil(LANES_PER_OBJECT) + CELL_CLASSIFIER_LATENCY as u64 + 1
}

/// Clocks from the first triangle in to the last leaf decided.
pub fn binning_cycles(work: &BinningWork) -> u64 {
    work.triangles + SETUP_LATENCY + work.cell_cycles
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cycles_count_every_entry_and_each_cell_once() {
        assert_eq!(cell_cycles(40, 91), 46 + 6);
        let work = BinningWork {
            triangles: 100,
            cells: 3,
            entries: 250,
            cell_cycles: 200,
        };
        assert_eq!(binning_cycles(&work), 100 + SETUP_LATENCY + 200);
    }
}
