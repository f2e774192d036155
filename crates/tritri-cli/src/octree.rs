//! `tritri octree`: the octree engine's operations on model files
//! (`.oct`): plane classification and the half-space cut, clipping to a
//! box, the set operations, conversion to other formats, renders.

use crate::input;
use crate::model_files::{read_octree, ModelOutput};
use crate::stdout::outln;
use crate::voxelize::ViewArgs;
use anyhow::Context as _;
use clap::Subcommand;
use std::process::ExitCode;
use std::time::Instant;
use tritri_cosim::engine::Engine;
use tritri_geom::octree::cell::Cell;
use tritri_geom::octree::clip::{clip, clip_logged};
use tritri_geom::octree::plane::classify_plane;
use tritri_geom::octree::segments::{boundary_edges, clip_segment, Clipped, Segment};
use tritri_geom::octree::tree::{Octree, OctreeFile, Placement, SetOperation};
use tritri_geom::octree::voxelize::level_of_resolution;
use tritri_geom::octree::voxels::VoxelGrid;
use tritri_rtl::emit::octree_builder_unit::OCTREE_BUILDER_NAME;
use tritri_rtl::emit::plane_traversal_unit::{PlaneInputs, PLANE_TRAVERSAL_NAME};
use tritri_rtl::emit::voxel_units::{OCTANT_CLIPPER_NAME, SET_OPERATION_NAME, VOXEL_FILL_NAME};
use tritri_rtl::octree::octant_clipper::CLIPPER_LATENCY;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(subcommand)]
    operation: Operation,
}

#[derive(Subcommand, Debug)]
enum Operation {
    /// Classify the grid against the plane n·p = d (p in voxel units): the
    /// voxels it crosses, and the half-space n·p <= d by voxel centres;
    /// with MODEL, the model cut by that half-space.
    Plane(PlaneArgs),
    /// Clip a model to a box of voxels: octants inside, outside, crossing.
    Clip(ClipArgs),
    /// A ∪ B.
    Union(PairArgs),
    /// A ∩ B.
    Intersection(PairArgs),
    /// A \ B.
    Difference(PairArgs),
    /// Write a model in other formats (.oct, .binvox, .vox, .obj, .png).
    Convert(ConvertArgs),
    /// A shaded render of a model.
    Render(RenderArgs),
}

#[derive(clap::Args, Debug)]
struct Outputs {
    /// Where to write the result: .oct, .binvox, .vox, .obj or .png; may be
    /// given several times.
    #[arg(long, value_name = "FILE")]
    out: Vec<String>,
    #[command(flatten)]
    view: ViewArgs,
}

#[derive(clap::Args, Debug)]
struct PlaneArgs {
    /// The model to cut (.oct); without it, the grid given by --resolution.
    model: Option<String>,
    /// Voxels per side when no model is given.
    #[arg(long, default_value_t = 512, value_name = "N", value_parser = input::parse_resolution)]
    resolution: u64,
    /// The plane's integer normal n.
    #[arg(long, value_name = "A,B,C", allow_hyphen_values = true, value_parser = input::parse_normal)]
    normal: [i64; 3],
    /// The plane's offset d (an integer).
    #[arg(long, value_name = "D", allow_hyphen_values = true, value_parser = crate::input::whole::<i64>(i64::MIN..=i64::MAX))]
    offset: i64,
    /// Who classifies (with `model`, the hardware's figures come from its
    /// cycle model), and the clock for the hardware's time.
    #[command(flatten)]
    hardware: EngineArgs,
    #[command(flatten)]
    outputs: Outputs,
}

/// A unit not routed yet is timed at this clock, said so.
pub const ASSUMED_CLOCK_MHZ: f64 = 100.0;

/// The clock a unit's time is given at: `--clock-mhz`, else its post-route
/// clock on the ECP5-85 from the measurements built in
/// (`rtl-out/measurements.json`), else [`ASSUMED_CLOCK_MHZ`]; with words
/// saying which.
pub fn unit_clock(hardware: &EngineArgs, unit: &str) -> (f64, &'static str) {
    routed_clock(hardware, unit).unwrap_or((ASSUMED_CLOCK_MHZ, " (assumed: not routed)"))
}

