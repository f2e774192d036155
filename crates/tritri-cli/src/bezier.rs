//! `tritri bezier tessellate`: the patches on a W-bit grid through the
//! patch tessellation unit (forward differences, one vertex per clock) or
//! its exact fixed-point model, the error against the f64 patches.
//!
//! `tritri bezier cones`: every patch classified from an eye by its cone
//! of normals in fixed point, in the hardware cone unit or its model.
//!
//! `tritri bezier render`: Bezier patches drawn the way
//! `bezier_lod_gpu.txt` displays them: back-facing patches culled by their
//! cone of normals, patches that may hold a silhouette refined, the rest
//! sampled by distance (5, 10, 15 or 20 per side), each patch coloured by
//! its level and silhouette patches outlined in red.

use crate::input;
use crate::model_files::write_png;
use crate::octree::{routed_clock, EngineArgs};
use crate::output_file::OutputFile;
use crate::stdout::outln;
use clap::Subcommand;
use std::process::ExitCode;
use tritri_cosim::engine::Engine;
use tritri_cosim::patch_tessellator::{run_emitted, run_rusthdl};
use tritri_geom::bezier::fixed::{fixed_grid, max_error_in_steps, FixedNet, PatchFrame};
use tritri_geom::bezier::subdivide::subdivide;
use tritri_geom::bezier::view::plan;
use tritri_geom::bezier::{oriented_outwards, read_bpt, BezierPatch};
use tritri_geom::raster::{Camera, Canvas};
use tritri_rtl::bezier::patch_tessellator::tessellation_clocks;
use tritri_rtl::emit::cone_unit_unit::cone_unit_name;
use tritri_rtl::emit::patch_tessellator_unit::{
    patch_tessellator_unit_name, TESSELLATOR_CONFIGURATIONS,
};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(subcommand)]
    command: BezierCommand,
}

#[derive(Subcommand, Debug)]
enum BezierCommand {
    /// Render the patches of a .bpt file with the paper's level of detail.
    Render(RenderArgs),
    /// Tessellate the patches on a W-bit grid, 2^K steps a side, in the
    /// hardware tessellation unit or its fixed-point model; report the
    /// error against the f64 patches and the clocks.
    Tessellate(TessellateArgs),
    /// Classify every patch from an eye with its cone of normals in fixed
    /// point (culled, front-facing, or a possible silhouette), in the
    /// hardware cone unit or its model; compare with the f64 guarantee.
    Cones(ConesArgs),
}

#[derive(clap::Args, Debug)]
struct ConesArgs {
    /// The patches (.bpt).
    file: String,
    /// The eye's position, in the patches' coordinates.
    #[arg(long, default_value = "7,-10,6", value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = input::parse_point)]
    eye: [f64; 3],
    /// Bits of a control point's coordinate on the patches' grid (16 or 24).
    #[arg(long, default_value_t = 24, value_parser = crate::input::whole::<usize>(16..=24))]
    width: usize,
    /// Cut every patch in two this many times first (0 to 6).
    #[arg(long, default_value_t = 0, value_name = "K", value_parser = crate::input::whole::<u32>(0..=6))]
    subdivide: u32,
    /// What classifies (`--engine`: the exact fixed-point model, or the
    /// unit in rust-hdl, Icarus or Verilator, checked against the model),
    /// and the clock of its time (`--clock-mhz`; else the unit's
    /// post-route clock, and no time for a unit not routed).
    #[command(flatten)]
    hardware: EngineArgs,
}

#[derive(clap::Args, Debug)]
struct TessellateArgs {
    /// The patches (.bpt).
    file: String,
    /// Bits of a grid coordinate (16 or 24).
    #[arg(long, default_value_t = 16, value_parser = crate::input::whole::<usize>(16..=24))]
    width: usize,
    /// 2^K steps a side (1 to 4).
    #[arg(long, default_value_t = 3, value_name = "K", value_parser = crate::input::whole::<usize>(1..=4))]
    steps: usize,
    /// Cut every patch in two this many times first (0 to 6; the teapot's
    /// 32 patches become 64 to 512 for 1 to 4).
    #[arg(long, default_value_t = 0, value_name = "K", value_parser = crate::input::whole::<u32>(0..=6))]
    subdivide: u32,
    /// What tessellates (`--engine`: the exact fixed-point model, or the
    /// unit in rust-hdl, Icarus or Verilator, checked against the model),
    /// and the clock of its time (`--clock-mhz`; else the unit's
    /// post-route clock, and no time for a unit not routed).
    #[command(flatten)]
    hardware: EngineArgs,
}

