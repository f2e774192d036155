//! The broad-phase accelerator with its scene in DRAM on a scene of your
//! own: the design `tritri gen --dram-broad-phase --width 16 --pipelines 1
//! --rare-cases shared --triangles 8192 --slots 8192 [--data-bits 128|256]`
//! writes (the one that fits the ECP5-85; the 256-bit top routes at 52.9
//! MHz, docs/axi-port.md), on a 64-, 128- or 256-bit port, emitted and run
//! in Verilator against the AXI4 memory model
//! `axi_memory.sv`, with an ideal memory and with one that stalls 20 % of
//! clocks, beside its clock-exact model.
//!
//! ```sh
//! cargo run --release --example dram_broad_phase [-- [--data-bits 64|128|256] A B [SCALE_B TX TY TZ]]
//! TRITRI_RUSTHDL=1 cargo run --release --example dram_broad_phase   # rust-hdl too
//! cargo run --release --example dram_broad_phase -- --write-case DIR [A B ...]
//! ```
//!
//! `--write-case DIR` writes the ideal memory's case for another testbench
//! instead (examples/dram-broad-phase and examples/fpga-top, cocotb against
//! cocotbext-axi's AxiRam): the emitted top in `DIR/rtl`, the memory as the
//! host leaves it in `DIR/memory.bin`, and in `DIR/case.txt` the top's
//! inputs (a name and a number a line), each list's triangle numbers
//! (`ids_0`, `ids_1`), the pairs the top must stream (`pair A B`,
//! `uncertain A B V` with V the host's verdict when it decides the pair
//! again on the f64 meshes, as the meshes number their triangles) with the
//! clock of `done` in Verilator, and the exact answer on the f64 meshes
//! (`exact A B`).
//!
//! A and B are as `examples/dram_binning.rs` takes them (default: the
//! built-in torus and sphere). The host's part is what the top expects:
//! the common box quantized onto the 16-bit grid, each object's kept
//! triangles written as a root list into the memory. The example fails
//! unless the pairs the top streams are the exact answer on the grid
//! (every kept pair that intersects, and every pair its leaves hold whose
//! verdict has no certificate), each once, with both memories; unless the
//! model's walk is Verilator's; unless the certain hits with the uncertain
//! pairs decided again on the f64 meshes are the software's exact answer
//! (timed beside it); with TRITRI_RUSTHDL=1, unless rust-hdl's run equals
//! Verilator's clock for clock. Every figure is in clocks of the port, the
//! memory's bandwidth in bytes per clock; a time is given only at a
//! post-route clock from rtl-out/measurements.json, with a table over
//! memories of 0.4 to 25.6 GB/s.

use anyhow::Context as _;
use std::collections::BTreeSet;
use tritri_cosim::dram_broad_phase::{
    exact_on_grid, once_and_exact, run_top_model, run_top_rusthdl, run_top_simulator,
    uncertain_in_leaves, TopCase, TopRun,
};
use tritri_cosim::dram_query::{device_case, host_root_lists, DramAccelerator};
use tritri_cosim::scene_query::ClockSource;
use tritri_cosim::simulator::Simulator;
use tritri_examples::{median_time, take_data_bits, take_option, VERSA_GBYTES, VERSA_LINK_GBYTES};
use tritri_geom::certificate::decide_again;
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::reference::{exact_f64_pairs, exact_f64_pairs_threads};
use tritri_geom::scene::{prepare, SceneOptions};
use tritri_rtl::axi::memory_model::MemoryParams;
use tritri_rtl::broad_phase::list_entry::ENTRY_BYTES;
use tritri_rtl::emit::dram_broad_phase_unit::emit_dram_broad_phase;
use tritri_rtl::emit::dsp_mapping::MultiplierMapping;

