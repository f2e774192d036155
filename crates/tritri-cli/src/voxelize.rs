//! `tritri voxelize`: a mesh into a voxel model, surface or solid, exactly
//! on a fine grid (`tritri_geom::octree::voxelize`), written as an octree,
//! `.binvox`, `.vox`, the boundary faces or a render.

use crate::input;
use crate::model_files::ModelOutput;
use crate::octree::EngineArgs;
use crate::progress::Progress;
use crate::stdout::outln;
use std::process::ExitCode;
use std::time::Instant;
use tritri_cosim::engine::Engine;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::render::View;
use tritri_geom::octree::tree::Octree;
use tritri_geom::octree::voxelize::{self, level_of_resolution, VoxelFrame, SUB_BITS};
use tritri_geom::octree::voxels::VoxelGrid;
use tritri_geom::scene::load::load_object;
use tritri_rtl::emit::triangle_voxelizer_unit::TRIANGLE_VOXELIZER_NAME;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The mesh: .obj, .ply, .off, Bezier patches (.bpt), or @torus / @sphere.
    mesh: String,
    /// Voxels per side: a power of two from 2 to 1024.
    #[arg(long, default_value_t = 64, value_name = "N", value_parser = input::parse_resolution)]
    resolution: u64,
    /// Voxels whose centre is inside or on the closed mesh, instead of the
    /// voxels the surface meets (the mesh must be closed).
    #[arg(long)]
    solid: bool,
    /// Samples per side of each Bezier patch (.bpt), 1 to 256.
    #[arg(long, default_value_t = 8, value_name = "N", value_parser = crate::input::whole::<u64>(1..=crate::scene_input::MAX_TESSELLATION))]
    tessellation: u64,
    /// Write the model: .oct (octree), .binvox, .vox (up to 256^3), .obj
    /// (boundary faces) or .png (render); may be given several times.
    #[arg(long, value_name = "FILE")]
    out: Vec<String>,
    /// A shaded render of the model (the same as --out FILE.png).
    #[arg(long, value_name = "FILE")]
    png: Option<String>,
    #[command(flatten)]
    view: ViewArgs,
    /// Surface mode: who voxelizes, the software model (with the hardware's
    /// cycle model) or the hardware voxelizer, checked against the model.
    #[command(flatten)]
    hardware: EngineArgs,
}

