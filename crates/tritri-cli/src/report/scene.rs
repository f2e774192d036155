//! The report's scene: `tritri sim`'s figures (model engine, octree broad
//! phase) at each width, from the same code.

use super::WidthRow;
use crate::scene_input::SceneArgs;
use anyhow::bail;
use serde::Serialize;
use std::time::Instant;
use tritri_cosim::engine::check_quantized;
use tritri_cosim::scene_query::{find_pairs, Accelerator, Clock, QueryOptions};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::reference::{exact_f64_pairs, PairDiff};
use tritri_rtl::pipeline::RareCasePath;

/// The clock of a width without a post-route figure (the thesis's).
pub const ASSUMED_CLOCK_MHZ: f64 = 100.0;

#[derive(Serialize)]
pub struct SceneSection {
    pub a: String,
    pub b: String,
    pub pose_b: String,
    pub triangles_a: usize,
    pub triangles_b: usize,
    /// Pairs that intersect, exact f64 on the original coordinates.
    pub exact_pairs: usize,
    /// The software box sweep with exact predicates, one thread, timed once.
    pub software_seconds: f64,
    pub rows: Vec<SceneRow>,
}

/// Where a scene row's clock comes from (the library's); report.json and
/// the table give its name.
pub use tritri_cosim::scene_query::ClockSource as SceneClock;

/// `tritri sim --scene A B --width W --pipelines P` in the model.
#[derive(Serialize, Clone)]
pub struct SceneRow {
    pub width: u32,
    /// The system's pipelines.
    pub pipelines: u32,
    pub pairs_tested: u64,
    /// Octree leaves holding both objects, and cells classified.
    pub leaves: usize,
    pub cells: u64,
    /// The narrow phase's cycles (`sim`'s `cycles:`), and first triangle in
    /// to last pair out (`sim`'s `speed, first triangle in ...`).
    pub cycles: u64,
    pub whole_cycles: u64,
    pub clock_mhz: f64,
    #[serde(serialize_with = "clock_name")]
    pub clock: SceneClock,
    /// Where the pipelines test their rare pairs: those of the width's
    /// routed pipeline.
    pub rare_cases: RareCasePath,
    /// With the rare pairs on the shared unit, the stall model's bound on
    /// the clocks the system holds for them (in `whole_cycles`); 0 with
    /// the parallel units.
    pub stall_cycles: u64,
    pub whole_seconds: f64,
    /// Software time over `whole_seconds`; none when the hardware took no
    /// time (no ratio to give; it was 1.2e302 once).
    pub speedup: Option<f64>,
    /// Intersecting pairs on the grid.
    pub intersecting: usize,
    pub uncertain: usize,
    /// The grid's answer against exact f64 on the originals.
    pub missing: usize,
    pub extra: usize,
    /// The certified answer (uncertain pairs decided again) against it.
    pub certified_missing: usize,
    pub certified_extra: usize,
}