fn main() -> anyhow::Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let write_case =
        take_option(&mut args, "--write-case", "a directory")?.map(std::path::PathBuf::from);
    let data_bits = take_data_bits(&mut args, 64)?;
    let with_rusthdl = std::env::var_os("TRITRI_RUSTHDL").is_some_and(|v| v == "1");
    let (a, b) = tritri_examples::scene_objects(
        &args,
        "dram_broad_phase [--data-bits 64|128|256] [--write-case DIR]",
    )?;

    let dram = DramAccelerator::with_port(data_bits);
    let scene = prepare(&a, &b, &dram.accelerator().scene_options())?;
    let pairs = exact_on_grid(&scene);
    println!(
        "{} x {} triangles, {} + {} in the common box on a 16-bit grid; the exact answer on the grid: {} pairs",
        a.triangles.len(),
        b.triangles.len(),
        scene.kept_a.len(),
        scene.kept_b.len(),
        pairs.len(),
    );
    let ideal = MemoryParams::ideal(data_bits as u64 / 8, 24);
    if let Some(dir) = write_case {
        let case = device_case(&dram, &scene, ideal)?;
        return write_case_files(&dir, &case, &a, &b);
    }
    println!();
    println!("| memory | pairs = exact, once | without a certificate | leaves | passes | binned at | tested at | done at | model: tested at | stalled | DRAM read | DRAM written | bytes a clock | Verilator | rust-hdl = Verilator |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---|");
    // The post-route clock, where the top was routed: then a memory of
    // the ECP5-5G Versa's 1.6 GB/s at that clock too.
    let mut ideal_case = Some(device_case(&dram, &scene, ideal)?);
    let routed = (dram.clock.source == ClockSource::PostRouteTop).then_some(dram.clock.mhz);
    let mut memories = vec![
        (
            format!(
                "ideal: a {}-byte beat each way a clock, latency 24",
                ideal.beat_bytes
            ),
            ideal,
        ),
        (
            "the same, 20 % of clocks stalled (seed 7)".to_string(),
            ideal.with_stalls(20, 7),
        ),
    ];
    if let Some(mhz) = routed {
        memories.push((
            format!("{VERSA_GBYTES} GB/s at {mhz:.1} MHz, latency 24"),
            ideal.at_bandwidth(VERSA_GBYTES, mhz),
        ));
    }
    let mut runs = Vec::new();
    for (name, params) in memories {
        let case = match ideal_case.take() {
            Some(case) => case,
            None => device_case(&dram, &scene, params)?,
        };
        let uncertain = uncertain_in_leaves(&case)?;
        let started = std::time::Instant::now();
        let verilator = run_top_simulator(Simulator::Verilator, &case, 100_000_000)?;
        let verilator_time = started.elapsed();
        verilator
            .is_exact(&pairs, &uncertain)
            .with_context(|| format!("{name}: Verilator"))?;
        let same = if with_rusthdl {
            let rusthdl = run_top_rusthdl(&case, 100_000_000)?;
            anyhow::ensure!(
                rusthdl == verilator,
                "{name}: rust-hdl's run is not Verilator's"
            );
            "yes"
        } else {
            "(TRITRI_RUSTHDL=1)"
        };
        let model = run_top_model(&case, 100_000_000)?;
        anyhow::ensure!(
            (model.binned_at, model.leaves, model.passes)
                == (verilator.binned_at, verilator.leaves, verilator.passes)
                && model.tested_at <= verilator.tested_at,
            "{name}: the model's walk is not Verilator's, or it tests later"
        );
        // The model has no shared rare-case unit: the clocks it held.
        let model_tested = match verilator.tested_at - model.tested_at {
            0 => format!("{} (= Verilator)", model.tested_at),
            held => format!(
                "{} (Verilator + {held}: shared unit's holds)",
                model.tested_at
            ),
        };
        let beat = params.beat_bytes;
        let (read, written) = (verilator.beats_read * beat, verilator.beats_written * beat);
        println!(
            "| {name} | yes | {} | {} | {} | {} | {} | {} | {model_tested} | {} | {} KiB | {} KiB | {:.2} | {:.1} s | {same} |",
            verilator.uncertain.len(),
            verilator.leaves,
            verilator.passes,
            verilator.binned_at,
            verilator.tested_at,
            verilator.cycles,
            verilator.stalled,
            read / 1024,
            written / 1024,
            (read + written) as f64 / verilator.cycles as f64,
            verilator_time.as_secs_f64()
        );
        runs.push((verilator, case, params));
    }
    // The ideal memory's run, then (past the stalled one) the Versa's.
    let mut runs = runs.into_iter();
    let (run, case, params) = runs.next().expect("the ideal memory ran");
    let at_versa = runs.nth(1).map(|(run, _, _)| run);
    let kept = scene.kept_a.len() + scene.kept_b.len();
    exact_answer_and_speed(&a, &b, kept, &run, &case, &params, routed.zip(at_versa))
}

