//! The broad phase's binning with every list in external memory, pass by
//! pass in the list pass unit's clock-exact model: the lists that reach the
//! leaves are the planner's, every entry is read once per split cell and
//! written once per child it meets, and the clocks stay within the beats
//! the passes move.

use tritri_cosim::dram_binning::walk;
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::{prepare_octree, SceneOptions};
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::octree::list_pass_machine::ListPassConfig;
use tritri_rtl::system::SystemConfig;

#[test]
fn the_lists_that_reach_the_leaves_are_the_planners() {
    let a = SceneObject::from_triangles("torus", torus([0.0, 0.0, 0.0], 1.0, 0.35, 48, 24));
    let b = SceneObject::from_triangles("sphere", sphere([1.0, 0.0, 0.55], 0.4, 32, 16));
    let depth = 32;
    let options = SceneOptions {
        grid_bits: 24,
        depth,
        split: true,
    };
    let config = SystemConfig::new(24, 2).with_depth(depth);
    let prepared = prepare_octree(&a, &b, &options, &config, None).unwrap();
    let schedule = prepared.octree.as_ref().unwrap();
    assert!(
        schedule.tree_depth >= 2,
        "a tree of depth {}",
        schedule.tree_depth
    );
    for data_bits in [64, 256] {
        let pass = ListPassConfig {
            grid_bits: 24,
            data_bits,
            max_read_burst: 16,
            outstanding: 4,
        };
        let run = walk(
            schedule,
            [&prepared.kept_a, &prepared.kept_b],
            pass,
            MemoryParams::ideal(data_bits as u64 / 8, 24),
        )
        .unwrap();
        assert_eq!(run.leaves, schedule.leaves.len() as u64);
        assert!(run.passes >= schedule.tree_depth as u64);
        // The planner also classifies the subtrees it tries and gives up.
        assert!(run.passes <= schedule.cells_visited, "{run:?}");
        let beat = data_bits as u64 / 8;
        let (read, written) = (run.bytes_read / beat, run.bytes_written / beat);
        // Reads and writes go on their own channels: at least the larger,
        // at most both and a pass's latencies.
        assert!(run.cycles >= read.max(written), "{run:?}");
        assert!(run.cycles <= read + written + 300 * run.passes, "{run:?}");
        eprintln!(
            "{data_bits}-bit port: {} passes (the planner classified {} cells), {} leaves, {} clocks; {} KiB read, {} KiB written \
             ({} beats / {} clocks)",
            run.passes,
            schedule.cells_visited,
            run.leaves,
            run.cycles,
            run.bytes_read / 1024,
            run.bytes_written / 1024,
            read + written,
            run.cycles
        );
    }
}
