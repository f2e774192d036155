//! `tritri chapter5 [--scene A B] [--fractions 5,25,50,75] [--axis x|y|z] ...`
//!
//! The comparison of the thesis's chapter 5: scenes in which a given share
//! of the polygons lies in the common BV, hardware time against software
//! time. B (default: a second copy of A, the built-in torus) is placed with
//! the centre of its box on the centre of A's box and slid along an axis;
//! a bisection on the offset finds, per target share, the scene whose share
//! of triangles in the common BV (of both objects, after the exact filter)
//! is the closest at or above the target.
//!
//! Per scene: triangles in the BV, pairs tested (of N1*N2), cycles of the
//! cycle model and the time at the clock; and the time measured on this
//! machine (one thread) of three software models:
//!
//! * exact f64: exact predicates on the original coordinates over all N1*N2
//!   pairs, deciding only pairs whose triangle boxes overlap (the complete
//!   software answer, no hardware needed);
//! * published f64: the published double-precision code on the pairs the
//!   hardware tests (every A-array × B-array pair, original coordinates);
//! * fixed point: the bit-exact model on the same pairs, quantized.
//!
//! The last three columns are the same scene with the octree broad phase
//! (the other columns are the thesis's flat system): pairs tested,
//! hardware time, and exact f64's time over it.
//!
//! Ratios are software time / hardware time: they compare this machine with
//! the cycle model at the given clock, nothing more.

use crate::input;
use crate::scene_input::{human, pipeline_latency, BroadPhase, HardwareArgs, SceneArgs};
use crate::stdout::outln;
use clap::ValueEnum;
use std::hint::black_box;
use std::process::ExitCode;
use std::time::{Duration, Instant};
use tritri_geom::bounding_volume::Aabb;
use tritri_geom::scene::load::{Pose, SceneObject};
use tritri_geom::scene::reference::exact_f64_pairs;
use tritri_geom::scene::{prepare, PreparedScene, SceneOptions};
use tritri_geom::{fixed_point, published_float};
use tritri_rtl::system::cycle_model::scene_cycles;

#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    hardware: HardwareArgs,
    /// Target shares of the triangles in the common BV, in percent.
    #[arg(long, value_delimiter = ',', default_value = "5,25,50,75", value_parser = input::parse_percentage)]
    fractions: Vec<f64>,
    /// Axis along which B slides.
    #[arg(long, value_enum, default_value_t = Axis::X)]
    axis: Axis,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Axis {
    X,
    Y,
    Z,
}

