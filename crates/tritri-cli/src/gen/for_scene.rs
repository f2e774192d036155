//! `tritri gen --for-scene A B [--pose-b ...] [--max-uncertain RATE] [--device NAME]`:
//! the system sized for one scene and an error budget, from measured
//! figures, and the reasons written into its README.
//!
//! **Error.** With certificates every answer is exact; what a width costs
//! in accuracy is the share of the pairs tested that goes back to the
//! host: the verdicts without a certificate, plus, with leaves in local
//! frames, the pairs whose triangles do not fit a leaf's window. Each
//! width W, on its own grid and on grids 2, 4 and 8 bits finer (and 24)
//! with the leaves in W-bit local frames (the same multipliers, a finer
//! step), is run in the bit-exact model on the scene;
//! the cheapest that keeps the host's share at or below `--max-uncertain`
//! wins, cheapest meaning fewest multipliers per pipeline on the device,
//! then fewest LUTs. The candidate just below it in cost is the answer to
//! "why not one bit fewer".
//!
//! **Size.** The device (one table, [`tritri_rtl::measured::DEVICES`])
//! bounds the pipelines P by its multipliers and LUTs, from the measured
//! pipeline (`rtl-out/measurements.json`; a width not measured on the
//! device's flow is not chosen). P doubles while the scene's cycles (the
//! cycle model) drop by at least [`MIN_GAIN`] and the next P fits; that is
//! "why not one more pipeline". The memory depth is the power of two from
//! 64 to 1024 with the fewest cycles (the smaller one when within 1 %).
//!
//! **Rare cases.** A width's pipeline is the one measured on the device's
//! flow: on ECP5 the routed one ([`Measurements::ecp5_pipeline`]: W = 16
//! is routed with its rare pairs on the shared unit), on Xilinx the
//! default's. With the shared unit, the cycles include the stall model's
//! bound on the clocks the system holds for the scene's rare pairs, and
//! the system emitted has that pipeline.
//!
//! A candidate is run in the model only where it could be chosen: a width
//! not measured on the device's flow is not, and neither is one whose host
//! pairs alone (local frames) already exceed the budget (its share is then
//! given as a lower bound). The chosen configuration is run once more in
//! the model to measure what the README states.

use crate::scene_input::{HardwareArgs, SceneArgs};
use crate::stdout::out;
use anyhow::Context;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use tritri_cosim::engine::{run_scene, Engine, SceneRunOptions};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::reference::PairSet;
use tritri_geom::scene::PreparedScene;
use tritri_rtl::emit::dsp_mapping::MultiplierMapping;
use tritri_rtl::measured::{Device, Measurements};
use tritri_rtl::pipeline::pipeline_for_width::SUPPORTED_WIDTHS;
use tritri_rtl::pipeline::pipeline_unit::pipeline_unit_name;
use tritri_rtl::pipeline::RareCasePath;
use tritri_rtl::system::cycle_model::scene_cycles;
use tritri_rtl::system::rare_case_model::stall_bound;
use tritri_rtl::system::system_for_width::PipelineKind;
use tritri_rtl::system::system_unit::emit_system_with;

/// Another doubling of P must save at least this share of the cycles.
pub const MIN_GAIN: f64 = 0.10;

/// The grid of the broad-phase top's local frames.
const LOCAL_GRID_BITS: u32 = 24;

/// The grids tried for a W-bit system: W itself, and finer grids with
/// leaves in W-bit local frames (2, 4 and 8 bits finer, and the
/// broad-phase top's 24), up to 32 bits.
fn grids_for(width: u32) -> Vec<u32> {
    let mut grids: Vec<u32> = [width, width + 2, width + 4, width + 8, LOCAL_GRID_BITS]
        .into_iter()
        .filter(|&g| g >= width && g <= 32)
        .collect();
    grids.sort_unstable();
    grids.dedup();
    grids
}

/// Memory depths tried.
const DEPTHS: [u64; 5] = [64, 128, 256, 512, 1024];

/// LUTs of the system's control beside its pipelines (address generator,
/// memories' logic, result FIFO, serializer): `tritri_system_w24_p1_d256`
/// less `tritri_pipeline_w24` in the Xilinx flow, a measured figure.
fn control_luts(m: &Measurements) -> u64 {
    match (
        m.xilinx("tritri_system_w24_p1_d256"),
        m.xilinx("tritri_pipeline_w24"),
    ) {
        (Some(s), Some(p)) => s.lut.saturating_sub(p.lut),
        _ => 0,
    }
}