/// The route's end on the host and the speed against software: the
/// certain hits with the uncertain pairs decided again on the f64 meshes
/// must be the software's exact answer; then the clocks against the
/// memory's bound and, at the routed clock (`routed`: that clock and the
/// run at the Versa's bandwidth), the time against software.
fn exact_answer_and_speed(
    a: &SceneObject,
    b: &SceneObject,
    kept: usize,
    run: &TopRun,
    case: &TopCase,
    memory: &MemoryParams,
    routed: Option<(f64, TopRun)>,
) -> anyhow::Result<()> {
    // The answer once, then its time as the median of five (one figure
    // for every line below).
    let software = exact_f64_pairs(&a.triangles, &b.triangles);
    let software_time = median_time(5, || {
        std::hint::black_box(exact_f64_pairs(&a.triangles, &b.triangles));
    });
    let started = std::time::Instant::now();
    let uncertain: BTreeSet<_> = run.uncertain.iter().copied().collect();
    let mut answer: BTreeSet<(u32, u32)> = run
        .pairs
        .iter()
        .copied()
        .filter(|p| !uncertain.contains(p))
        .collect();
    answer.extend(
        uncertain
            .iter()
            .copied()
            .filter(|&(i, j)| decide_again(&a.triangles[i as usize], &b.triangles[j as usize])),
    );
    let host_time = started.elapsed();
    anyhow::ensure!(
        answer == software.pairs,
        "the exact answer: {} pairs, the software's {} ({} missing, {} extra)",
        answer.len(),
        software.pairs.len(),
        software.pairs.difference(&answer).count(),
        answer.difference(&software.pairs).count()
    );
    println!();
    println!(
        "exact answer on the f64 meshes: {} pairs, equal to the software's (box sweep + exact predicates, one thread, median of five: {:.2} ms); the host decided {} pairs again in {:.1} us",
        answer.len(),
        software_time.as_secs_f64() * 1e3,
        uncertain.len(),
        host_time.as_secs_f64() * 1e6
    );
    // The port moves a beat a clock each way; the memory `bytes_per_clock`
    // in all.
    let beat = memory.beat_bytes as f64;
    let (read, written) = (
        (run.beats_read as f64) * beat,
        (run.beats_written as f64) * beat,
    );
    let (num, den) = memory.bytes_per_clock;
    let bound = (read / beat)
        .max(written / beat)
        .max((read + written) * den as f64 / num as f64);
    println!(
        "memory: {:.0} KiB read, {:.0} KiB written; the port's bound {:.0} clocks; the top {} clocks, {:.2} x the bound",
        read / 1024.0,
        written / 1024.0,
        bound,
        run.cycles,
        run.cycles as f64 / bound
    );
    let software = software_time.as_secs_f64();
    match routed {
        Some((mhz, versa)) => {
            let time = |clocks: u64| clocks as f64 / (mhz * 1e6);
            end_to_end(
                a,
                b,
                case,
                kept,
                run.pairs.len(),
                host_time.as_secs_f64(),
                time(versa.cycles),
                software,
            )?;
            // The ideal memory's bytes a clock at the routed clock.
            let gbytes = num as f64 / den as f64 * mhz * 1e6 / 1e9;
            println!(
                "at the post-route clock on the ECP5-85, {mhz:.1} MHz (rtl-out/measurements.json): with the ECP5-5G Versa's {VERSA_GBYTES} GB/s {} clocks, {:.3} ms, {:.1} x the software; with the ideal memory ({gbytes:.2} GB/s) {:.3} ms, {:.1} x",
                versa.cycles,
                time(versa.cycles) * 1e3,
                software / time(versa.cycles),
                time(run.cycles) * 1e3,
                software / time(run.cycles),
            );
            bandwidth_table(case, mhz, software)?;
        }
        None => println!(
            "{} has no post-route clock in rtl-out/measurements.json",
            case.config.unit_name()
        ),
    }
    Ok(())
}

/// The whole route against the best software, both measured here (medians
/// of five runs): from the f64 meshes on the host to the exact pairs on the
/// host. The host prepares the scene (common box, cull, quantize:
/// `scene::prepare`) and packs `case`'s root lists (`host_root_lists`): all
/// the DRAM top needs. It sends the `kept` triangles' list entries over
/// the Versa's link, the top runs (`accelerator`
/// seconds, at the routed clock with the Versa's memory), the `pairs` come
/// back over the link, and the host decides the uncertain ones again
/// (`redecide` seconds). `one` is the software's time on one thread.
fn end_to_end(
    a: &SceneObject,
    b: &SceneObject,
    case: &TopCase,
    kept: usize,
    pairs: usize,
    redecide: f64,
    accelerator: f64,
    one: f64,
) -> anyhow::Result<()> {
    let options = SceneOptions {
        grid_bits: 16,
        depth: 256,
        split: true,
    };
    let scene = prepare(a, b, &options)?;
    let cases = std::slice::from_ref(case);
    host_root_lists(&scene, cases)?;
    let host = median_time(5, || {
        let scene = prepare(a, b, &options).ok();
        std::hint::black_box(scene.map(|scene| host_root_lists(&scene, cases).ok()));
    })
    .as_secs_f64();
    let link = |bytes: usize| bytes as f64 / (VERSA_LINK_GBYTES * 1e9);
    let (sent, back) = (kept * ENTRY_BYTES, pairs * 8);
    let whole = host + link(sent) + accelerator + link(back) + redecide;
    let two = median_time(5, || {
        std::hint::black_box(exact_f64_pairs_threads(&a.triangles, &b.triangles, 2));
    })
    .as_secs_f64();
    let ms = |s: f64| s * 1e3;
    println!(
        "end to end, f64 meshes to exact pairs on the host: {:.3} ms = host preparation and root lists {:.3} + {} KiB in over the Versa's PCIe Gen 2 x1 ({VERSA_LINK_GBYTES} GB/s) {:.3} + the top {:.3} + {pairs} pairs back {:.3} + uncertain pairs decided again {:.3}",
        ms(whole),
        ms(host),
        sent / 1024,
        ms(link(sent)),
        ms(accelerator),
        ms(link(back)),
        ms(redecide)
    );
    println!(
        "the best software in this run (the exact path, box sweep + exact predicates; CGAL's box_intersection_d is slower, examples/software_baseline): one thread {:.3} ms, the route {:.2} x its speed; two threads {:.3} ms, the route {:.2} x",
        ms(one),
        one / whole,
        ms(two),
        two / whole
    );
    Ok(())
}