pub fn measure(
    a: &SceneObject,
    b: &SceneObject,
    args: &SceneArgs,
    widths: &[u32],
    pipelines: u32,
    rows: &[WidthRow],
) -> anyhow::Result<SceneSection> {
    eprintln!(
        "report: scene {} x {}: exact f64 on the originals",
        a.name, b.name
    );
    let started = Instant::now();
    let truth = exact_f64_pairs(&a.triangles, &b.triangles);
    let software_seconds = started.elapsed().as_secs_f64();
    let mut out = Vec::new();
    for &width in widths {
        eprintln!("report: scene at W = {width}");
        // Where W was routed, the system has the pipelines that fit the
        // device at its clock (the system's where it was routed, else the
        // pipeline's), and the rare pairs where the routed pipeline tests
        // them; elsewhere P at the assumed clock.
        let row = rows.iter().find(|r| r.width == width);
        let routed = row.and_then(WidthRow::clock_mhz);
        let clock = match (routed, row.and_then(|r| r.system_fmax_mhz)) {
            (Some(mhz), Some(_)) => Clock {
                mhz,
                source: SceneClock::PostRouteSystem,
            },
            (Some(mhz), None) => Clock {
                mhz,
                source: SceneClock::PostRoutePipeline,
            },
            _ => Clock {
                mhz: ASSUMED_CLOCK_MHZ,
                source: SceneClock::Assumed,
            },
        };
        let accelerator = Accelerator {
            pipelines: row.and_then(|r| r.ecp5_pipelines).unwrap_or(pipelines),
            rare_cases: row.map_or(RareCasePath::Parallel, |r| r.rare_cases),
            clock,
            ..Accelerator::new(width)
        };
        // The software baseline is timed once above, not per width.
        let options = QueryOptions {
            check: false,
            ..QueryOptions::default()
        };
        let answer = find_pairs(a, b, &accelerator, &options)?;
        if let Some(fault) = answer.faults.first() {
            bail!("W = {width}: {fault}");
        }
        let (quantized, same) = check_quantized(&answer.scene, &answer.grid_pairs());
        if !same.is_empty() {
            bail!("W = {width}: the model differs from the exact model on the quantized coordinates (a bug)");
        }
        let Some(hardware) = &answer.hardware else {
            bail!("W = {width}: the objects' boxes do not meet");
        };
        let whole_cycles = hardware.cycles.whole;
        let whole_seconds = accelerator.time_of(whole_cycles).as_secs_f64();
        let diff = PairDiff::between(&truth.pairs, &quantized);
        let certified_diff = PairDiff::between(&truth.pairs, &answer.pairs);
        let scene = &answer.scene;
        out.push(SceneRow {
            width,
            pipelines: accelerator.pipelines,
            pairs_tested: scene.pairs_tested(),
            leaves: scene.octree.as_ref().map_or(0, |o| o.leaves.len()),
            cells: scene.octree.as_ref().map_or(0, |o| o.cells_visited as u64),
            cycles: hardware.cycles.narrow,
            whole_cycles,
            clock_mhz: clock.mhz,
            clock: clock.source,
            rare_cases: accelerator.rare_cases,
            stall_cycles: hardware.cycles.stall_bound,
            whole_seconds,
            speedup: speedup(software_seconds, whole_seconds),
            intersecting: hardware.run.pairs.len(),
            uncertain: hardware.run.uncertain.len(),
            missing: diff.missing.len(),
            extra: diff.extra.len(),
            certified_missing: certified_diff.missing.len(),
            certified_extra: certified_diff.extra.len(),
        });
    }
    Ok(SceneSection {
        a: a.name.clone(),
        b: b.name.clone(),
        pose_b: args.pose_b.unwrap_or_default().to_string(),
        triangles_a: a.triangles.len(),
        triangles_b: b.triangles.len(),
        exact_pairs: truth.pairs.len(),
        software_seconds,
        rows: out,
    })
}

/// report.json gives a clock by its name.
fn clock_name<S: serde::Serializer>(clock: &SceneClock, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(clock.name())
}

impl SceneRow {
    /// Seconds of `whole_cycles` at `mhz`.
    pub fn cycles_at(&self, mhz: f64) -> f64 {
        self.whole_cycles as f64 / (mhz * 1e6)
    }
}

/// Software time over hardware time, or none when the hardware took no
/// time (a ratio over 0 is no figure: it was printed as 1.2e302).
fn speedup(software_seconds: f64, hardware_seconds: f64) -> Option<f64> {
    (hardware_seconds > 0.0 && software_seconds.is_finite())
        .then(|| software_seconds / hardware_seconds)
}

#[cfg(test)]
mod speedup_tests {
    use super::speedup;

    #[test]
    fn no_time_gives_no_ratio() {
        assert_eq!(speedup(2.0, 0.5), Some(4.0));
        assert_eq!(speedup(2.0, 0.0), None);
        assert_eq!(speedup(f64::INFINITY, 1.0), None);
    }
}
