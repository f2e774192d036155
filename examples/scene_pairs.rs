//! Two objects through the octree broad phase and the collision system:
//! the pairs from the bit-exact model, then from the rust-hdl simulation
//! of the system's hardware, which must agree pair for pair and with the
//! system's cycle model. Both runs go through `tritri_cosim::engine`, the
//! route `tritri sim` takes (`--engine icarus` or `verilator` are one
//! word away).
//!
//! ```sh
//! cargo run --release --example scene_pairs [-- A B]
//! ```
//!
//! A and B are mesh files (.obj, .ply, .off), Bezier patches (.bpt) or the
//! built-ins `@torus` and `@sphere` (the default). The program fails if
//! the hardware's pairs or cycles differ from the models'.

use tritri_cosim::engine::{check_quantized, run_scene, Engine};
use tritri_geom::scene::load::load_object;
use tritri_geom::scene::{prepare_octree, SceneOptions};
use tritri_rtl::pipeline::triangle_pipeline::latency;
use tritri_rtl::system::SystemConfig;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (a, b) = match args.as_slice() {
        [a, b] => (a.as_str(), b.as_str()),
        [] => ("@torus", "@sphere"),
        _ => anyhow::bail!("usage: scene_pairs [A B]"),
    };
    // Bezier patches are tessellated into 2 * 8^2 triangles each.
    let (a, b) = (load_object(a, 8)?, load_object(b, 8)?);

    // The hardware: 24-bit coordinates, 2 pipelines, 256 triangles per array.
    let config = SystemConfig::new(24, 2, latency()).with_depth(256);
    let options = SceneOptions {
        width: 24,
        depth: 256,
        split: true,
    };
    // The octree broad phase, its splits costed by the system's cycle model.
    let scene = prepare_octree(&a, &b, &options, &config, None)?;
    let model = run_scene(Engine::Model, &scene, config, &|_| {})?;
    println!(
        "{} x {} triangles: {} batches, {} pairs tested, {} intersect (bit-exact model), {} cycles (cycle model)",
        a.triangles.len(),
        b.triangles.len(),
        scene.batches().len(),
        scene.pairs_tested(),
        model.pairs.len(),
        model.cycles
    );

    // The same scene through the rust-hdl simulation of the system.
    let hardware = run_scene(Engine::Rusthdl, &scene, config, &|_| {})?;
    println!(
        "rust-hdl: {} pairs in {} cycles",
        hardware.pairs.len(),
        hardware.cycles
    );
    for (i, j) in hardware.pairs.iter().take(5) {
        println!("  A's triangle {i} meets B's triangle {j}");
    }
    anyhow::ensure!(
        hardware.pairs == model.pairs,
        "the hardware's pairs differ from the model's"
    );
    anyhow::ensure!(
        hardware.faults().is_empty(),
        "the hardware: {}",
        hardware.faults().join("; ")
    );
    // An exact model on the same integer coordinates must agree too.
    let (_, diff) = check_quantized(&scene, &hardware.pairs);
    anyhow::ensure!(
        diff.is_empty(),
        "the hardware differs from the exact model: {diff:?}"
    );
    println!("the hardware agrees with the models, pair for pair and cycle for cycle");
    Ok(())
}
