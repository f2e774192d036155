//! Two objects to their exact intersecting pairs with one library call,
//! `tritri_cosim::scene_query::find_pairs`, the route `tritri sim` takes:
//! the host's preparation, the octree broad phase and the collision system
//! on an engine, the verdicts without a certificate decided again on the
//! original coordinates, and the time from the first triangle in to the
//! last exact pair out. It runs on the bit-exact model, then on the rust-hdl
//! simulation of the hardware, which must give the same pairs and the
//! cycle model's cycles (`Engine::Icarus` or `Engine::Verilator` are one
//! word away).
//!
//! ```sh
//! cargo run --release --example scene_pairs [-- A B]
//! ```
//!
//! A and B are mesh files (.obj, .ply, .off), Bezier patches (.bpt) or the
//! built-ins `@torus` and `@sphere` (the default). The program fails if
//! the answer differs from exact f64 on the originals, or the hardware
//! from the model.

use tritri_cosim::engine::Engine;
use tritri_cosim::scene_query::{find_pairs, Accelerator, QueryOptions};
use tritri_geom::scene::load::load_object;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (a, b) = match args.as_slice() {
        [a, b] => (a.as_str(), b.as_str()),
        [] => ("@torus", "@sphere"),
        _ => anyhow::bail!("usage: scene_pairs [A B]"),
    };
    // Bezier patches are tessellated into 2 * 8^2 triangles each.
    let (a, b) = (load_object(a, 8)?, load_object(b, 8)?);

    // The hardware: 24-bit coordinates, 2 pipelines, 256 triangles per
    // array, the octree broad phase, at the thesis's (assumed) 100 MHz.
    let accelerator = Accelerator::new(24);
    let model = find_pairs(&a, &b, &accelerator, &QueryOptions::default())?;
    anyhow::ensure!(model.faults.is_empty(), "faults: {:?}", model.faults);
    let check = model.check.as_ref().expect("checked by default");
    let hardware = model.hardware.as_ref().expect("the boxes meet");
    let time = model.end_to_end().expect("the boxes meet");
    println!(
        "{} x {} triangles: {} exact pairs ({} on the grid, {} uncertain verdicts decided again, {} changed); exact f64 on the originals: {}",
        a.triangles.len(),
        b.triangles.len(),
        model.pairs.len(),
        hardware.run.pairs.len(),
        hardware.run.uncertain.len(),
        hardware.redecided.changed,
        check.truth.pairs.len()
    );
    println!(
        "end to end {:?}: host {:?} + accelerator {} cycles = {:?} at {} MHz ({}) + re-decisions {:?}; software {:?}",
        time.total(),
        time.host,
        time.cycles,
        time.accelerator,
        accelerator.clock.mhz,
        accelerator.clock.source.name(),
        time.redecide,
        check.software
    );
    anyhow::ensure!(
        model.pairs == check.truth.pairs,
        "the exact answer differs from exact f64 on the originals"
    );

    // The same scene through the rust-hdl simulation of the system.
    let options = QueryOptions {
        engine: Engine::Rusthdl,
        ..QueryOptions::default()
    };
    let simulated = find_pairs(&a, &b, &accelerator, &options)?;
    let run = &simulated.hardware.as_ref().expect("the boxes meet").run;
    println!(
        "rust-hdl: {} exact pairs, the system in {} cycles (cycle model {})",
        simulated.pairs.len(),
        run.cycles,
        run.model_cycles
    );
    for (i, j) in simulated.pairs.iter().take(5) {
        println!("  A's triangle {i} meets B's triangle {j}");
    }
    // A fault names what differed: the grid against the exact model on the
    // same integer coordinates, the cycles against the cycle model.
    anyhow::ensure!(
        simulated.faults.is_empty(),
        "the hardware: {:?}",
        simulated.faults
    );
    anyhow::ensure!(
        simulated.pairs == model.pairs,
        "the hardware's pairs differ from the model's"
    );
    println!("the hardware agrees with the models, pair for pair and cycle for cycle");
    Ok(())
}