#[derive(clap::Args, Debug)]
struct RenderArgs {
    /// The patches (.bpt, e.g. ../shared/testdata/teapot.bpt).
    file: String,
    /// The eye's position, in the patches' coordinates.
    #[arg(long, default_value = "7,-10,6", value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = input::parse_point)]
    eye: [f64; 3],
    /// The point looked at.
    #[arg(long, default_value = "0.2,0,1.3", value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = input::parse_point)]
    target: [f64; 3],
    /// Cut every patch in two this many times first (32 teapot patches
    /// become 64 to 512 for 1 to 4), 0 to 6.
    #[arg(long, default_value_t = 0, value_name = "K", value_parser = crate::input::whole::<u32>(0..=6))]
    subdivide: u32,
    /// Patches nearer than this get 20 samples per side; to twice it 15, to
    /// four times 10, beyond 5.
    #[arg(long, default_value_t = 4.0, value_name = "D", value_parser = input::parse_scale)]
    near: f64,
    /// The picture.
    #[arg(long, value_name = "FILE")]
    png: String,
    /// Picture size in pixels (16 to 4096).
    #[arg(long, default_value_t = 640, value_name = "PX", value_parser = crate::input::whole::<u32>(16..=4096))]
    size: u32,
}

/// Colours of the four levels, coarse to fine.
const LEVEL_COLOURS: [[u8; 3]; 4] = [
    [90, 140, 230],
    [110, 200, 120],
    [235, 210, 90],
    [240, 150, 70],
];

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let a = match args.command {
        BezierCommand::Render(a) => a,
        BezierCommand::Tessellate(t) => return tessellate(t),
        BezierCommand::Cones(c) => return cones(c),
    };
    if !a.png.to_ascii_lowercase().ends_with(".png") {
        eprintln!("error: --png {}: the render is written as .png", a.png);
        return Ok(ExitCode::from(2));
    }
    let output = match OutputFile::reserve(&a.png) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: --png: {e:#}");
            return Ok(ExitCode::from(2));
        }
    };
    // The cone tests need d_u x d_v to point out of the object.
    let (patches, turned) = match read_bpt(std::path::Path::new(&a.file)) {
        Ok(p) => oriented_outwards(&subdivide(&p, a.subdivide)),
        Err(e) => {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(2));
        }
    };
    if a.eye == a.target {
        eprintln!("error: --eye and --target are the same point");
        return Ok(ExitCode::from(2));
    }
    let views = plan(&patches, a.eye.into(), a.near);
    let camera = Camera {
        eye: a.eye.into(),
        target: a.target.into(),
        up: [0.0, 0.0, 1.0].into(),
        fov_degrees: 40.0,
    };
    let mut canvas = Canvas::new(a.size, a.size, camera);
    let mut triangles = 0usize;
    let mut per_level = [0usize; 4];
    for (patch, view) in patches.iter().zip(&views) {
        if view.culled {
            continue;
        }
        let level = tritri_geom::bezier::lod::DISTANCE_LEVELS
            .iter()
            .position(|&l| l == view.samples)
            .unwrap_or(0);
        per_level[level] += 1;
        for t in patch.tessellate(view.samples) {
            canvas.triangle(&t, LEVEL_COLOURS[level]);
            triangles += 1;
        }
    }
    for (patch, view) in patches.iter().zip(&views) {
        if view.silhouette {
            outline(&mut canvas, patch, [200, 30, 30]);
        }
    }
    let culled = views.iter().filter(|v| v.culled).count();
    let silhouettes = views.iter().filter(|v| v.silhouette).count();
    let uniform = patches
        .iter()
        .map(|p| p.tessellate(20).len())
        .sum::<usize>();
    outln!(
        "{}: {} patches from eye {:?}: {culled} culled (back-facing by their cone of normals), {silhouettes} may hold a silhouette (refined, outlined in red); \
         samples per side 5 / 10 / 15 / 20: {} / {} / {} / {} patches; {triangles} triangles against {uniform} for every patch at 20{}",
        a.file,
        patches.len(),
        a.eye,
        per_level[0],
        per_level[1],
        per_level[2],
        per_level[3],
        if turned { " (the file's d_u x d_v points inwards: patches turned round)" } else { "" }
    )?;
    let image = canvas.image;
    output.commit(|w| write_png(&image, w))?;
    outln!("wrote {}", a.png)?;
    Ok(ExitCode::SUCCESS)
}

