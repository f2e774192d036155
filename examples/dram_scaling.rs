//! How the broad-phase accelerator with its scene in DRAM grows with the
//! scene: two meshes cut by their edge midpoints (each triangle into
//! 4^K, the same surfaces), run in the top's clock-exact model
//! (`broad_phase::dram_broad_phase_machine`, which the co-simulations
//! hold equal to Verilator on real scenes: docs/axi-port.md) on the
//! 256-bit port of the design that fits the ECP5-85, with the memory
//! model at a beat each way a clock, latency 24. Each row gives the
//! triangles in the common box, the walk, the DRAM bytes, the clocks to
//! the last verdict and the port's bound; where rtl-out/measurements.json
//! has the top's post-route clock, the time at that clock with the
//! ECP5-5G Versa's 1.6 GB/s, beside the project's software path (box
//! sweep and exact predicates, one thread, triangles in memory).
//!
//! ```sh
//! bash scripts/fetch-meshes.sh
//! cargo run --release --example dram_scaling -- [--levels KA:KB,...] \
//!     build/meshes/camel.off build/meshes/elephant.off 1 0.3 0 0
//! ```
//!
//! It fails if a row takes more clocks per triangle in the common box
//! than an earlier row by a tenth (the run must grow with those
//! triangles, no faster).
//!
//! - `--levels` lists the cuts of A and of B, row by row (default
//!   `0:0,1:1,2:2,3:4`: camel × elephant at 1, 4 and 16 times its
//!   triangles, and 1.25 M × 1.42 M).
//! - `--data-bits` sets the port (64, 128 or 256 bits; the pass takes an
//!   entry every 256 / bits clocks), `--bytes-per-clock` the memory's
//!   bandwidth in all (default: a beat each way a clock), so that a user
//!   reads their own port and memory.
//!
//! Scenes larger than the routed design's owner filter tables (8,192
//! triangles and entries per object) run in a top whose tables fit them;
//! the model's clocks do not depend on the tables' size, only on the
//! triangles in the common box (their heads are cleared one a clock).

use anyhow::Context as _;
use tritri_cosim::dram_binning::run_model;
use tritri_cosim::dram_broad_phase::{run_top_model, top_case};
use tritri_cosim::scene_query::Accelerator;
use tritri_examples::{take_data_bits, take_option, VERSA_GBYTES};
use tritri_geom::scene::reference::exact_f64_pairs;
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::broad_phase::list_pass_machine::ListPassConfig;
use tritri_rtl::measured::Measurements;
use tritri_rtl::pipeline::RareCasePath;

/// The unit whose post-route clock times the rows.
const ROUTED_UNIT: &str = "tritri_dram_broad_phase_g16_w16_d256_p1_t256_i8192_s8192_shared";

