//! Cycles and memory of a binning unit built around the classifier step
//! ([`super::cell_classifier`]), following the broad phase's plan
//! (`tritri_geom::scene::octree`) cell for cell. The classifier and the
//! setup unit ([`super::triangle_setup`]: each triangle's gradients and
//! intervals at the root, the multiplications) are built and
//! co-simulated; the depth-first controller is modelled here, not built
//! yet.
//!
//! The unit works like this:
//!
//! 1. The host streams each object's triangles once, one per clock; the
//!    setup unit turns each into an entry of the root, which goes straight
//!    on through the classifier (the root's pass is the stream itself).
//! 2. A cell is decided by streaming its entries through the classifiers,
//!    [`LANES_PER_OBJECT`] per clock and object (four classifiers; each
//!    object's entries in two banks by index parity, as the system has one
//!    memory per object): each comes out with its values over the cell and its
//!    children mask, is stored for the cell, and counted per child and
//!    object. After the last entry and the classifier's latency, one clock
//!    decides: leaf, or split (the planner's rule on the counts).
//! 3. Splitting visits each child with entries of both objects: its
//!    entries are the parent's with the child's bit set, streamed again
//!    with `descend` (an index list per child, written in step 2, saves
//!    scanning the parent).
//! 4. A leaf's triangle ids go to the system's write port; loading them is
//!    the batch load the system's cycle model already counts.
//!
//! So binning takes `N + setup + Σ_cells (ceil(max(a, b) / 2) + latency
//! + 1)` clocks, and the narrow phase follows (not overlapped: an upper
//! bound).

use super::cell_classifier::{AXES, CELL_CLASSIFIER_LATENCY, TAG_BITS};
use super::value_bits;

/// Clocks from a triangle into the setup unit to its root entry (the
/// built unit's latency); paid once per run.
pub const SETUP_LATENCY: u64 = super::triangle_setup::TRIANGLE_SETUP_LATENCY as u64;

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
    /// Most entries held at once along the depth-first path.
    pub peak_path_entries: u64,
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

/// Bits of one stored entry: the thirteen values, the triangle id and the
/// children mask (gradients and intervals stay in a per-triangle table).
pub fn entry_bits(grid_bits: usize) -> u64 {
    (AXES * value_bits(grid_bits) + TAG_BITS + 8) as u64
}

/// Bits of the per-triangle table: the vertices (the edge-axis gradients
/// are their differences, wired; the axes' gradients are constants), the
/// normal, and the triangle's interval along each function.
pub fn triangle_record_bits(grid_bits: usize) -> u64 {
    (9 * grid_bits + 3 * (2 * grid_bits + 3) + 2 * AXES * value_bits(grid_bits)) as u64
}

/// Memory the binning unit needs: the entries on the path at their peak
/// plus the per-triangle table.
pub fn binning_memory_bits(work: &BinningWork, grid_bits: usize) -> u64 {
    work.peak_path_entries * entry_bits(grid_bits) + work.triangles * triangle_record_bits(grid_bits)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cycles_count_every_entry_and_each_cell_once() {
        assert_eq!(cell_cycles(40, 91), 46 + 6);
        let work = BinningWork { triangles: 100, cells: 3, entries: 250, cell_cycles: 200, peak_path_entries: 180 };
        assert_eq!(binning_cycles(&work), 100 + SETUP_LATENCY + 200);
        assert_eq!(entry_bits(24), 13 * 78 + 16 + 8);
    }
}