/// The patch's four boundary curves as lines.
fn outline(canvas: &mut Canvas, patch: &BezierPatch, colour: [u8; 3]) {
    let steps = 16;
    let edges: [Box<dyn Fn(f64) -> (f64, f64)>; 4] = [
        Box::new(|t| (t, 0.0)),
        Box::new(|t| (t, 1.0)),
        Box::new(|t| (0.0, t)),
        Box::new(|t| (1.0, t)),
    ];
    for edge in &edges {
        for s in 0..steps {
            let (u0, v0) = edge(s as f64 / steps as f64);
            let (u1, v1) = edge((s + 1) as f64 / steps as f64);
            canvas.line(patch.evaluate(u0, v0), patch.evaluate(u1, v1), colour);
        }
    }
}

/// `tritri bezier tessellate`.
fn tessellate(a: TessellateArgs) -> anyhow::Result<ExitCode> {
    if !TESSELLATOR_CONFIGURATIONS.contains(&(a.width, a.steps)) {
        eprintln!("error: --width {} --steps {}: the tessellation unit is built for (W, K) in {TESSELLATOR_CONFIGURATIONS:?}", a.width, a.steps);
        return Ok(ExitCode::from(2));
    }
    let patches = match read_bpt(std::path::Path::new(&a.file)) {
        Ok(p) => subdivide(&p, a.subdivide),
        Err(e) => {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(2));
        }
    };
    let frame = PatchFrame::fit(&patches, a.width as u32);
    let nets: Vec<FixedNet> = patches.iter().map(|p| frame.quantize(p)).collect();
    let k = a.steps;
    let side = (1usize << k) + 1;
    let model: Vec<Vec<[i64; 3]>> = nets.iter().map(|net| fixed_grid(net, k as u32)).collect();
    let formula = patches.len() as u64 * tessellation_clocks(k as u32);
    let mut status = ExitCode::SUCCESS;
    let clocks = match a.hardware.engine {
        Engine::Model => formula,
        engine => {
            let runs = match engine.simulator() {
                None => run_rusthdl(a.width, k, &nets, &|_| true),
                Some(simulator) => run_emitted(a.width, k, &nets, simulator)?,
            };
            let wrong = runs
                .iter()
                .zip(&model)
                .filter(|(run, want)| {
                    run.vertices.len() != want.len()
                        || run
                            .vertices
                            .iter()
                            .zip(want.iter())
                            .any(|(got, w)| got.2 != *w)
                })
                .count();
            let clocks: u64 = runs.iter().map(|r| r.clocks).sum();
            outln!(
                "engine: {}: {} of {} patches differ from the fixed-point model; {clocks} clocks (formula: {formula})",
                engine.name(),
                wrong,
                patches.len()
            )?;
            if wrong > 0 || clocks != formula {
                status = ExitCode::from(1);
            }
            clocks
        }
    };
    let worst = patches
        .iter()
        .map(|p| max_error_in_steps(p, &frame, k as u32))
        .fold(0.0, f64::max);
    let triangles: usize = model
        .iter()
        .map(|grid| assembled_triangles(grid, side))
        .sum();
    outln!(
        "{}: {} patches at {} steps a side on a {}-bit grid (step {:.3e}): {} vertices, {triangles} triangles (degenerate ones left out)",
        a.file,
        patches.len(),
        1 << k,
        a.width,
        frame.step,
        patches.len() * side * side
    )?;
    outln!("error against the f64 patches: at most {worst:.3} grid steps per coordinate ({:.3e} in the file's units; the bound is 1 step)", worst * frame.step)?;
    let unit = patch_tessellator_unit_name(a.width, k);
    outln!(
        "clocks: {clocks}, one vertex per clock after 2 a patch; {}",
        rates(&a.hardware, &unit, clocks, patches.len(), Some(triangles))
    )?;
    Ok(status)
}