/// One width on one device: what a pipeline costs there and how much of
/// the scene goes back to the host.
#[derive(Clone, Debug)]
struct Candidate {
    width: u32,
    /// The grid's bits (above `width`: local frames).
    grid_bits: u32,
    /// Where its pipelines test their rare pairs: that of the pipeline
    /// measured on the device's flow ([`Measurements::ecp5_pipeline`] on
    /// ECP5; the default, parallel, on Xilinx).
    rare_cases: RareCasePath,
    /// Multipliers and LUTs of one pipeline on the device's flow.
    multipliers: u64,
    luts: u64,
    /// `None`: not measured on the device's flow.
    measured: bool,
    pairs_tested: u64,
    /// Verdicts without a certificate in the leaves; `None` where the
    /// model was not run (the host pairs alone exceed the budget, or the
    /// width is not measured on the device's flow).
    uncertain: Option<u64>,
    host_pairs: u64,
}

impl Candidate {
    /// Of every pair the hardware or the host decides, those the host
    /// decides (a host pair without a certificate is counted once).
    fn host_share(&self) -> f64 {
        (self.uncertain.unwrap_or(0) + self.host_pairs) as f64
            / (self.pairs_tested + self.host_pairs).max(1) as f64
    }

    /// The host's share, `>=` where the model was not run.
    fn share_text(&self) -> String {
        let bound = if self.uncertain.is_some() { "" } else { ">= " };
        format!("{bound}{:.4} %", 100.0 * self.host_share())
    }

    fn name(&self) -> String {
        let rare = match self.rare_cases {
            RareCasePath::Parallel => "",
            RareCasePath::Shared => ", rare cases shared",
        };
        if self.grid_bits > self.width {
            format!(
                "W = {} in local frames of a {}-bit grid{rare}",
                self.width, self.grid_bits
            )
        } else {
            format!("W = {}{rare}", self.width)
        }
    }

    fn sim_flags(&self) -> String {
        let rare = match self.rare_cases {
            RareCasePath::Parallel => String::new(),
            RareCasePath::Shared => " --rare-cases shared".into(),
        };
        if self.grid_bits > self.width {
            format!(
                "--width {} --grid-bits {}{rare}",
                self.width, self.grid_bits
            )
        } else {
            format!("--width {}{rare}", self.width)
        }
    }
}

/// P and the depth, with the cycles of every P tried.
struct Sizing {
    pipelines: u32,
    depth: u64,
    /// (P, cycles at its best depth, fits the device).
    tried: Vec<(u32, u64, bool)>,
}

pub struct Request<'a> {
    pub scene: &'a SceneArgs,
    pub max_uncertain: f64,
    pub device: &'a Device,
    pub out: Option<PathBuf>,
}