/// `--clock-mhz`, else the unit's post-route clock on the ECP5-85, with
/// words saying which; `None` for a unit not routed (no time is given).
pub fn routed_clock(hardware: &EngineArgs, unit: &str) -> Option<(f64, &'static str)> {
    match (
        hardware.clock_mhz,
        tritri_rtl::measured::Measurements::committed().ecp5(unit),
    ) {
        (Some(f), _) => Some((f, "")),
        (None, Some(row)) => Some((row.fmax_mhz, " (post-route, ECP5-85)")),
        (None, None) => None,
    }
}

#[derive(clap::Args, Debug)]
struct ClipArgs {
    model: String,
    /// The box in voxel indices, half-open: x0 <= x < x1 and so on.
    #[arg(long = "box", value_name = "X0,Y0,Z0,X1,Y1,Z1", allow_hyphen_values = true, value_parser = input::parse_voxel_box)]
    voxel_box: [i64; 6],
    /// Also write the model's display data: the edges of its boundary
    /// faces clipped exactly against the box (its closed extent), as OBJ
    /// line elements.
    #[arg(long, value_name = "FILE.obj")]
    segments: Option<String>,
    #[command(flatten)]
    hardware: EngineArgs,
    #[command(flatten)]
    outputs: Outputs,
}

/// Who computes, and the clock for the hardware's time.
#[derive(clap::Args, Debug)]
pub struct EngineArgs {
    /// `model` (software), or the hardware unit in `rusthdl`, `icarus` or
    /// `verilator`, checked against the model.
    #[arg(long, value_enum, default_value_t = Engine::Model)]
    pub engine: Engine,
    /// Clock frequency in MHz for the hardware's time [default: the
    /// unit's post-route clock on an ECP5-85, rtl-out/README.md; an
    /// assumed 100 MHz for a unit not routed].
    #[arg(long, value_name = "F", value_parser = input::parse_clock_mhz)]
    pub clock_mhz: Option<f64>,
}

#[derive(clap::Args, Debug)]
struct PairArgs {
    a: String,
    b: String,
    #[command(flatten)]
    hardware: EngineArgs,
    #[command(flatten)]
    outputs: Outputs,
}

#[derive(clap::Args, Debug)]
struct ConvertArgs {
    model: String,
    /// With a hardware engine, the octree's full leaves are also written
    /// into a voxel memory by the voxel fill unit, and that memory turned
    /// back into an octree by the octree builder, both checked.
    #[command(flatten)]
    hardware: EngineArgs,
    #[command(flatten)]
    outputs: Outputs,
}

#[derive(clap::Args, Debug)]
struct RenderArgs {
    model: String,
    /// The picture (.png).
    #[arg(long, value_name = "FILE")]
    png: String,
    #[command(flatten)]
    view: ViewArgs,
}

/// Bad input: the message, status 2, nothing computed.
fn bad(e: anyhow::Error) -> anyhow::Result<ExitCode> {
    eprintln!("error: {e:#}");
    Ok(ExitCode::from(2))
}

/// Reserves every output for a grid of `side`, none over an input.
fn reserve(paths: &[String], side: usize, inputs: &[&str]) -> anyhow::Result<Vec<ModelOutput>> {
    paths
        .iter()
        .map(|p| ModelOutput::reserve(p, side, inputs))
        .collect()
}

/// Reads a model and reserves its outputs (errors: bad input).
fn open(path: &str, outputs: &[String]) -> anyhow::Result<(OctreeFile, Vec<ModelOutput>)> {
    let model = read_octree(path)?;
    let outputs = reserve(outputs, 1 << model.tree.level(), &[path])?;
    describe(path, &model)?;
    Ok((model, outputs))
}

