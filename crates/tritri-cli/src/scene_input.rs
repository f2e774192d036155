//! What `tritri sim` and `tritri chapter5` share: the scene options, the
//! hardware options and loading the objects.

use crate::input;
use anyhow::Context as _;
use std::time::Duration;
use tritri_cosim::engine::Engine;
use tritri_cosim::patch_triangles::tessellate_pieces;
use tritri_cosim::scene_query::{Accelerator, Clock, ClockSource};
use tritri_geom::bezier::query::{
    patches_box, query_pieces, tessellate_for_query, MAX_SAMPLES, MAX_SPLITS,
};
use tritri_geom::bezier::{read_bpt, BezierPatch};
use tritri_geom::bounding_volume::Aabb;
use tritri_geom::scene::load::{load_object, LoadError, Pose, SceneObject};
use tritri_geom::scene::{PreparedScene, SceneError};
use tritri_rtl::pipeline::RareCasePath;
use tritri_rtl::system::{
    SystemConfig, DEFAULT_TRIANGLES_PER_BANK, MAX_PIPELINES, MAX_TRIANGLES_PER_BANK,
};

/// Most samples per side of a Bezier patch.
pub const MAX_TESSELLATION: u64 = tritri_geom::bezier::MAX_SAMPLES as u64;

/// The two objects and the pose of B.
#[derive(clap::Args, Clone, Debug)]
pub struct SceneArgs {
    /// Objects A and B: mesh files (.obj, .ply, .off), Bezier patches (.bpt),
    /// or the built-ins @torus and @sphere [default: the built-in scene].
    #[arg(long, num_args = 2, value_names = ["A", "B"])]
    pub scene: Option<Vec<String>>,
    /// Pose of B: tx,ty,tz[,rx,ry,rz]; rotations in degrees about the x, then
    /// y, then z axis through B's origin, then the translation.
    #[arg(long, allow_hyphen_values = true, value_name = "TX,TY,TZ,RX,RY,RZ")]
    pub pose_b: Option<Pose>,
    /// Uniform scale of B about its own origin, applied before the pose
    /// (the bunny is about 1 unit across, the armadillo about 127).
    #[arg(long, default_value_t = 1.0, value_name = "S", allow_negative_numbers = true, value_parser = input::parse_scale)]
    pub scale_b: f64,
    /// Cut every triangle of both objects into 4^K by edge midpoints (the
    /// same surfaces with more triangles, for scaling studies; 0 to 4).
    #[arg(long, default_value_t = 0, value_name = "K", value_parser = crate::input::whole::<u32>(0..=4))]
    pub subdivide: u32,
    /// Samples per side of each Bezier patch (.bpt): 2 n^2 triangles per
    /// patch (1 to 256: the teapot's 32 patches at 256 are 4.2 M triangles).
    #[arg(long, default_value_t = 8, value_name = "N", value_parser = crate::input::whole::<u64>(1..=MAX_TESSELLATION))]
    pub tessellation: u64,
    /// Tessellate `.bpt` objects for the query instead of uniformly: only
    /// the patches (cut into quarters up to 4 times) whose control nets
    /// can meet the other object, each at the fewest samples per side that
    /// keep it within this distance of the surface (mesh units, after
    /// --scale-b).
    #[arg(long, value_name = "T", allow_negative_numbers = true, value_parser = input::parse_tolerance)]
    pub tolerance: Option<f64>,
}

/// The grid the tessellation unit works on for `--tolerance` with a
/// hardware engine: fit to the kept pieces, so its step is far below any
/// tolerance (the unit is built for 16 and 24 bits).
const UNIT_GRID_BITS: usize = 24;

impl SceneArgs {
    /// The files `--scene` names (none for the built-in scene), which no
    /// output of the run may replace.
    pub fn files(&self) -> Vec<&str> {
        self.scene.iter().flatten().map(String::as_str).collect()
    }

    /// Loads A and B (B posed); `default` names the objects when `--scene`
    /// is not given.
    pub fn load(&self, default: [&str; 2]) -> anyhow::Result<(SceneObject, SceneObject)> {
        let (a, b, _) = self.load_with_notes(default, None)?;
        Ok((a, b))
    }