pub fn run(request: Request) -> anyhow::Result<ExitCode> {
    let (a, b) = match request.scene.load(crate::sim::DEFAULT_SCENE) {
        Ok(objects) => objects,
        Err(e) => {
            eprintln!("error: --for-scene: {e}");
            return Ok(ExitCode::from(2));
        }
    };
    let measurements = Measurements::committed();
    let device = request.device;
    eprintln!(
        "for-scene: {} ({} triangles) x {} ({} triangles) on {} ({})",
        a.name,
        a.triangles.len(),
        b.name,
        b.triangles.len(),
        device.name,
        device.part
    );

    let mut candidates = Vec::new();
    for &w in SUPPORTED_WIDTHS {
        let w = w as u32;
        for grid_bits in grids_for(w) {
            candidates.push(measure(
                &a,
                &b,
                w,
                grid_bits,
                &measurements,
                device,
                request.max_uncertain,
            )?);
        }
    }
    // Cheapest first: multipliers per pipeline, then LUTs, then the
    // coarser grid.
    candidates.sort_by_key(|c| (!c.measured, c.multipliers, c.luts, c.grid_bits));
    let fits = |c: &Candidate| {
        c.measured
            && c.multipliers <= device.dsps
            && c.luts + control_luts(&measurements) <= device.luts
    };
    let chosen = candidates
        .iter()
        .position(|c| fits(c) && c.uncertain.is_some() && c.host_share() <= request.max_uncertain);
    let Some(chosen) = chosen else {
        let best = candidates
            .iter()
            .filter(|c| fits(c))
            .min_by(|x, y| x.host_share().total_cmp(&y.host_share()));
        match best {
            Some(best) => eprintln!(
                "error: --max-uncertain {}: no configuration on {} keeps the host's share of the pairs that low; the best there is {} ({} of {} pairs back to the host, {} multipliers per pipeline)",
                request.max_uncertain,
                device.name,
                best.name(),
                best.share_text(),
                best.pairs_tested + best.host_pairs,
                best.multipliers
            ),
            None => eprintln!("error: --device {}: no width measured on its flow ({}) fits it", device.name, device.flow),
        }
        return Ok(ExitCode::from(2));
    };
    let candidate = candidates[chosen].clone();
    let sizing = size(&a, &b, &candidate, &measurements, device)?;
    let hardware = hardware(&candidate, sizing.pipelines, sizing.depth);
    let scene = hardware.prepare(&a, &b)?;
    let run = run_scene(
        Engine::Model,
        &scene,
        hardware.system_config(),
        &SceneRunOptions::default(),
    )?;
    let measured = Candidate {
        pairs_tested: scene.pairs_tested(),
        uncertain: Some(uncertain_in_leaves(&scene, &run.uncertain)),
        host_pairs: scene.host_pairs(),
        ..candidate.clone()
    };

    let config = hardware.system_config();
    let stalls = stall_bound(
        candidate.rare_cases,
        sizing.pipelines as usize,
        &scene.batches(),
    );
    let kind = PipelineKind::from(candidate.rare_cases);
    let mut design = emit_system_with(config, kind, MultiplierMapping::Inferred)
        .with_context(|| format!("emitting {}", config.unit_name()))?;
    let why = explain(
        &request,
        &a,
        &b,
        &candidates,
        chosen,
        &sizing,
        &measured,
        (run.cycles, stalls),
        &measurements,
    );
    if let Some(readme) = design.files.iter_mut().find(|f| f.path == "README.md") {
        readme.contents.push_str(&why);
    }
    let dir = request
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("rtl-out").join(&design.top));
    design
        .write_to(&dir)
        .with_context(|| format!("writing {}", dir.display()))?;
    out!("{why}")?;
    eprintln!(
        "wrote {} ({} modules) to {}",
        design.top,
        design.modules.len(),
        dir.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// The system for `c` with `pipelines` and `depth`, octree broad phase.
fn hardware(c: &Candidate, pipelines: u32, depth: u64) -> HardwareArgs {
    HardwareArgs {
        width: c.width,
        pipelines,
        depth,
        no_split: false,
        clock_mhz: 100.0,
        grid_bits: (c.grid_bits > c.width).then_some(c.grid_bits),
    }
}

/// The pairs without a certificate that the hardware decided (those of
/// the host's own batches are the host's already).
fn uncertain_in_leaves(scene: &PreparedScene, uncertain: &PairSet) -> u64 {
    let host: std::collections::HashSet<(u32, u32)> = scene
        .host_batches()
        .iter()
        .flat_map(|batch| {
            batch
                .a
                .iter()
                .flat_map(|a| batch.b.iter().map(move |b| (a.id, b.id)))
        })
        .collect();
    uncertain.iter().filter(|p| !host.contains(p)).count() as u64
}

/// `w` on the device's flow, and the scene in the model at P = 2, depth
/// 256 (not run where it cannot be chosen: module docs).
fn measure(
    a: &SceneObject,
    b: &SceneObject,
    width: u32,
    grid_bits: u32,
    m: &Measurements,
    device: &Device,
    budget: f64,
) -> anyhow::Result<Candidate> {
    let (rare_cases, multipliers, luts, measured) = match device.flow {
        "ecp5" => m
            .ecp5_pipeline(width)
            .map_or((RareCasePath::Parallel, 0, 0, false), |(path, r)| {
                (path, r.mult18x18d, r.lut4, true)
            }),
        _ => m
            .xilinx(&pipeline_unit_name(width as usize))
            .map_or((RareCasePath::Parallel, 0, 0, false), |r| {
                (RareCasePath::Parallel, r.dsp48e1, r.lut, true)
            }),
    };
    let mut c = Candidate {
        width,
        grid_bits,
        rare_cases,
        multipliers,
        luts,
        measured,
        pairs_tested: 0,
        uncertain: None,
        host_pairs: 0,
    };
    let hardware = hardware(&c, 2, 256);
    let scene = hardware.prepare(a, b)?;
    c.pairs_tested = scene.pairs_tested();
    c.host_pairs = scene.host_pairs();
    if measured && c.host_share() <= budget {
        let run = run_scene(
            Engine::Model,
            &scene,
            hardware.system_config(),
            &SceneRunOptions::default(),
        )?;
        c.uncertain = Some(uncertain_in_leaves(&scene, &run.uncertain));
    }
    eprintln!(
        "for-scene: {}: {} of {} pairs to the host",
        c.name(),
        c.share_text(),
        c.pairs_tested + c.host_pairs
    );
    Ok(c)
}

/// P and the depth for `c` (module docs).
fn size(
    a: &SceneObject,
    b: &SceneObject,
    c: &Candidate,
    m: &Measurements,
    device: &Device,
) -> anyhow::Result<Sizing> {
    let fits = |p: u32| {
        p as u64 * c.multipliers <= device.dsps
            && p as u64 * c.luts + control_luts(m) <= device.luts
    };
    let best_depth = |p: u32| -> anyhow::Result<(u64, u64)> {
        let mut best: Option<(u64, u64)> = None;
        for depth in DEPTHS {
            let hardware = hardware(c, p, depth);
            let scene = hardware.prepare(a, b)?;
            let batches = scene.batches();
            let cycles = scene_cycles(hardware.system_config(), &batches)
                + stall_bound(c.rare_cases, p as usize, &batches);
            if best.is_none_or(|(_, b)| (cycles as f64) < 0.99 * b as f64) {
                best = Some((depth, cycles));
            }
        }
        Ok(best.expect("depths tried"))
    };
    let (mut depth, mut cycles) = best_depth(1)?;
    let mut sizing = Sizing {
        pipelines: 1,
        depth,
        tried: vec![(1, cycles, fits(1))],
    };
    let mut p = 1;
    while p < tritri_rtl::system::MAX_PIPELINES as u32 {
        let next = 2 * p;
        let (next_depth, next_cycles) = best_depth(next)?;
        let next_fits = fits(next);
        sizing.tried.push((next, next_cycles, next_fits));
        if !next_fits || (next_cycles as f64) > (1.0 - MIN_GAIN) * cycles as f64 {
            break;
        }
        (p, depth, cycles) = (next, next_depth, next_cycles);
    }
    sizing.pipelines = p;
    sizing.depth = depth;
    Ok(sizing)
}

/// The README's section: the choice and why.
#[allow(clippy::too_many_arguments)]
fn explain(
    request: &Request,
    a: &SceneObject,
    b: &SceneObject,
    candidates: &[Candidate],
    chosen: usize,
    sizing: &Sizing,
    measured: &Candidate,
    (cycles, stalls): (u64, u64),
    m: &Measurements,
) -> String {
    let c = &candidates[chosen];
    let device = request.device;
    let mut s = String::new();
    let _ = writeln!(s, "\n## Sized for a scene (`tritri gen --for-scene`)\n");
    let _ = writeln!(
        s,
        "Scene: A = `{}` ({} triangles), B = `{}` ({} triangles), pose of B {}; budget: at most {} % of the pairs tested back to the host; device: {} ({}: {} multipliers, {} LUTs). Hardware figures: rtl-out/measurements.json (measured {}).\n",
        a.name,
        a.triangles.len(),
        b.name,
        b.triangles.len(),
        request.scene.pose_b.unwrap_or_default(),
        100.0 * request.max_uncertain,
        device.name,
        device.part,
        device.dsps,
        device.luts,
        m.measured
    );
    let _ = writeln!(
        s,
        "**Chosen: {}, P = {}, memory depth {}.** In the model on this scene, so built: {:.4} % of {} pairs go back to the host; {} cycles for the narrow phase{}.\n",
        c.name(),
        sizing.pipelines,
        sizing.depth,
        100.0 * measured.host_share(),
        measured.pairs_tested + measured.host_pairs,
        cycles + stalls,
        match c.rare_cases {
            RareCasePath::Parallel => String::new(),
            RareCasePath::Shared => format!(
                ", of which at most {stalls} hold for the rare pairs (the pipeline routed on {} tests them on a shared unit: the stall model's bound)",
                device.flow
            ),
        }
    );
    // Every cheaper configuration misses the budget; the closest says by how much.
    let fewer = candidates[..chosen]
        .iter()
        .filter(|x| x.measured && x.multipliers < c.multipliers)
        .min_by(|x, y| x.host_share().total_cmp(&y.host_share()));
    let _ = match fewer {
        Some(x) => writeln!(
            s,
            "*Why not one bit fewer:* every configuration with fewer multipliers sends more back to the host than the budget allows; the closest, {} ({} multipliers per pipeline), sends {}.\n",
            x.name(),
            x.multipliers,
            x.share_text()
        ),
        None => writeln!(s, "*Why not one bit fewer:* no cheaper configuration is measured on {}.\n", device.flow),
    };
    let last = sizing.tried.last().copied();
    let current = sizing
        .tried
        .iter()
        .find(|t| t.0 == sizing.pipelines)
        .map_or(0, |t| t.1);
    let _ = match last.filter(|t| t.0 > sizing.pipelines) {
        Some((p, _, false)) => writeln!(s, "*Why not one more pipeline:* P = {p} does not fit: {} x {} multipliers and LUTs of one pipeline exceed the device.\n", p, c.multipliers),
        Some((p, next, true)) => writeln!(
            s,
            "*Why not one more pipeline:* P = {p} would take {next} cycles instead of {current} ({:.1} % fewer, below the {:.0} % a doubling must save).\n",
            100.0 * (1.0 - next as f64 / current.max(1) as f64),
            100.0 * MIN_GAIN
        ),
        None => writeln!(s, "*Why not one more pipeline:* P = {} is the most the system takes.\n", sizing.pipelines),
    };
    let _ = writeln!(s, "| configuration | multipliers / pipeline | LUT / pipeline | pairs in leaves | uncertain in leaves | host pairs (too long for a leaf's frame) | back to the host |");
    let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|");
    // Local frames whose host pairs alone exceed the budget are counted,
    // not listed.
    let hopeless = |x: &Candidate| x.measured && x.uncertain.is_none() && x.grid_bits > x.width;
    for (i, x) in candidates.iter().enumerate().filter(|(_, x)| !hopeless(x)) {
        let mark = if i == chosen { " (chosen)" } else { "" };
        if x.measured {
            let _ = writeln!(
                s,
                "| {}{mark} | {} | {} | {} | {} | {} | {} |",
                x.name(),
                x.multipliers,
                x.luts,
                x.pairs_tested,
                x.uncertain.map_or("not run".into(), |u| u.to_string()),
                x.host_pairs,
                x.share_text()
            );
        } else {
            let _ = writeln!(
                s,
                "| {} | not measured on {} | - | {} | not run | {} | - |",
                x.name(),
                device.flow,
                x.pairs_tested,
                x.host_pairs
            );
        }
    }
    let left_out = candidates.iter().filter(|x| hopeless(x)).count();
    if left_out > 0 {
        let _ = writeln!(s, "\nNot listed: {left_out} configurations in local frames whose pairs too long for a leaf's frame alone exceed the budget.");
    }
    let _ = writeln!(
        s,
        "\n| P | narrow-phase cycles (best depth) | fits |\n|---:|---:|---|"
    );
    for (p, cycles, fits) in &sizing.tried {
        let _ = writeln!(
            s,
            "| {p} | {cycles} | {} |",
            if *fits { "yes" } else { "no" }
        );
    }
    let scene_flags = format!(
        "--scene {} {}{}{}",
        a.name,
        b.name,
        request
            .scene
            .pose_b
            .map_or(String::new(), |p| format!(" --pose-b {p}")),
        if request.scene.scale_b == 1.0 {
            String::new()
        } else {
            format!(" --scale-b {}", request.scene.scale_b)
        }
    );
    let _ = writeln!(
        s,
        "\nRun this design on the scene in Verilator (the on-chip broad phase that batches for it): `tritri sim {scene_flags} --broad-phase octree {} --pipelines {} --depth {} --engine verilator`.",
        c.sim_flags(),
        sizing.pipelines,
        sizing.depth
    );
    s
}