/// Writes `model` to every output.
fn write_all(outputs: Vec<ModelOutput>, model: &OctreeFile, view: &ViewArgs) -> anyhow::Result<()> {
    if outputs.is_empty() {
        return Ok(());
    }
    let grid = model.tree.to_voxels();
    for output in outputs {
        let path = output.path.clone();
        let bytes = output.write(&model.tree, &grid, &model.placement, &view.view())?;
        outln!("wrote {path} ({bytes} bytes)")?;
    }
    Ok(())
}

fn describe(name: &str, model: &OctreeFile) -> std::io::Result<()> {
    let n = 1u64 << model.tree.level();
    outln!(
        "{name}: {n}^3 grid, {} voxels, {} octree nodes",
        model.tree.voxel_count(),
        model.tree.nodes().len()
    )
}

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    match args.operation {
        Operation::Plane(a) => plane(a),
        Operation::Clip(a) => clip_model(a),
        Operation::Union(a) => combine(a, SetOperation::Union),
        Operation::Intersection(a) => combine(a, SetOperation::Intersection),
        Operation::Difference(a) => combine(a, SetOperation::Difference),
        Operation::Convert(a) => {
            let (model, outputs) = match open(&a.model, &a.outputs.out) {
                Ok(x) => x,
                Err(e) => return bad(e),
            };
            if a.hardware.engine != Engine::Model {
                fill_in_hardware(&model, &a.hardware)?;
                build_in_hardware(&model.tree.to_voxels(), &model.tree, &a.hardware)?;
            }
            write_all(outputs, &model, &a.outputs.view)?;
            Ok(ExitCode::SUCCESS)
        }
        Operation::Render(a) => {
            if !a.png.to_ascii_lowercase().ends_with(".png") {
                return bad(anyhow::anyhow!(
                    "--png {}: the render is written as .png",
                    a.png
                ));
            }
            let (model, outputs) = match open(&a.model, std::slice::from_ref(&a.png)) {
                Ok(x) => x,
                Err(e) => return bad(e),
            };
            write_all(outputs, &model, &a.view)?;
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// Octree → voxels in hardware: the tree's full leaves as records through
/// the voxel fill, the memory checked against the model's voxels.
fn fill_in_hardware(model: &OctreeFile, hardware: &EngineArgs) -> anyhow::Result<()> {
    let level = model.tree.level();
    anyhow::ensure!(
        level >= 1,
        "the voxel fill needs a grid of at least 2^3 voxels"
    );
    let records = model.tree.fill_records();
    let started = Instant::now();
    let run = match hardware.engine.simulator() {
        None => tritri_cosim::voxel_fill::fill_rusthdl(level, &records)?,
        Some(simulator) => tritri_cosim::voxel_fill::fill_emitted(level, &records, simulator)?,
    };
    anyhow::ensure!(
        run.words.as_slice() == model.tree.to_voxels().words(),
        "the voxel fill in {} left a memory that differs from the model (a bug)",
        hardware.engine.name()
    );
    let (clock, _) = unit_clock(hardware, VOXEL_FILL_NAME);
    outln!(
        "hardware ({}): {} fill records, {} word writes into the voxel memory, the model's voxels; {} cycles (a write per clock) = {:.3} ms at {clock} MHz (simulated in {:.1} s)",
        hardware.engine.name(),
        records.len(),
        run.writes,
        run.writes + 1,
        (run.writes + 1) as f64 / (clock * 1e3),
        started.elapsed().as_secs_f64()
    )?;
    Ok(())
}

/// Voxels → octree in hardware: the grid's 4x4x4 bricks through the octree
/// builder, its nodes checked against the model's tree.
pub fn build_in_hardware(
    grid: &VoxelGrid,
    tree: &Octree,
    hardware: &EngineArgs,
) -> anyhow::Result<()> {
    let started = Instant::now();
    let run = tritri_cosim::octree_builder::run(hardware.engine, grid)?;
    anyhow::ensure!(
        run.preorder() == tree.nodes(),
        "the octree builder in {} wrote a tree that differs from the model's (a bug)",
        hardware.engine.name()
    );
    let (clock, how) = unit_clock(hardware, OCTREE_BUILDER_NAME);
    outln!(
        "hardware ({}): octree builder, {} bricks in, the model's {} nodes out; {} cycles = {:.3} ms at {clock} MHz{how} (simulated in {:.1} s)",
        hardware.engine.name(),
        1u64 << (3 * grid.level().saturating_sub(2)),
        run.nodes.len(),
        run.cycles,
        run.cycles as f64 / (clock * 1e3),
        started.elapsed().as_secs_f64()
    )?;
    Ok(())
}

fn plane(a: PlaneArgs) -> anyhow::Result<ExitCode> {
    let model = match &a.model {
        Some(path) => match read_octree(path) {
            Ok(m) => Some(m),
            Err(e) => return bad(e),
        },
        None => None,
    };
    let level = match &model {
        Some(m) => m.tree.level(),
        None => level_of_resolution(a.resolution)?,
    };
    if let Err(e) = PlaneInputs::new(level, a.normal, a.offset) {
        return bad(anyhow::anyhow!("--normal {:?}: {e}", a.normal));
    }
    let inputs: Vec<&str> = a.model.iter().map(String::as_str).collect();
    let outputs = match reserve(&a.outputs.out, 1 << level, &inputs) {
        Ok(o) => o,
        Err(e) => return bad(e),
    };
    let started = Instant::now();
    let c = classify_plane(level, a.normal, a.offset);
    let took = started.elapsed();
    let n = 1u64 << level;
    outln!(
        "plane {:?}·p = {} on {n}^3: {} voxels crossed, {} cells split, half-space {} voxels in {} octree nodes; {:.3} ms",
        a.normal,
        a.offset,
        c.crossed_voxels,
        c.cells_split,
        c.half_space.voxel_count(),
        c.half_space.nodes().len(),
        took.as_secs_f64() * 1e3
    )?;
    // The hardware: its records must describe the model's half-space.
    let engine = a.hardware.engine;
    let (clock, _) = unit_clock(&a.hardware, PLANE_TRAVERSAL_NAME);
    let started = Instant::now();
    let hardware = tritri_cosim::plane_traversal::run(engine, level, a.normal, a.offset)?;
    let simulated = started.elapsed();
    let agrees = hardware.crossed_voxels() == c.crossed_voxels
        && hardware.half_space(level) == c.half_space.to_voxels();
    anyhow::ensure!(
        agrees,
        "the plane traversal in {} differs from the software model (a bug)",
        engine.name()
    );
    let words = hardware.fill_words(64);
    outln!(
        "hardware ({}): {} cells classified, {} records, {} cycles = {:.3} ms at {} MHz{}; the same half-space and crossed voxels as the model; \
         filling a voxel memory of 64-bit words takes {words} writes ({:.3} ms at one write per clock, overlapped with the traversal)",
        engine.name(),
        if engine == Engine::Model { hardware.cells.to_string() } else { "-".into() },
        hardware.records.len(),
        hardware.cycles,
        hardware.cycles as f64 / (clock * 1e3),
        clock,
        if engine == Engine::Model { String::new() } else { format!(" (simulated in {:.1} s)", simulated.as_secs_f64()) },
        words as f64 / (clock * 1e3)
    )?;
    let result = match model {
        Some(m) => {
            describe(a.model.as_deref().unwrap_or(""), &m)?;
            let cut = m.tree.combine(SetOperation::Intersection, &c.half_space);
            outln!(
                "cut: {} voxels kept of {}",
                cut.voxel_count(),
                m.tree.voxel_count()
            )?;
            OctreeFile {
                tree: cut,
                placement: m.placement,
            }
        }
        None => OctreeFile {
            tree: c.half_space,
            placement: Placement::default(),
        },
    };
    write_all(outputs, &result, &a.outputs.view)?;
    Ok(ExitCode::SUCCESS)
}

fn clip_model(a: ClipArgs) -> anyhow::Result<ExitCode> {
    let (model, outputs) = match open(&a.model, &a.outputs.out) {
        Ok(x) => x,
        Err(e) => return bad(e),
    };
    let b = a.voxel_box;
    if let Some(path) = a
        .segments
        .as_deref()
        .filter(|p| !p.to_ascii_lowercase().ends_with(".obj"))
    {
        return bad(anyhow::anyhow!(
            "--segments {path}: the segments are written as .obj"
        ));
    }
    let started = Instant::now();
    let (lo, hi) = ([b[0], b[1], b[2]], [b[3], b[4], b[5]]);
    // The octants are listed only for a hardware engine to be given them.
    let (clipped, counts, octants) = if a.hardware.engine == Engine::Model {
        let (clipped, counts) = clip(&model.tree, lo, hi);
        (clipped, counts, Vec::new())
    } else {
        clip_logged(&model.tree, lo, hi)
    };
    let took = started.elapsed();
    outln!(
        "clip to [{}, {}) x [{}, {}) x [{}, {}): {} octants ({} inside, {} outside, {} crossing) in {:.3} ms, {:.1} ns per octant; {} voxels kept",
        b[0],
        b[3],
        b[1],
        b[4],
        b[2],
        b[5],
        counts.octants(),
        counts.inside,
        counts.outside,
        counts.crossing,
        took.as_secs_f64() * 1e3,
        took.as_secs_f64() * 1e9 / counts.octants() as f64,
        clipped.voxel_count()
    )?;
    if a.hardware.engine != Engine::Model {
        // The clipper takes the box clamped to the grid (no octant changes class).
        let n = 1i64 << model.tree.level();
        let (lo, hi) = (lo.map(|c| c.clamp(0, n)), hi.map(|c| c.clamp(0, n)));
        let cells: Vec<Cell> = octants.iter().map(|&(c, _)| c).collect();
        let started = Instant::now();
        let classes = match a.hardware.engine.simulator() {
            None => tritri_cosim::voxel_units::clip_rusthdl(lo, hi, &cells)?,
            Some(simulator) => {
                tritri_cosim::voxel_units::clip_emitted(&[(lo, hi, &cells)], simulator)?.remove(0)
            }
        };
        let wrong = classes
            .iter()
            .zip(&octants)
            .filter(|(h, (_, m))| *h != m)
            .count()
            + octants.len().abs_diff(classes.len());
        anyhow::ensure!(wrong == 0, "the octant clipper in {} classified {wrong} octants differently from the model (a bug)", a.hardware.engine.name());
        let (clock, _) = unit_clock(&a.hardware, OCTANT_CLIPPER_NAME);
        let cycles = cells.len() as u64 + CLIPPER_LATENCY as u64;
        outln!(
            "hardware ({}): the model's {} classes, one octant per clock: {cycles} cycles = {:.3} ms at {clock} MHz ({:.1} ns per octant; simulated in {:.1} s)",
            a.hardware.engine.name(),
            cells.len(),
            cycles as f64 / (clock * 1e3),
            1e3 / clock,
            started.elapsed().as_secs_f64()
        )?;
    }
    write_all(
        outputs,
        &OctreeFile {
            tree: clipped,
            placement: model.placement,
        },
        &a.outputs.view,
    )?;
    // After the model's outputs, so a bad path loses none of them.
    if let Some(path) = &a.segments {
        write_clipped_segments(path, &model, lo, hi)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The boundary's edges clipped against the voxel box's closed extent
/// (corners `lo` to `hi`), written as OBJ lines in the model's coordinates.
fn write_clipped_segments(
    path: &str,
    model: &OctreeFile,
    lo: [i64; 3],
    hi: [i64; 3],
) -> anyhow::Result<()> {
    let edges = boundary_edges(&model.tree.to_voxels());
    let started = Instant::now();
    let clipped: Vec<(Segment, Clipped)> = edges
        .iter()
        .filter_map(|s| clip_segment(s, lo, hi).map(|c| (*s, c)))
        .collect();
    let took = started.elapsed();
    let whole = clipped.iter().filter(|(_, c)| c.is_whole()).count();
    outln!(
        "segments: {} boundary edges clipped in {:.3} ms, {:.1} ns per segment: {whole} inside, {} cut or touching it, {} outside",
        edges.len(),
        took.as_secs_f64() * 1e3,
        took.as_secs_f64() * 1e9 / edges.len().max(1) as f64,
        clipped.len() - whole,
        edges.len() - clipped.len()
    )?;
    let p = &model.placement;
    let mut text =
        String::from("# boundary edges of a voxel model clipped to a box, written by tritri\n");
    for (s, c) in &clipped {
        for end in c.ends(s) {
            text += &format!(
                "v {} {} {}\n",
                p.origin[0] + end[0] * p.voxel_size,
                p.origin[1] + end[1] * p.voxel_size,
                p.origin[2] + end[2] * p.voxel_size
            );
        }
    }
    for i in 0..clipped.len() {
        text += &format!("l {} {}\n", 2 * i + 1, 2 * i + 2);
    }
    std::fs::write(path, text).with_context(|| format!("writing {path}"))?;
    outln!("wrote {path} ({} segments)", clipped.len())?;
    Ok(())
}

fn combine(a: PairArgs, op: SetOperation) -> anyhow::Result<ExitCode> {
    let (ma, mb) = match (read_octree(&a.a), read_octree(&a.b)) {
        (Ok(x), Ok(y)) => (x, y),
        (Err(e), _) | (_, Err(e)) => return bad(e),
    };
    if ma.tree.level() != mb.tree.level() {
        return bad(anyhow::anyhow!(
            "{} is a {}^3 grid and {} a {}^3 grid: set operations need models of one grid",
            a.a,
            1u64 << ma.tree.level(),
            a.b,
            1u64 << mb.tree.level()
        ));
    }
    if ma.placement != mb.placement {
        eprintln!(
            "warning: {} and {} are placed differently; the result keeps {}'s placement",
            a.a, a.b, a.a
        );
    }
    let outputs = match reserve(&a.outputs.out, 1 << ma.tree.level(), &[&a.a, &a.b]) {
        Ok(o) => o,
        Err(e) => return bad(e),
    };
    describe(&a.a, &ma)?;
    describe(&a.b, &mb)?;
    let started = Instant::now();
    let result = ma.tree.combine(op, &mb.tree);
    let took = started.elapsed();
    outln!(
        "{op:?}: {} voxels, {} octree nodes, {:.3} ms (on the trees, no voxels expanded)",
        result.voxel_count(),
        result.nodes().len(),
        took.as_secs_f64() * 1e3
    )?;
    if a.hardware.engine != Engine::Model {
        // The unit streams both voxel memories a word per clock.
        let (va, vb) = (ma.tree.to_voxels(), mb.tree.to_voxels());
        let started = Instant::now();
        let words = match a.hardware.engine.simulator() {
            None => tritri_cosim::voxel_units::set_operation_rusthdl(op, va.words(), vb.words()).0,
            Some(simulator) => tritri_cosim::voxel_units::set_operations_emitted(
                &[(op, va.words(), vb.words())],
                simulator,
            )?
            .remove(0),
        };
        anyhow::ensure!(
            words.as_slice() == result.to_voxels().words(),
            "the set-operation unit in {} differs from the model (a bug)",
            a.hardware.engine.name()
        );
        let (clock, _) = unit_clock(&a.hardware, SET_OPERATION_NAME);
        let cycles = words.len() as u64 + 1;
        outln!(
            "hardware ({}): {} words of 64 voxels, the model's result; {cycles} cycles = {:.3} ms at {clock} MHz (simulated in {:.1} s)",
            a.hardware.engine.name(),
            words.len(),
            cycles as f64 / (clock * 1e3),
            started.elapsed().as_secs_f64()
        )?;
    }
    write_all(
        outputs,
        &OctreeFile {
            tree: result,
            placement: ma.placement,
        },
        &a.outputs.view,
    )?;
    Ok(ExitCode::SUCCESS)
}