/// Default objects: two copies of the built-in torus.
pub const DEFAULT_SCENE: [&str; 2] = ["@torus", "@torus"];

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    if args
        .hardware
        .grid_bits
        .is_some_and(|g| g != args.hardware.width)
    {
        eprintln!("error: --grid-bits: chapter5 compares the flat system, which sends the whole box in one W-bit frame; use it with tritri sim");
        return Ok(ExitCode::from(2));
    }
    let (a, b) = match args.scene.load(DEFAULT_SCENE) {
        Ok(objects) => objects,
        Err(e) => {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(2));
        }
    };
    let (Some(box_a), Some(box_b)) = (
        Aabb::of_triangles(&a.triangles),
        Aabb::of_triangles(&b.triangles),
    ) else {
        anyhow::bail!("both objects need at least one triangle");
    };
    let options = SceneOptions {
        split: true,
        ..args.hardware.scene_options()
    };
    let config = args.hardware.system_config();
    let axis = args.axis as usize;
    let centre = |b: &Aabb<f64>| [0, 1, 2].map(|k| (b.lo[k] + b.hi[k]) / 2.0);
    let (ca, cb) = (centre(&box_a), centre(&box_b));
    // Past this offset the boxes are apart along the axis: no triangle in the BV.
    let apart = (box_a.hi[axis] - box_a.lo[axis] + box_b.hi[axis] - box_b.lo[axis]) / 2.0 * 1.01
        + f64::MIN_POSITIVE;
    let place = |offset: f64| {
        let mut t = [0, 1, 2].map(|k| ca[k] - cb[k]);
        t[axis] += offset;
        b.posed(&Pose::translation(t))
    };
    let scene_at = |offset: f64| -> anyhow::Result<(SceneObject, PreparedScene)> {
        let b = place(offset);
        let s = prepare(&a, &b, &options)?;
        Ok((b, s))
    };

    outln!(
        "chapter 5: A = {} ({} triangles), B = {} ({} triangles) slid along {:?}; W = {}, P = {}, depth {}, {} MHz, latency {}",
        a.name,
        a.triangles.len(),
        b.name,
        b.triangles.len(),
        args.axis,
        args.hardware.width,
        args.hardware.pipelines,
        args.hardware.depth,
        args.hardware.clock_mhz,
        pipeline_latency()
    )?;
    outln!("software: measured on this machine, one thread; hardware: cycle model of the system at the clock")?;
    outln!()?;
    outln!(
        "| target | in BV (A+B) | offset | pairs tested | of N1*N2 | hw cycles | hw time | exact f64, all pairs (AABB) | ratio | published f64, same pairs | ratio | fixed point, same pairs | ratio | octree: pairs tested | octree: hw time | ratio |"
    )?;
    outln!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")?;
    for &target in &args.fractions {
        let goal = target / 100.0;
        // Bisection: the share falls as the offset grows (the common box shrinks).
        let (mut near, mut far) = (0.0, apart);
        let (_, at_centre) = scene_at(0.0)?;
        let reachable = at_centre.fraction_in_common_bv() >= goal;
        if reachable {
            for _ in 0..60 {
                let mid = (near + far) / 2.0;
                if scene_at(mid)?.1.fraction_in_common_bv() >= goal {
                    near = mid;
                } else {
                    far = mid;
                }
            }
        }
        let (b_placed, scene) = scene_at(near)?;
        let batches = scene.batches();
        let cycles = scene_cycles(config, &batches);
        let hw = args.hardware.time_of(cycles);
        let exact = time(|| {
            exact_f64_pairs(&a.triangles, &b_placed.triangles)
                .pairs
                .len()
        });
        let published = time(|| {
            let mut hits = 0usize;
            for batch in &batches {
                for x in batch.a {
                    let tx = &a.triangles[x.id as usize];
                    for y in batch.b {
                        hits += published_float::intersects_f64(
                            black_box(tx),
                            &b_placed.triangles[y.id as usize],
                        ) as usize;
                    }
                }
            }
            hits
        });
        let fixed = time(|| {
            let mut hits = 0usize;
            for batch in &batches {
                for x in batch.a {
                    for y in batch.b {
                        hits +=
                            fixed_point::intersects(black_box(&x.triangle), &y.triangle) as usize;
                    }
                }
            }
            hits
        });
        let ratio_to = |sw: Duration, hw: Duration| {
            if hw.is_zero() {
                "-".to_string()
            } else {
                format!("{:.1}", sw.as_secs_f64() / hw.as_secs_f64())
            }
        };
        let ratio = |sw: Duration| ratio_to(sw, hw);
        let octree = args
            .hardware
            .accelerator()
            .prepare_with(BroadPhase::Octree, &a, &b_placed)?;
        let octree_hw = args
            .hardware
            .time_of(scene_cycles(config, &octree.batches()));
        outln!(
            "| {target} % | {} + {} = {:.1} %{} | {:.4} | {} | {:.2} % | {cycles} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            scene.kept_a.len(),
            scene.kept_b.len(),
            100.0 * scene.fraction_in_common_bv(),
            if reachable { "" } else { " (most reachable)" },
            near,
            scene.pairs_tested(),
            100.0 * scene.pairs_tested() as f64 / scene.all_pairs().max(1) as f64,
            human(hw),
            human(exact),
            ratio(exact),
            human(published),
            ratio(published),
            human(fixed),
            ratio(fixed),
            octree.pairs_tested(),
            human(octree_hw),
            ratio_to(exact, octree_hw),
        )?;
    }
    Ok(ExitCode::SUCCESS)
}

/// Wall time of one run of `f`, repeated while the total is under 0.2 s
/// (the mean of the runs).
fn time<T>(mut f: impl FnMut() -> T) -> Duration {
    let start = Instant::now();
    let mut runs = 0u32;
    loop {
        black_box(f());
        runs += 1;
        let elapsed = start.elapsed();
        if elapsed >= Duration::from_millis(200) || runs >= 1000 {
            return elapsed / runs;
        }
    }
}