    /// [`Self::load`], and a line per `.bpt` object tessellated for the
    /// query (`--tolerance`) saying what it took. With `unit`, a hardware
    /// engine, the query's pieces go through the patch tessellation unit
    /// (with its triangles assembled) in that engine instead of the f64
    /// tessellation.
    pub fn load_with_notes(
        &self,
        default: [&str; 2],
        unit: Option<Engine>,
    ) -> anyhow::Result<(SceneObject, SceneObject, Vec<String>)> {
        let names: Vec<&str> = match &self.scene {
            Some(v) => v.iter().map(String::as_str).collect(),
            None => default.to_vec(),
        };
        let Some(tolerance) = self.tolerance else {
            let a = load_object(names[0], self.tessellation as usize)?.subdivided(self.subdivide);
            let b = self
                .placed(load_object(names[1], self.tessellation as usize)?)
                .subdivided(self.subdivide);
            return Ok((a, b, Vec::new()));
        };
        // The query's region is the overlap of conservative boxes: a patch
        // set's control nets, a mesh's triangles.
        let shape = |name: &str, is_b: bool| -> Result<Shape, LoadError> {
            Ok(match is_bpt(name) {
                true => {
                    let patches = read_bpt(std::path::Path::new(name))?;
                    Shape::Patches(if is_b {
                        patches.iter().map(|p| self.placed_patch(p)).collect()
                    } else {
                        patches
                    })
                }
                false => {
                    let object = load_object(name, self.tessellation as usize)?;
                    Shape::Mesh(if is_b { self.placed(object) } else { object })
                }
            })
        };
        let (a, b) = (shape(names[0], false)?, shape(names[1], true)?);
        let region = a.bounds().zip(b.bounds()).and_then(|(x, y)| x.overlap(&y));
        let mut notes = Vec::new();
        let mut object = |name: &str, shape: Shape| -> anyhow::Result<SceneObject> {
            Ok(match shape {
                Shape::Mesh(object) => object.subdivided(self.subdivide),
                Shape::Patches(patches) if unit.is_some() => {
                    let engine = unit.unwrap_or(Engine::Model);
                    let (pieces, kept) =
                        query_pieces(&patches, region.as_ref(), tolerance, MAX_SPLITS);
                    let t = tessellate_pieces(engine, UNIT_GRID_BITS, &pieces, tolerance)
                        .with_context(|| format!("{name} through the tessellation unit"))?;
                    notes.push(format!(
                    "tessellation for the query: {name}: {kept} of {} patches can meet the other object, {} pieces recut to {} for the tessellation unit in {} ({}-bit grid, step {:.3e}): {} triangles within {tolerance} of the surface plus a grid step, {} unit clocks",
                    patches.len(),
                    pieces.len(),
                    t.pieces,
                    engine.name(),
                    UNIT_GRID_BITS,
                    t.step,
                    t.triangles.len(),
                    t.clocks
                ));
                    SceneObject {
                        name: name.to_string(),
                        triangles: t.triangles,
                        face_of: t.face_of,
                    }
                    .subdivided(self.subdivide)
                }
                Shape::Patches(patches) => {
                    let q = tessellate_for_query(&patches, region.as_ref(), tolerance, MAX_SPLITS);
                    // What the tessellation reached: the tolerance, or (a
                    // piece capped at MAX_SAMPLES a side) its own bound.
                    let within = if q.bound <= tolerance {
                        format!("within {tolerance} of the surface")
                    } else {
                        format!(
                            "within {:.3e} of the surface (not the tolerance {tolerance}: a piece stops at {MAX_SAMPLES} samples a side)",
                            q.bound
                        )
                    };
                    notes.push(format!(
                    "tessellation for the query: {name}: {} of {} patches can meet the other object, cut into {} pieces: {} triangles {within}, against {} for every patch at {} samples a side (the same tolerance)",
                    q.patches_kept,
                    patches.len(),
                    q.pieces,
                    q.triangles.len(),
                    q.uniform_triangles,
                    q.uniform_samples
                ));
                    SceneObject {
                        name: name.to_string(),
                        triangles: q.triangles,
                        face_of: q.face_of,
                    }
                    .subdivided(self.subdivide)
                }
            })
        };
        let a = object(names[0], a)?;
        let b = object(names[1], b)?;
        Ok((a, b, notes))
    }

    /// Object B scaled and posed.
    fn placed(&self, b: SceneObject) -> SceneObject {
        let b = if self.scale_b == 1.0 {
            b
        } else {
            b.scaled(self.scale_b)
        };
        let pose = self.pose_b.unwrap_or_default();
        if pose.is_identity() {
            b
        } else {
            b.posed(&pose)
        }
    }