/// A unit's time and rates at its clock (`--clock-mhz` or its post-route
/// clock): patches, and `triangles` when it makes them, per second; for a
/// unit not routed, only that it is not.
fn rates(
    hardware: &EngineArgs,
    unit: &str,
    clocks: u64,
    patches: usize,
    triangles: Option<usize>,
) -> String {
    let Some((mhz, how)) = routed_clock(hardware, unit) else {
        return format!("{unit} is not routed (no time without a clock; --clock-mhz F gives one)");
    };
    let seconds = clocks as f64 / (mhz * 1e6);
    let per_second = |n: usize| n as f64 / seconds;
    let mut line = format!(
        "at {mhz:.1} MHz{how}: {:.2} us, {:.3e} patches/s",
        seconds * 1e6,
        per_second(patches)
    );
    if let Some(t) = triangles {
        line += &format!(", {:.3e} triangles/s", per_second(t));
    }
    line
}

/// Triangles of one patch's vertex grid, two per cell as in
/// `BezierPatch::tessellate`, those with two equal vertices left out.
fn assembled_triangles(grid: &[[i64; 3]], side: usize) -> usize {
    let at = |i: usize, j: usize| grid[i * side + j];
    let mut count = 0;
    for i in 0..side - 1 {
        for j in 0..side - 1 {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            count += [[a, b, c], [a, c, d]]
                .iter()
                .filter(|t| t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
                .count();
        }
    }
    count
}

/// `tritri bezier cones`: the fixed-point cone test on every patch.
fn cones(a: ConesArgs) -> anyhow::Result<ExitCode> {
    use tritri_cosim::cone_unit::{expected, inputs_for};
    use tritri_geom::bezier::cone::{back_facing, NormalCone};
    use tritri_geom::bezier::cone_fixed::Facing;
    use tritri_rtl::bezier::cone_unit::{CONE_UNIT_LATENCY, CONE_UNIT_WIDTHS};
    if !CONE_UNIT_WIDTHS.contains(&a.width) {
        eprintln!(
            "error: --width {}: the cone unit is built for {CONE_UNIT_WIDTHS:?}",
            a.width
        );
        return Ok(ExitCode::from(2));
    }
    let patches = match read_bpt(std::path::Path::new(&a.file)) {
        Ok(p) => oriented_outwards(&subdivide(&p, a.subdivide)).0,
        Err(e) => {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(2));
        }
    };
    let eye = a.eye.into();
    let inputs = match inputs_for(&patches, &[eye], a.width) {
        Ok(i) => i,
        Err(e) => {
            eprintln!("error: --eye {:?}: {e:#}", a.eye);
            return Ok(ExitCode::from(2));
        }
    };
    let started = std::time::Instant::now();
    let model = expected(&inputs);
    let engine = a.hardware.engine;
    let classes = match engine.simulator() {
        _ if engine == Engine::Model => model.clone(),
        None => tritri_cosim::cone_unit::run_rusthdl(a.width, &inputs)?,
        Some(simulator) => tritri_cosim::cone_unit::run_emitted(a.width, &inputs, simulator)?,
    };
    anyhow::ensure!(
        classes == model,
        "the cone unit in {} differs from the fixed-point model (a bug)",
        engine.name()
    );
    let count = |f: Facing| classes.iter().filter(|&&c| c == f).count();
    let f64_culled: Vec<bool> = patches
        .iter()
        .map(|p| NormalCone::of(p).is_some_and(|c| back_facing(&c, p, eye)))
        .collect();
    let differ = f64_culled
        .iter()
        .zip(&classes)
        .filter(|(&f, &c)| f != (c == Facing::Back))
        .count();
    outln!(
        "{} patches from ({}, {}, {}) on a {}-bit grid: {} culled, {} front-facing, {} possible silhouettes; the f64 guarantee culls {}, {differ} answers differ",
        patches.len(),
        a.eye[0],
        a.eye[1],
        a.eye[2],
        a.width,
        count(Facing::Back),
        count(Facing::Front),
        count(Facing::Silhouette),
        f64_culled.iter().filter(|&&c| c).count(),
    )?;
    let cycles = (patches.len() + CONE_UNIT_LATENCY) as u64;
    let simulated = match engine {
        Engine::Model => String::new(),
        _ => format!(
            " (the model's classes in {}, simulated in {:.1} s)",
            engine.name(),
            started.elapsed().as_secs_f64()
        ),
    };
    outln!(
        "clocks: {cycles}, one patch a clock after {CONE_UNIT_LATENCY}{simulated}; {}",
        rates(
            &a.hardware,
            &cone_unit_name(a.width),
            cycles,
            patches.len(),
            None
        )
    )?;
    Ok(ExitCode::SUCCESS)
}
