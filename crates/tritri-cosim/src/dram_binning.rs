//! The broad phase's binning with its lists in external memory, pass by
//! pass: the planner's tree ([`tritri_geom::scene::octree`]) walked depth
//! first, each split cell one pass of the list pass unit in its
//! clock-exact model ([`crate::list_pass::run_model`], co-simulated in
//! tests/list_pass.rs) against the memory model, its children's lists read
//! back from the memory and handed to the children's passes. It counts the
//! clocks and the bytes every pass moves, and checks that the lists that
//! reach the leaves are the planner's.
//!
//! It walks the planner's final tree: a cell is a leaf where the planner
//! made one, is split where it holds both objects and is not a leaf, and is
//! dropped where one object is absent. The planner (and the on-chip binning
//! unit, which follows it) also classifies the cells of subtrees it tries
//! and then gives up for a leaf above them (its lookahead); those passes
//! are not walked here, so [`DramBinning::passes`] is at most the
//! planner's `cells_visited`, and both are reported. Nor is the controller
//! between the passes counted yet (the unit that pops the next cell and
//! allocates its children's regions): the clocks are the passes' own, one
//! after another.

use crate::list_pass::{run_model, PassCase};
use anyhow::{bail, Context as _};
use std::collections::{HashMap, HashSet};
use tritri_geom::octree::cell::Cell;
use tritri_geom::scene::octree::OctreeSchedule;
use tritri_geom::scene::TaggedTriangle;
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::octree::list_entry::{pack, unpack, ENTRY_BYTES};
use tritri_rtl::octree::list_pass_machine::ListPassConfig;

/// What the walk took.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DramBinning {
    /// Cells split: one pass each.
    pub passes: u64,
    /// The passes' clocks, summed.
    pub cycles: u64,
    /// Clocks the memory stalled in them.
    pub stalled: u64,
    /// Bytes the passes read (every entry of every split cell) and wrote
    /// (every entry of every child).
    pub bytes_read: u64,
    pub bytes_written: u64,
    /// Of those, the bytes written to children that hold one object only,
    /// which no later pass or leaf reads.
    pub bytes_dropped: u64,
    /// The leaves reached, as the planner's leaves were checked against.
    pub leaves: u64,
    /// The largest list a pass read (entries of both objects): what the
    /// children's regions are sized by.
    pub largest_pass: u64,
}

/// Walks `schedule`'s tree from `root_lists` (each object's triangles that
/// the root bins, in the grid's coordinates) on a unit of `config` against
/// a memory of `params`. An error if a pass fails, or if the lists that
/// reach a leaf are not the planner's (as sets of triangle indices).
pub fn walk(
    schedule: &OctreeSchedule,
    root_lists: [&[TaggedTriangle]; 2],
    config: ListPassConfig,
    params: MemoryParams,
) -> anyhow::Result<DramBinning> {
    let root = schedule.root.context("the schedule has no root")?;
    let g = config.grid_bits;
    // The planner's leaves by cell.
    let mut leaves: HashMap<Cell, [HashSet<u32>; 2]> = HashMap::new();
    for leaf in &schedule.leaves {
        let (a, b) = schedule.leaf_arrays(leaf);
        let ids = |t: &[TaggedTriangle]| t.iter().map(|t| t.id).collect::<HashSet<_>>();
        leaves.insert(leaf.cell, [ids(a), ids(b)]);
    }
    let entries = |list: &[TaggedTriangle]| -> Vec<[u8; ENTRY_BYTES]> {
        list.iter().map(|t| pack(t.id, &t.triangle, g)).collect()
    };
    let mut stack = vec![(root, [entries(root_lists[0]), entries(root_lists[1])])];
    let mut run = DramBinning::default();
    while let Some((cell, lists)) = stack.pop() {
        if let Some(expected) = leaves.get(&cell) {
            for (k, list) in lists.iter().enumerate() {
                let got: HashSet<u32> = list.iter().map(|e| unpack(e, g).0).collect();
                if got != expected[k] {
                    bail!(
                        "leaf {cell:?}: object {k}'s list has {} triangles, the planner's {}",
                        got.len(),
                        expected[k].len()
                    );
                }
            }
            run.leaves += 1;
            continue;
        }
        if lists[0].is_empty() || lists[1].is_empty() {
            run.bytes_dropped += ((lists[0].len() + lists[1].len()) * ENTRY_BYTES) as u64;
            continue;
        }
        if !cell.splittable() {
            bail!("cell {cell:?} holds both objects, cannot be split, and is not a leaf");
        }
        let entries_in = (lists[0].len() + lists[1].len()) as u64;
        // The shorter list goes first: the unit writes the second only to
        // children the first reached (`list_pass`), so the longer is cut.
        let swapped = lists[1].len() < lists[0].len();
        let [first, second] = lists;
        let lists = if swapped {
            [second, first]
        } else {
            [first, second]
        };
        let case = PassCase {
            config,
            params,
            cell,
            lists,
            limit: 64 * (entries_in + 64) * config.beats_per_entry(),
        };
        let out = run_model(&case).with_context(|| format!("the pass of cell {cell:?}"))?;
        if out.error || out.faults != 0 {
            bail!(
                "the pass of cell {cell:?}: error {}, {} protocol faults",
                out.error,
                out.faults
            );
        }
        let mut children = case.child_lists(&out)?;
        if swapped {
            children.rotate_left(8);
        }
        run.passes += 1;
        run.cycles += out.cycles;
        run.stalled += out.stalled;
        run.bytes_read += entries_in * ENTRY_BYTES as u64;
        run.bytes_written += out.child_counts.iter().sum::<u64>() * ENTRY_BYTES as u64;
        run.largest_pass = run.largest_pass.max(entries_in);
        // Depth first, octant 0 on top, as the binning unit walks.
        for o in (0..8).rev() {
            let list = |i: usize| -> Vec<[u8; ENTRY_BYTES]> {
                children[i]
                    .iter()
                    .map(|e| e.as_slice().try_into().expect("32-byte entries"))
                    .collect()
            };
            stack.push((cell.child(o), [list(o), list(8 + o)]));
        }
    }
    if run.leaves != schedule.leaves.len() as u64 {
        bail!(
            "the walk reached {} leaves, the planner has {}",
            run.leaves,
            schedule.leaves.len()
        );
    }
    Ok(run)
}