fn main() -> anyhow::Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let levels = match take_option(&mut args, "--levels", "KA:KB[,KA:KB...]")? {
        Some(list) => parse_levels(&list)?,
        None => vec![(0, 0), (1, 1), (2, 2), (3, 4)],
    };
    let data_bits = take_data_bits(&mut args, 256)?;
    let bytes_per_clock =
        match take_option(&mut args, "--bytes-per-clock", "a whole number of bytes")? {
            Some(b) => {
                let b: u64 = b.parse().ok().filter(|&b| b >= 1).with_context(|| {
                    format!(
                        "--bytes-per-clock takes a whole number of bytes, at least 1, not {b:?}"
                    )
                })?;
                Some(b)
            }
            None => None,
        };
    let (a, b) = tritri_examples::scene_objects(
        &args,
        "dram_scaling [--levels KA:KB,...] [--data-bits 64|128|256] [--bytes-per-clock B]",
    )?;
    // The routed design is the 256-bit one.
    let routed = Measurements::committed()
        .ecp5(ROUTED_UNIT)
        .map(|row| row.fmax_mhz)
        .filter(|_| data_bits == 256);
    let mut accelerator = Accelerator::new(16);
    accelerator.pipelines = 1;
    accelerator.rare_cases = RareCasePath::Shared;
    let pass = ListPassConfig {
        grid_bits: 16,
        data_bits,
        max_read_burst: 16,
        outstanding: 4,
    };
    let mut ideal = MemoryParams::ideal(data_bits as u64 / 8, 24);
    if let Some(bytes) = bytes_per_clock {
        ideal.bytes_per_clock = (bytes, 1);
    }
    println!(
        "{data_bits}-bit port; the memory moves {} bytes a clock in all, latency 24",
        ideal.bytes_per_clock.0
    );
    println!("| K (A, B) | N1 × N2 | in the common box | leaves | passes | DRAM read / written | peak arena | clocks to the last verdict | × the port's bound | at {VERSA_GBYTES} GB/s: clocks | time at the routed clock | software | model's run |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    // Clocks per triangle in the common box, row by row.
    let mut per_triangle: Vec<(String, f64)> = Vec::new();
    for (ka, kb) in levels {
        let (a, b) = (a.subdivided(ka), b.subdivided(kb));
        // The project's software path, one thread, triangles in memory.
        let started = std::time::Instant::now();
        let software = exact_f64_pairs(&a.triangles, &b.triangles);
        let software_time = started.elapsed().as_secs_f64();
        let started = std::time::Instant::now();
        let scene = accelerator.prepare(&a, &b)?;
        let kept = scene.kept_a.len() + scene.kept_b.len();
        // The arena: what the walk takes, found with room to spare first.
        let room = (kept as u64 * 32 * 32).max(1 << 20);
        let (wide, _) = top_case(&accelerator, &scene, pass, ideal, room)?;
        let (walk, _) = run_model(&wide.binning)?;
        anyhow::ensure!(
            walk.arena_full == 0,
            "K = {ka}, {kb}: {} cells found an arena of {room} bytes full",
            walk.arena_full
        );
        let run = run_top_model(&wide, u64::MAX)?;
        let (read, written) = (
            run.beats_read * ideal.beat_bytes,
            run.beats_written * ideal.beat_bytes,
        );
        // A beat a clock each way, and the memory's bytes a clock in all.
        let bound = run
            .beats_read
            .max(run.beats_written)
            .max((read + written).div_ceil(ideal.bytes_per_clock.0));
        let (versa, time) = match routed {
            Some(mhz) => {
                let mut case = wide.clone();
                case.binning.params = ideal.at_bandwidth(VERSA_GBYTES, mhz);
                let versa = run_top_model(&case, u64::MAX)?;
                let seconds = versa.tested_at as f64 / (mhz * 1e6);
                (
                    versa.tested_at.to_string(),
                    format!(
                        "{:.3} ms at {mhz:.1} MHz, {:.1} × the software",
                        seconds * 1e3,
                        software_time / seconds
                    ),
                )
            }
            None => ("-".into(), "not routed".into()),
        };
        per_triangle.push((
            format!("{ka}, {kb}"),
            run.tested_at as f64 / kept.max(1) as f64,
        ));
        println!(
            "| {ka}, {kb} | {} × {} | {} + {} | {} | {} | {:.1} / {:.1} MiB | {:.1} MiB | {} | {:.2} | {versa} | {time} | {} pairs in {:.1} ms | {:.1} s |",
            a.triangles.len(),
            b.triangles.len(),
            scene.kept_a.len(),
            scene.kept_b.len(),
            run.leaves,
            run.passes,
            read as f64 / (1 << 20) as f64,
            written as f64 / (1 << 20) as f64,
            walk.peak_arena as f64 / (1 << 20) as f64,
            run.tested_at,
            run.tested_at as f64 / bound.max(1) as f64,
            software.pairs.len(),
            software_time * 1e3,
            started.elapsed().as_secs_f64()
        );
    }
    // The run grows with the triangles in the common box, no faster: no
    // row's clocks per triangle there exceed an earlier row's by a tenth.
    for (i, (row, clocks)) in per_triangle.iter().enumerate() {
        for (earlier, before) in &per_triangle[..i] {
            anyhow::ensure!(
                *clocks <= before * 1.1,
                "K = {row}: {clocks:.2} clocks per triangle in the common box, where K = {earlier} took {before:.2}"
            );
        }
    }
    if routed.is_none() {
        println!("no post-route clock for this port in rtl-out/measurements.json ({ROUTED_UNIT} is the 256-bit design): clocks only");
    }
    Ok(())
}

/// `0:0,1:1`: the cuts of A and B, row by row.
fn parse_levels(list: &str) -> anyhow::Result<Vec<(u32, u32)>> {
    list.split(',')
        .map(|pair| {
            let (ka, kb) = pair
                .split_once(':')
                .with_context(|| format!("--levels: {pair:?} is not KA:KB"))?;
            let level = |k: &str| -> anyhow::Result<u32> {
                let k: u32 = k
                    .parse()
                    .with_context(|| format!("--levels: {k:?} is not a whole number"))?;
                // 4^5 = 1,024 times the triangles: beyond that, memory runs out
                // before the model does.
                anyhow::ensure!(k <= 5, "--levels: {k} cuts (at most 5)");
                Ok(k)
            };
            Ok((level(ka)?, level(kb)?))
        })
        .collect()
}