/// The top's clocks to its last verdict (its model) and time at the routed
/// clock `mhz`, for memories of 0.4 to 25.6 GB/s (latency 24 clocks); the
/// port moves at most a beat a clock each way. The model has no shared
/// rare-case unit: its clocks leave out that unit's holds, which the
/// Verilator runs above count.
fn bandwidth_table(case: &TopCase, mhz: f64, software: f64) -> anyhow::Result<()> {
    println!();
    println!("| memory (GB/s) | bytes a clock at {mhz:.1} MHz | clocks to the last verdict (model) | time | / software |");
    println!("|---:|---:|---:|---:|---:|");
    for gbytes in [0.4, 0.8, 1.6, 3.2, 6.4, 12.8, 25.6] {
        let mut case = case.clone();
        case.binning.params = case.binning.params.at_bandwidth(gbytes, mhz);
        let model = run_top_model(&case, 1_000_000_000)?;
        let seconds = model.tested_at as f64 / (mhz * 1e6);
        println!(
            "| {gbytes} | {:.2} | {} | {:.3} ms | {:.1} x |",
            gbytes * 1000.0 / mhz.round(),
            model.tested_at,
            seconds * 1e3,
            software / seconds
        );
    }
    Ok(())
}

/// The files of `--write-case` in `dir`, for the scene of `a` and `b`.
fn write_case_files(
    dir: &std::path::Path,
    case: &TopCase,
    a: &SceneObject,
    b: &SceneObject,
) -> anyhow::Result<()> {
    use std::fmt::Write as _;
    let design = emit_dram_broad_phase(&case.config, MultiplierMapping::Inferred)?;
    design
        .write_to(&dir.join("rtl"))
        .with_context(|| format!("writing {}", dir.join("rtl").display()))?;
    let run = run_top_simulator(Simulator::Verilator, case, 100_000_000)?;
    let uncertain = uncertain_in_leaves(case)?;
    once_and_exact(&run.uncertain, &uncertain, "without a certificate")?;
    let binning = &case.binning;
    let mut text = String::new();
    writeln!(text, "unit {}", case.config.unit_name())?;
    for (name, value) in case.inputs() {
        writeln!(text, "{name} {value}")?;
    }
    writeln!(text, "done_at {}", run.cycles)?;
    for (k, ids) in case.ids.iter().enumerate() {
        let ids: Vec<String> = ids.iter().map(u32::to_string).collect();
        writeln!(text, "ids_{k} {}", ids.join(" "))?;
    }
    for (a, b) in &run.pairs {
        writeln!(text, "pair {a} {b}")?;
    }
    // The host's part after the run: each pair without a certificate
    // decided again on the f64 meshes, and the exact answer they give.
    for &(i, j) in &run.uncertain {
        let verdict = decide_again(&a.triangles[i as usize], &b.triangles[j as usize]);
        writeln!(text, "uncertain {i} {j} {}", u8::from(verdict))?;
    }
    for (i, j) in exact_f64_pairs(&a.triangles, &b.triangles).pairs {
        writeln!(text, "exact {i} {j}")?;
    }
    std::fs::write(dir.join("case.txt"), text)
        .with_context(|| format!("writing {}", dir.join("case.txt").display()))?;
    // The arena starts empty: the memory up to it is what the host writes.
    let host = &binning.bytes[..binning.config.arena.0 as usize];
    std::fs::write(dir.join("memory.bin"), host)
        .with_context(|| format!("writing {}", dir.join("memory.bin").display()))?;
    println!(
        "wrote {} in {}: {} pairs, {} without a certificate, done at clock {} in Verilator",
        case.config.unit_name(),
        dir.display(),
        run.pairs.len(),
        run.uncertain.len(),
        run.cycles
    );
    Ok(())
}
