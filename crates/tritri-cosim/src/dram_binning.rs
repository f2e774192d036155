//! The broad phase's binning with every list in external memory, on a
//! prepared scene: the host's lists written into the memory, the
//! controller's clock-exact model
//! ([`tritri_rtl::octree::dram_binning_machine`]) run over the list pass
//! unit's (co-simulated in tests/list_pass.rs) against the memory model,
//! and its leaves held to the planner's for a binner that streams its
//! leaves ([`DramSplitRule`]), cell for cell and triangle for triangle.
//!
//! The memory: A's root list at 0, B's after it on a write burst, then
//! the arena for the children's lists.

use anyhow::{bail, Context as _};
use tritri_geom::scene::octree::{schedule, OctreeSchedule};
use tritri_geom::scene::{PreparedScene, TaggedTriangle};
use tritri_rtl::axi::memory_model::{AxiMemory, MemoryParams};
use tritri_rtl::octree::binning_machine::BinningParams;
use tritri_rtl::octree::dram_binning_machine::{
    run_dram_binning, DramBinningConfig, DramBinningRun, DramSplitRule,
};
use tritri_rtl::octree::list_entry::{pack, unpack, ENTRY_BYTES};
use tritri_rtl::octree::list_pass_machine::ListPassConfig;

use crate::scene_query::Accelerator;

/// A run and what it was held to.
pub struct DramBinning {
    pub run: DramBinningRun,
    /// The planner's tree for the same rule.
    pub schedule: OctreeSchedule,
    /// Bytes of the two root lists (what the host writes).
    pub root_bytes: u64,
}

/// Bins `scene` (prepared for `accelerator`) with its lists in a memory of
/// `params`, the arena `arena_bytes` long. When no cell found the arena
/// full, an error unless the leaves are the planner's.
pub fn bin_in_dram(
    accelerator: &Accelerator,
    scene: &PreparedScene,
    pass: ListPassConfig,
    params: MemoryParams,
    arena_bytes: u64,
) -> anyhow::Result<DramBinning> {
    let root_box = scene
        .integer_box
        .context("the objects' boxes do not meet: nothing to bin")?;
    let depth = accelerator.depth as usize;
    if !depth.is_power_of_two() || !accelerator.pipelines.is_power_of_two() {
        bail!(
            "the split rule in hardware needs a power-of-two depth and pipeline count, not {} and {}",
            depth,
            accelerator.pipelines
        );
    }
    let local_frames = accelerator.local_frames();
    let rule = DramSplitRule {
        system: accelerator.system_config(),
        pass,
    };
    let schedule = schedule(
        &scene.kept_a,
        &scene.kept_b,
        &root_box,
        depth,
        &rule,
        local_frames,
    );
    let root = schedule.root.context("the schedule has no root")?;
    // The triangles the planner bins (the others go to the host).
    let binned = |list: &[TaggedTriangle]| -> Vec<[u8; ENTRY_BYTES]> {
        list.iter()
            .filter(|t| local_frames.is_none_or(|l| l.fits_any_leaf(t)))
            .map(|t| pack(t.id, &t.triangle, pass.grid_bits))
            .collect()
    };
    let lists = [binned(&scene.kept_a), binned(&scene.kept_b)];
    let burst = pass.burst_bytes();
    let round_up = |n: u64| n.div_ceil(burst) * burst;
    let b_at = round_up((lists[0].len() * ENTRY_BYTES) as u64);
    let arena_start = round_up(b_at + (lists[1].len() * ENTRY_BYTES) as u64);
    let arena_end = arena_start + round_up(arena_bytes);
    let mut bytes = vec![0u8; arena_end as usize];
    for (at, list) in [0, b_at].into_iter().zip(&lists) {
        for (i, entry) in list.iter().enumerate() {
            let from = at as usize + i * ENTRY_BYTES;
            bytes[from..from + ENTRY_BYTES].copy_from_slice(entry);
        }
    }
    let mut memory = AxiMemory::new(params, bytes);
    let config = DramBinningConfig {
        pass,
        rule: BinningParams {
            log_depth: depth.ilog2(),
            log_pipelines: accelerator.pipelines.ilog2(),
            max_leaf_level: local_frames.map(|l| l.max_leaf_level()),
        },
        arena: (arena_start, arena_end),
    };
    let run = run_dram_binning(
        config,
        &mut memory,
        root,
        [(0, lists[0].len() as u64), (b_at, lists[1].len() as u64)],
    )
    .map_err(anyhow::Error::msg)?;
    if run.arena_full == 0 {
        leaves_are_the_planners(&run, &schedule, pass.grid_bits)?;
    }
    Ok(DramBinning {
        run,
        schedule,
        root_bytes: arena_start,
    })
}

/// An error naming the first leaf that is not the planner's.
fn leaves_are_the_planners(
    run: &DramBinningRun,
    schedule: &OctreeSchedule,
    grid_bits: usize,
) -> anyhow::Result<()> {
    if run.leaves.len() != schedule.leaves.len() {
        bail!(
            "{} leaves, the planner has {}",
            run.leaves.len(),
            schedule.leaves.len()
        );
    }
    for (i, (leaf, planned)) in run.leaves.iter().zip(&schedule.leaves).enumerate() {
        if leaf.cell != planned.cell {
            bail!(
                "leaf {i} is cell {:?}, the planner's {:?}",
                leaf.cell,
                planned.cell
            );
        }
        let (a, b) = schedule.leaf_arrays(planned);
        for (k, expected) in [a, b].into_iter().enumerate() {
            let got: Vec<u32> = leaf.entries[k]
                .iter()
                .map(|e| unpack(e, grid_bits).0)
                .collect();
            let want: Vec<u32> = expected.iter().map(|t| t.id).collect();
            if got != want {
                bail!(
                    "leaf {i} ({:?}): object {k}'s list is {} triangles, not the planner's {}",
                    leaf.cell,
                    got.len(),
                    want.len()
                );
            }
        }
    }
    Ok(())
}