    /// A patch of B scaled and posed (control points move with the surface).
    fn placed_patch(&self, patch: &BezierPatch) -> BezierPatch {
        let motion = self.pose_b.unwrap_or_default().isometry();
        BezierPatch {
            net: patch
                .net
                .map(|row| row.map(|p| motion.transform_point(&(p * self.scale_b)))),
        }
    }
}

/// An object before tessellation.
enum Shape {
    Mesh(SceneObject),
    Patches(Vec<BezierPatch>),
}

impl Shape {
    /// A box holding every triangle the object can become.
    fn bounds(&self) -> Option<Aabb<f64>> {
        match self {
            Shape::Mesh(object) => Aabb::of_triangles(&object.triangles),
            Shape::Patches(patches) => patches_box(patches),
        }
    }
}

fn is_bpt(name: &str) -> bool {
    std::path::Path::new(name)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("bpt"))
}

/// The generated hardware.
#[derive(clap::Args, Clone, Debug)]
pub struct HardwareArgs {
    /// Coordinate width W (8 to 32 bits).
    #[arg(long, default_value_t = 24, value_parser = input::parse_width)]
    pub width: u32,
    /// Pipelines working in parallel (1 to 16).
    #[arg(long, default_value_t = 2, value_parser = crate::input::whole::<u32>(1..=MAX_PIPELINES as u32))]
    pub pipelines: u32,
    /// Memory depth: triangles per array per bank (1 to 32767); longer
    /// arrays are split into tiles.
    #[arg(long, default_value_t = DEFAULT_TRIANGLES_PER_BANK as u64,
          value_parser = crate::input::whole::<u64>(1..=MAX_TRIANGLES_PER_BANK as u64))]
    pub depth: u64,
    /// Refuse scenes whose arrays exceed D instead of splitting them.
    #[arg(long)]
    pub no_split: bool,
    /// Clock frequency in MHz, for times (0.001 to 100000).
    #[arg(long, default_value_t = 100.0, value_name = "F", allow_negative_numbers = true, value_parser = input::parse_clock_mhz)]
    pub clock_mhz: f64,
    /// Bits of the one grid the scene is quantized onto (W to 32; default
    /// W). Above W, each octree leaf goes to the W-bit hardware in a frame
    /// of its own: the same W gives a finer step.
    #[arg(long, value_name = "G", value_parser = input::parse_width)]
    pub grid_bits: Option<u32>,
}

pub use tritri_cosim::scene_query::BroadPhase;

impl HardwareArgs {
    /// The accelerator these options describe (the octree broad phase and
    /// the rare pairs on parallel units; `tritri sim --broad-phase` and
    /// `--rare-cases` set them), at `--clock-mhz`, assumed. Every other
    /// fact below is the accelerator's.
    pub fn accelerator(&self) -> Accelerator {
        Accelerator {
            width: self.width,
            grid_bits: self.grid_bits.unwrap_or(self.width),
            pipelines: self.pipelines,
            depth: self.depth as u32,
            split: !self.no_split,
            broad_phase: BroadPhase::Octree,
            rare_cases: RareCasePath::Parallel,
            clock: Clock {
                mhz: self.clock_mhz,
                source: ClockSource::Assumed,
            },
        }
    }

    pub fn scene_options(&self) -> tritri_geom::scene::SceneOptions {
        self.accelerator().scene_options()
    }

    /// The scene prepared for this hardware with the chosen broad phase.
    pub fn prepare(&self, a: &SceneObject, b: &SceneObject) -> Result<PreparedScene, SceneError> {
        self.accelerator().prepare(a, b)
    }

    pub fn time_of(&self, cycles: u64) -> Duration {
        self.accelerator().time_of(cycles)
    }

    /// The generator parameters of the system these options describe.
    pub fn system_config(&self) -> SystemConfig {
        self.accelerator().system_config()
    }
}

/// Pipeline latency `L` of the generated triangle pipeline.
pub fn pipeline_latency() -> u64 {
    tritri_rtl::pipeline::triangle_pipeline::latency() as u64
}

/// A duration in the unit that reads best.
pub fn human(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s >= 1.0 {
        format!("{s:.3} s")
    } else if s >= 1e-3 {
        format!("{:.3} ms", s * 1e3)
    } else if s >= 1e-6 {
        format!("{:.3} us", s * 1e6)
    } else {
        format!("{:.0} ns", s * 1e9)
    }
}
