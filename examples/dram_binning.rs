//! The broad phase's binning with its lists in external memory, beside the
//! on-chip binning unit, on a scene of your own: the octree walked by the
//! controller's clock-exact model (`tritri_cosim::dram_binning::bin_in_dram`),
//! a pass per cell split, each pass the list pass unit's clock-exact model
//! against the AXI4 memory model, which its Verilog equals in
//! co-simulation (crates/tritri-cosim/tests/list_pass.rs).
//!
//! ```sh
//! cargo run --release --example dram_binning [-- A B [SCALE_B TX TY TZ]]
//! ```
//!
//! A and B are mesh files (.obj, .ply, .off), Bezier patches (.bpt) or the
//! built-ins `@torus` and `@sphere` (the default); B is scaled by SCALE_B
//! and moved by (TX, TY, TZ). The accelerator is `Accelerator::new(24)`:
//! a 24-bit grid, two pipelines, 256 triangles per array. Every figure is
//! in clocks of the unit's port, with the memory's bandwidth in bytes per
//! clock beside it; no clock frequency is assumed.
//!
//! Then the controller itself (`tritri_rtl::broad_phase::dram_binning_unit`)
//! runs on the same scene, 64-bit port, in rust-hdl and, emitted, in
//! Verilator against `axi_memory.sv`, with an ideal memory and with one
//! that stalls 20 % of clocks; each must equal the clock-exact model in
//! every leaf, clock and byte of the memory, or the example fails.

use anyhow::Context as _;
use tritri_cosim::binning_unit::bin_scene;
use tritri_cosim::dram_binning::{bin_in_dram, dram_case, run_model, run_rusthdl, run_simulator};
use tritri_cosim::scene_query::Accelerator;
use tritri_cosim::simulator::Simulator;
use tritri_geom::scene::octree::OctreeSchedule;
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::broad_phase::leaf_cost::leaf_cost;
use tritri_rtl::broad_phase::list_pass_machine::ListPassConfig;

/// The collision system's clocks on the leaves of `schedule`, as the
/// split rule counts them.
fn narrow_phase(schedule: &OctreeSchedule, accelerator: &Accelerator) -> u64 {
    let (log_depth, log_pipelines) = (accelerator.depth.ilog2(), accelerator.pipelines.ilog2());
    schedule
        .leaves
        .iter()
        .map(|l| leaf_cost(l.a.len() as u64, l.b.len() as u64, log_depth, log_pipelines))
        .sum()
}

/// The memory the children's lists may take.
const ARENA_BYTES: u64 = 256 << 20;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (a, b) = tritri_examples::scene_objects(&args, "dram_binning")?;

    let accelerator = Accelerator::new(24);
    let scene = accelerator.prepare(&a, &b)?;
    let schedule = scene
        .octree
        .as_ref()
        .filter(|o| o.root.is_some() && !o.leaves.is_empty())
        .context("the objects' boxes do not meet: nothing to bin")?;
    let on_chip = bin_scene(
        &scene,
        accelerator.grid_bits as usize,
        accelerator.depth as usize,
        accelerator.pipelines as usize,
        None,
    )
    .map_err(|e| anyhow::anyhow!("the on-chip binning unit: {e}"))?;
    println!(
        "{} x {} triangles, {} + {} in the common box; the planner: {} leaves, depth {}, {} cells classified",
        a.triangles.len(),
        b.triangles.len(),
        scene.kept_a.len(),
        scene.kept_b.len(),
        schedule.leaves.len(),
        schedule.tree_depth,
        schedule.cells_visited
    );
    println!(
        "on-chip binning unit (scene in block RAM): {} clocks",
        on_chip.run.cycles
    );
    println!();
    println!(
        "| port | memory | passes | leaves | first leaf out | read | written (to one-object children) | arena | clocks | of them in passes | / on-chip |"
    );
    println!("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for data_bits in [64, 128, 256] {
        let beat = data_bits as u64 / 8;
        let memories = [
            (
                format!("ideal: 2 beats a clock, {} clocks latency", 24),
                MemoryParams::ideal(beat, 24),
            ),
            (
                "16 B a clock shared, 40 clocks latency".to_string(),
                MemoryParams {
                    bytes_per_clock: (16, 1),
                    write_latency: 40,
                    ..MemoryParams::ideal(beat, 40)
                },
            ),
        ];
        for (name, params) in memories {
            let config = ListPassConfig {
                grid_bits: accelerator.grid_bits as usize,
                data_bits,
                max_read_burst: 16,
                outstanding: 4,
            };
            let got = bin_in_dram(&accelerator, &scene, config, params, ARENA_BYTES)?;
            let run = &got.run;
            if data_bits == 64 && name.starts_with("ideal") {
                println!(
                    "the streaming split rule: {} leaves, narrow phase {} clocks; the planner's: {} leaves, {} clocks",
                    got.schedule.leaves.len(),
                    narrow_phase(&got.schedule, &accelerator),
                    schedule.leaves.len(),
                    narrow_phase(schedule, &accelerator)
                );
            }
            if run.arena_full > 0 {
                println!(
                    "({} cells found the {} MiB arena full and stayed leaves)",
                    run.arena_full,
                    ARENA_BYTES >> 20
                );
            }
            println!(
                "| {data_bits} bits | {name} | {} | {} | clock {} | {} KiB | {} KiB ({} KiB) | {} KiB | {} | {} | {:.2} |",
                run.passes,
                run.leaves.len(),
                run.leaves.first().map_or(0, |l| l.clock),
                run.bytes_read / 1024,
                run.bytes_written / 1024,
                run.bytes_dropped / 1024,
                run.peak_arena / 1024,
                run.cycles,
                run.pass_cycles,
                run.cycles as f64 / on_chip.run.cycles as f64
            );
        }
    }
    cosimulate(&accelerator, &scene)
}

