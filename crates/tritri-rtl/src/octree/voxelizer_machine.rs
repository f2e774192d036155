//! The cycle model of the triangle voxelizer
//! ([`super::triangle_voxelizer`]): its records and the clock edge each is
//! taken at, edge for edge, for a stream of triangles offered one after
//! another (the reader always ready).
//!
//! A triangle enters the setup when the setup advances; it reaches the
//! setup's output [`TRIANGLE_SETUP_LATENCY`] edges later and waits there
//! until the traversal of the previous triangle is over, which is when it
//! is loaded. The setup stalls while its output waits. The traversal
//! ([`StackSchedule`]) issues the root the edge after the load. The masks
//! are decided by `tritri_geom::octree::triangle_cell::TriangleCellTest`
//! on the fine grid, each cell directly; the records are the surface
//! voxelization's (`tritri_geom::octree::voxelize::surface`).

use super::cell_classifier::CELL_CLASSIFIER_LATENCY;
use super::triangle_setup::TRIANGLE_SETUP_LATENCY;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::cell::Cell;
use tritri_geom::octree::stack_schedule::StackSchedule;
use tritri_geom::octree::triangle_cell::TriangleCellTest;
use tritri_geom::octree::voxelize::SUB_BITS;
use tritri_geom::octree::voxels::VoxelGrid;

/// One record: a level-1 cell (low corner in voxels, even coordinates) and
/// the mask of its eight voxels the triangle meets (bit `o`, bit `k` of
/// `o` the upper half along axis `k`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct VoxelRecord {
    pub lo: [i64; 3],
    pub mask: u8,
}

/// A run of the voxelizer over a stream of triangles.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct VoxelizerRun {
    /// In the order they leave the unit.
    pub records: Vec<VoxelRecord>,
    /// The edge each record is taken at, counted from 0, the edge the first
    /// triangle is offered at.
    pub edges: Vec<u64>,
    /// Edges until the unit is idle with every triangle taken.
    pub cycles: u64,
    /// Cells classified (the cycle model's only).
    pub cells: u64,
    /// The most entries the stack's RAM held (the cycle model's only).
    pub stack_depth: usize,
}

impl VoxelizerRun {
    /// The voxels the records mark on the `2^level` grid.
    pub fn grid(&self, level: u32) -> VoxelGrid {
        let mut grid = VoxelGrid::empty(level);
        for r in &self.records {
            let cell = Cell { lo: r.lo, level: 1 };
            for o in (0..8).filter(|o| r.mask >> o & 1 == 1) {
                grid.set(cell.child(o).lo.map(|c| c as usize));
            }
        }
        grid
    }
}

/// A cell in voxels on the fine grid the triangles are quantized to.
pub fn fine_cell(cell: Cell) -> Cell {
    Cell {
        lo: cell.lo.map(|c| c << SUB_BITS),
        level: cell.level + SUB_BITS,
    }
}

/// The records and edges of the voxelizer for `triangles` (fine-grid
/// vertices in `[0, 2^(level + SUB_BITS)]`) on the `2^level` grid.
pub fn voxelizer_schedule(triangles: &[FixedTriangle], level: u32) -> VoxelizerRun {
    let mut run = VoxelizerRun::default();
    let mut machine = StackSchedule::new(CELL_CLASSIFIER_LATENCY as u64);
    // The setup's stages (the last is its output register), by triangle.
    let mut setup: [Option<usize>; TRIANGLE_SETUP_LATENCY] = [None; TRIANGLE_SETUP_LATENCY];
    let mut loaded: Option<TriangleCellTest> = None;
    let mut offered = 0usize;
    let mut shown = false;
    let mut edge = 0u64;
    while offered < triangles.len() || setup.iter().any(Option::is_some) || machine.busy() || shown
    {
        let output = setup[TRIANGLE_SETUP_LATENCY - 1];
        let load = output.is_some() && !machine.busy();
        let advance = output.is_none() || load;
        let result = match &loaded {
            Some(test) => machine.edge(edge, |cell| {
                let mask = test.children_of_cell(&fine_cell(cell));
                if cell.level == 1 {
                    ((mask != 0).then_some(VoxelRecord { lo: cell.lo, mask }), 0)
                } else {
                    (None, mask)
                }
            }),
            None => None,
        };
        shown = false;
        if let Some(Some(record)) = result {
            run.records.push(record);
            // Shown after this edge, taken at the next.
            run.edges.push(edge + 1);
            shown = true;
        }
        if let (true, Some(t)) = (load, output) {
            loaded = Some(TriangleCellTest::new(&triangles[t]));
            machine.start(Cell { lo: [0; 3], level });
        }
        if advance {
            setup.rotate_right(1);
            setup[0] = (offered < triangles.len()).then(|| {
                offered += 1;
                offered - 1
            });
        }
        edge += 1;
    }
    run.cycles = edge;
    run.cells = machine.cells;
    run.stack_depth = machine.stack_depth;
    run
}

#[cfg(test)]
mod tests {
    use super::*;
    use tritri_geom::octree::voxelize::surface;

    /// The records mark the software voxelizer's voxels, on triangles
    /// lying on cell faces, edges and corners, degenerate ones too.
    #[test]
    fn records_mark_the_surface_voxels() {
        let s = 1i64 << SUB_BITS;
        let level = 3;
        let triangles: Vec<FixedTriangle> = vec![
            [[0, 0, 0], [8 * s, 0, 0], [0, 8 * s, 0]],
            [
                [2 * s, 2 * s, 2 * s],
                [6 * s, 2 * s, 2 * s],
                [2 * s, 6 * s, 5 * s],
            ],
            [[3 * s, 3 * s, 3 * s]; 3],
            [[s, s, s], [7 * s, 7 * s, 7 * s], [4 * s, 4 * s, 4 * s]],
            [
                [s / 3, 5 * s + 7, 8 * s],
                [8 * s, s, s / 2],
                [4 * s, 8 * s, 0],
            ],
        ];
        let run = voxelizer_schedule(&triangles, level);
        assert_eq!(run.grid(level), surface(&triangles, level, &mut |_| ()));
        assert_eq!(run.records.len(), run.edges.len());
        assert!(run.edges.windows(2).all(|w| w[0] < w[1]));
        assert!(run.cycles > *run.edges.last().unwrap());
    }
}