/// Where renders are taken from.
#[derive(clap::Args, Debug, Clone)]
pub struct ViewArgs {
    /// View direction for renders: from the model's centre towards the eye.
    #[arg(long, default_value = "1,0.7,1.6", value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = input::parse_eye)]
    pub eye: [f64; 3],
    /// The axis pointing up in renders (meshes are mostly y-up; the Utah
    /// teapot's patches are z-up).
    #[arg(long, value_enum, default_value_t = UpAxis::Y)]
    pub up: UpAxis,
    /// Render size in pixels (16 to 4096).
    #[arg(long, default_value_t = 512, value_name = "PX", value_parser = crate::input::whole::<u32>(16..=4096))]
    pub size: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum UpAxis {
    X,
    Y,
    Z,
}

impl ViewArgs {
    pub fn view(&self) -> View {
        View {
            eye: self.eye.into(),
            size: self.size,
            up: self.up as usize,
        }
    }
}

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let level = level_of_resolution(args.resolution)?;
    if args.solid && args.hardware.engine != Engine::Model {
        eprintln!("error: --engine {}: the hardware voxelizes surfaces; --solid runs in the software model only", args.hardware.engine.name());
        return Ok(ExitCode::from(2));
    }
    let side = args.resolution as usize;
    // Outputs are checked before the work.
    let mut outputs = Vec::new();
    for path in args.out.iter().chain(&args.png) {
        match ModelOutput::reserve(path, side, &[&args.mesh]) {
            Ok(o) => outputs.push(o),
            Err(e) => {
                eprintln!("error: {e:#}");
                return Ok(ExitCode::from(2));
            }
        }
    }
    let object = match load_object(&args.mesh, args.tessellation as usize) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(2));
        }
    };
    let frame = match VoxelFrame::fit(&object.triangles, level) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("error: {}: {e}", args.mesh);
            return Ok(ExitCode::from(2));
        }
    };
    let triangles: Vec<_> = object.triangles.iter().map(|t| frame.quantize(t)).collect();
    outln!("mesh: {} ({} triangles)", object.name, triangles.len())?;
    outln!(
        "grid: {n}^3 voxels of {:.6} units from ({:.6}, {:.6}, {:.6}); vertices rounded to 1/{} voxel ({:.3e} units, error at most half of it)",
        frame.voxel_size,
        frame.origin[0],
        frame.origin[1],
        frame.origin[2],
        1u64 << SUB_BITS,
        frame.fine_step(),
        n = side,
    )?;
    let started = Instant::now();
    let progress = Progress::new(triangles.len() as u64, "triangles", 200_000);
    let mut done = 0usize;
    let mut report = |n: usize| {
        progress.inc((n - done) as u64);
        done = n;
    };
    let grid = if args.solid {
        match voxelize::solid(&triangles, &frame, &mut report) {
            Ok(g) => g,
            Err(e) => {
                progress.finish();
                eprintln!("error: {}: {e}", args.mesh);
                return Ok(ExitCode::from(2));
            }
        }
    } else {
        voxelize::surface(&triangles, level, &mut report)
    };
    progress.finish();
    let voxelized = started.elapsed();
    let tree = Octree::from_voxels(&grid);
    let bitmap_bytes = (side * side * side).div_ceil(8);
    let tree_bytes = tree.nodes().len().div_ceil(4);
    outln!(
        "{}: {} voxels in {:.3} s; octree {} nodes, {} bytes of nodes against a {} byte bitmap ({:.1} %)",
        if args.solid { "solid" } else { "surface" },
        grid.count(),
        voxelized.as_secs_f64(),
        tree.nodes().len(),
        tree_bytes,
        bitmap_bytes,
        100.0 * tree_bytes as f64 / bitmap_bytes as f64
    )?;
    if !args.solid {
        match voxelize_in_hardware(&triangles, level, &grid, &args.hardware) {
            // The model's voxels are the answer; the hardware's figures are
            // extra when no hardware was asked for.
            Err(e) if args.hardware.engine == Engine::Model => {
                outln!("hardware: no cycle count: {e:#}")?
            }
            result => result?,
        }
    }
    if args.hardware.engine != Engine::Model {
        crate::octree::build_in_hardware(&grid, &tree, &args.hardware)?;
    }
    for output in outputs {
        let path = output.path.clone();
        let bytes = output.write(&tree, &grid, &frame.placement(), &args.view.view())?;
        outln!("wrote {path} ({bytes} bytes)")?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The surface through the hardware voxelizer (or its cycle model), its
/// voxels checked against the software model's.
fn voxelize_in_hardware(
    triangles: &[FixedTriangle],
    level: u32,
    grid: &VoxelGrid,
    hardware: &EngineArgs,
) -> anyhow::Result<()> {
    if hardware.engine != Engine::Model {
        outln!(
            "hardware ({}): simulating {} triangles ...",
            hardware.engine.name(),
            triangles.len()
        )?;
    }
    let started = Instant::now();
    let run = tritri_cosim::triangle_voxelizer::run(hardware.engine, triangles, level)?;
    anyhow::ensure!(
        run.grid(level) == *grid,
        "the triangle voxelizer in {} marked voxels that differ from the software model (a bug)",
        hardware.engine.name()
    );
    let (clock, how) = crate::octree::unit_clock(hardware, TRIANGLE_VOXELIZER_NAME);
    let simulated = if hardware.engine == Engine::Model {
        String::new()
    } else {
        format!(" (simulated in {:.1} s)", started.elapsed().as_secs_f64())
    };
    outln!(
        "hardware ({}): {} records of 8 voxels, the model's voxels; {} cycles = {:.3} ms at {clock} MHz{how}{simulated}",
        hardware.engine.name(),
        run.records.len(),
        run.cycles,
        run.cycles as f64 / (clock * 1e3),
    )?;
    Ok(())
}