/// The controller in rust-hdl and in Verilator against its model, on a
/// 64-bit port with an arena as large as the model's walk needs.
fn cosimulate(
    accelerator: &Accelerator,
    scene: &tritri_geom::scene::PreparedScene,
) -> anyhow::Result<()> {
    let config = ListPassConfig {
        grid_bits: accelerator.grid_bits as usize,
        data_bits: 64,
        max_read_burst: 16,
        outstanding: 4,
    };
    let ideal = MemoryParams::ideal(8, 24);
    println!();
    println!("| the controller, 64-bit port | passes | leaves | clocks | stalled | leaves waiting at most / dropped / sent together | model = rust-hdl = Verilator | rust-hdl | Verilator |");
    println!("|---|---:|---:|---:|---:|---:|---|---:|---:|");
    for (name, params) in [
        ("ideal, latency 24", ideal),
        ("20 % of clocks stalled (seed 7)", ideal.with_stalls(20, 7)),
    ] {
        let (wide, _) = dram_case(accelerator, scene, config, params, ARENA_BYTES)?;
        let (first, _) = run_model(&wide)?;
        // The same walk in an arena just large enough for it.
        let (case, _) = dram_case(accelerator, scene, config, params, first.peak_arena.max(1))?;
        let (model, bytes) = run_model(&case)?;
        anyhow::ensure!(
            model.leaves.len() == first.leaves.len() && model.cycles == first.cycles,
            "the walk changed with the arena cut to its peak"
        );
        let limit = 2 * model.cycles + 1000;
        let started = std::time::Instant::now();
        let rust_hdl = run_rusthdl(&case, limit)?;
        let rust_hdl_time = started.elapsed();
        rust_hdl
            .check_against(&model, &bytes)
            .context("rust-hdl against the model")?;
        let started = std::time::Instant::now();
        let verilator = run_simulator(Simulator::Verilator, &case, limit)?;
        let verilator_time = started.elapsed();
        verilator
            .check_against(&model, &bytes)
            .context("Verilator against the model")?;
        // Leaves sent from the waiting memory go out a clock apart.
        let together = model
            .leaves
            .windows(2)
            .filter(|w| w[1].clock == w[0].clock + 1)
            .count();
        println!(
            "| {name} | {} | {} | {} | {} | {} / {} / {together} | yes | {:.1} s | {:.1} s |",
            model.passes,
            model.leaves.len(),
            model.cycles,
            model.stalled,
            model.peak_waiting,
            model.leaves_dropped,
            rust_hdl_time.as_secs_f64(),
            verilator_time.as_secs_f64()
        );
    }
    Ok(())
}
