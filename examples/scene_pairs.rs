//! Two objects through the octree broad phase and the collision system:
//! the pairs from the bit-exact model, then from the rust-hdl simulation
//! of the system's hardware, which must agree pair for pair and with the
//! system's cycle model.
//!
//! ```sh
//! cargo run --release --example scene_pairs [-- A B]
//! ```
//!
//! A and B are mesh files (.obj, .ply, .off), Bezier patches (.bpt) or the
//! built-ins `@torus` and `@sphere` (the default). The program fails if
//! the hardware's pairs or cycles differ from the models'.

use tritri_cosim::system_harness::{run_system, Batch as HardwareBatch, ReaderBehaviour};
use tritri_cosim::stream::IdTriangle;
use tritri_geom::scene::load::load_object;
use tritri_geom::scene::reference::{fixed_point_pairs, PairSet};
use tritri_geom::scene::{prepare_octree, SceneOptions};
use tritri_rtl::pipeline::triangle_pipeline::latency;
use tritri_rtl::system::cycle_model::{system_cycles, BatchSizes};
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
    let options = SceneOptions { width: 24, depth: 256, split: true };
    // The octree broad phase, its splits costed by the system's cycle model.
    let scene = prepare_octree(&a, &b, &options, &config, None)?;
    let batches = scene.batches();
    let model = fixed_point_pairs(&batches, &|_| {});
    println!("{} x {} triangles: {} leaves, {} pairs tested, {} intersect (bit-exact model)", a.triangles.len(), b.triangles.len(), batches.len(), scene.pairs_tested(), model.len());

    // The same batches through the rust-hdl simulation of the system.
    let hardware_batches: Vec<HardwareBatch> = batches
        .iter()
        .map(|batch| {
            let ids = |ts: &[tritri_geom::scene::TaggedTriangle]| ts.iter().map(|t| IdTriangle { id: t.id, triangle: t.triangle }).collect();
            HardwareBatch { a: ids(batch.a), b: ids(batch.b) }
        })
        .collect();
    let result = run_system(config, &hardware_batches, ReaderBehaviour::AlwaysReady)?;
    // A pair shared by several leaves comes once per leaf; the set keeps one.
    let hardware: PairSet = result.pairs.iter().copied().collect();
    let sizes: Vec<BatchSizes> = batches.iter().map(|b| BatchSizes { a: b.a.len(), b: b.b.len() }).collect();
    let model_cycles = system_cycles(config, &sizes, true, ReaderBehaviour::AlwaysReady);
    println!("rust-hdl: {} pairs in {} cycles (cycle model {model_cycles})", hardware.len(), result.cycles);
    for (i, j) in hardware.iter().take(5) {
        println!("  A's triangle {i} meets B's triangle {j}");
    }
    anyhow::ensure!(hardware == model, "the hardware's pairs differ from the model's");
    anyhow::ensure!(result.cycles == model_cycles, "the hardware took {} cycles, the cycle model says {model_cycles}", result.cycles);
    println!("the hardware agrees with the model, pair for pair and cycle for cycle");
    Ok(())
}
