//! What the rare cases on a shared path would cost the system (issue 14,
//! part 3): each pipeline's coplanar and degenerate pairs go to a shared
//! unit ([`crate::pipeline::shared_rare_cases`]) that takes a coplanar pair
//! every [`COPLANAR_STEPS`] clocks and two segments every
//! [`SEGMENTS_STEPS`], and the system stalls (one `advance` for all
//! pipelines) while a rare pair waits for its pipeline's unit.
//!
//! The pairs come in the system's order ([`super::cycle_model`]): each
//! group of up to `P` bases is loaded, one a clock, then B streams past all
//! of them, pipeline `p` testing base `p` of the group. A pair that reaches
//! its unit before the unit is free holds every pipeline until it is. The
//! unit's time carries across groups and batches with only the bases'
//! loads between groups and nothing between batches, so the count is an
//! upper bound: the system has more idle clocks than that.
//!
//! The pipeline with the shared unit
//! ([`crate::pipeline::shared_rare_pipeline`]) and its system meet it: on
//! one batch, or one pipeline fed without gaps, the clocks they hold are
//! this count exactly; over several batches it is their upper bound
//! (`tritri-cosim/tests/system_shared_rare_cases.rs`,
//! `rusthdl_pipeline.rs`, `rtl_cosim.rs`). It counts holds only: the
//! system's `stall_cycles` also counts the clocks a filling result FIFO
//! holds the read side, which the tests rule out with a large FIFO.

use crate::pipeline::shared_rare_cases::{COPLANAR_STEPS, SEGMENTS_STEPS};
use crate::pipeline::RareCasePath;
use tritri_geom::devillers_guigue::{shape, Shape};
use tritri_geom::fixed_point::{orient3d_value, FixedPoint, FixedTriangle};
use tritri_geom::scene::Batch;

/// The test a pair needs beyond the general path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RareKind {
    /// The coplanar test: both triangles in one plane, or a degenerate
    /// triangle's segment in the other's plane.
    Coplanar,
    /// Two degenerate triangles: the segment test.
    Segments,
}

impl RareKind {
    /// Clocks of the shared unit's lanes.
    pub fn steps(self) -> u64 {
        match self {
            RareKind::Coplanar => COPLANAR_STEPS as u64,
            RareKind::Segments => SEGMENTS_STEPS as u64,
        }
    }
}

/// A segment or a point: `devillers_guigue::shape`'s test, the pipeline's
/// degenerate flag.
pub fn degenerate(t: &FixedTriangle) -> bool {
    !matches!(shape::<FixedPoint>(*t), Shape::Triangle(_))
}

/// Whether every vertex of `t` lies in the plane of the proper `plane`.
fn in_plane(t: &FixedTriangle, plane: &FixedTriangle) -> bool {
    t.iter()
        .all(|&v| orient3d_value(plane[0], plane[1], plane[2], v) == 0)
}

/// The rare test the pipeline's decision takes for `(t1, t2)` on the grid,
/// if any (`decision` in the pipeline: a segment lies in a plane when both
/// its ends do, and its ends are among its three collinear vertices).
pub fn rare_kind(t1: &FixedTriangle, t2: &FixedTriangle) -> Option<RareKind> {
    let coplanar = match (degenerate(t1), degenerate(t2)) {
        (true, true) => return Some(RareKind::Segments),
        (false, _) => in_plane(t2, t1),
        (true, false) => in_plane(t1, t2),
    };
    coplanar.then_some(RareKind::Coplanar)
}

/// The rare pairs of a run and the stall cycles they would cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RareCaseCost {
    pub pairs: u64,
    pub coplanar: u64,
    pub segments: u64,
    /// At most this many clocks with every pipeline held.
    pub stall_cycles: u64,
}

/// The clocks `pipelines` pipelines testing their rare pairs on
/// `rare_cases` hold for them on `batches`, at most: 0 on parallel units,
/// [`rare_case_cost`]'s count on a shared unit.
pub fn stall_bound(rare_cases: RareCasePath, pipelines: usize, batches: &[Batch]) -> u64 {
    match rare_cases {
        RareCasePath::Parallel => 0,
        RareCasePath::Shared => rare_case_cost(pipelines, batches).stall_cycles,
    }
}

/// The cost of `batches` on `pipelines` pipelines, each with a shared
/// rare-case unit.
pub fn rare_case_cost(pipelines: usize, batches: &[Batch]) -> RareCaseCost {
    let mut cost = RareCaseCost::default();
    let pipelines = pipelines.max(1);
    // `now`: the clock at which the current pairs reach the units; `free`:
    // the first clock at which each pipeline's unit takes a job.
    let mut now = 0u64;
    let mut free = vec![0u64; pipelines];
    for batch in batches {
        for group in batch.a.chunks(pipelines) {
            now += group.len() as u64;
            for b in batch.b {
                let kinds: Vec<Option<RareKind>> = group
                    .iter()
                    .map(|a| rare_kind(&a.triangle, &b.triangle))
                    .collect();
                let wait = kinds
                    .iter()
                    .zip(&free)
                    .filter(|(k, _)| k.is_some())
                    .map(|(_, &f)| f.saturating_sub(now))
                    .max()
                    .unwrap_or(0);
                now += wait;
                cost.stall_cycles += wait;
                for (p, kind) in kinds.iter().enumerate() {
                    if let Some(kind) = kind {
                        free[p] = now + kind.steps();
                        match kind {
                            RareKind::Coplanar => cost.coplanar += 1,
                            RareKind::Segments => cost.segments += 1,
                        }
                    }
                }
                cost.pairs += group.len() as u64;
                now += 1;
            }
        }
    }
    cost
}

#[cfg(test)]
mod tests {
    use super::*;
    use tritri_geom::scene::TaggedTriangle;

    fn tagged(ts: &[FixedTriangle]) -> Vec<TaggedTriangle> {
        ts.iter()
            .enumerate()
            .map(|(i, &triangle)| TaggedTriangle {
                id: i as u32,
                triangle,
            })
            .collect()
    }

    const FLOOR: FixedTriangle = [[0, 0, 0], [4, 0, 0], [0, 4, 0]];
    const ON_FLOOR: FixedTriangle = [[1, 1, 0], [3, 1, 0], [1, 3, 0]];
    const ABOVE: FixedTriangle = [[1, 1, 1], [3, 1, 2], [1, 3, 1]];
    const SEGMENT: FixedTriangle = [[0, 0, 0], [1, 1, 0], [2, 2, 0]];
    const POINT: FixedTriangle = [[1, 2, 3], [1, 2, 3], [1, 2, 3]];

    #[test]
    fn kinds_follow_the_decision() {
        assert_eq!(rare_kind(&FLOOR, &ON_FLOOR), Some(RareKind::Coplanar));
        assert_eq!(rare_kind(&FLOOR, &ABOVE), None);
        assert_eq!(rare_kind(&SEGMENT, &FLOOR), Some(RareKind::Coplanar));
        assert_eq!(rare_kind(&FLOOR, &SEGMENT), Some(RareKind::Coplanar));
        assert_eq!(rare_kind(&ABOVE, &SEGMENT), None);
        assert_eq!(rare_kind(&SEGMENT, &POINT), Some(RareKind::Segments));
    }

    /// One pipeline: rare pairs back to back wait the unit's steps less the
    /// clock each takes anyway; spaced by the steps, they cost nothing.
    #[test]
    fn back_to_back_rare_pairs_stall() {
        let a = tagged(&[FLOOR]);
        let b = tagged(&[ON_FLOOR; 4]);
        let batch = Batch { a: &a, b: &b };
        let cost = rare_case_cost(1, &[batch]);
        assert_eq!((cost.pairs, cost.coplanar, cost.segments), (4, 4, 0));
        assert_eq!(cost.stall_cycles, 3 * (COPLANAR_STEPS as u64 - 1));
        let mut spaced = Vec::new();
        for _ in 0..3 {
            spaced.push(ON_FLOOR);
            spaced.extend([ABOVE; COPLANAR_STEPS - 1]);
        }
        let b = tagged(&spaced);
        let batch = Batch { a: &a, b: &b };
        assert_eq!(rare_case_cost(1, &[batch]).stall_cycles, 0);
    }

    /// Two pipelines share the stall: a rare pair on each in the same
    /// clock waits for the later unit only.
    #[test]
    fn pipelines_stall_together() {
        let a = tagged(&[FLOOR, FLOOR]);
        let b = tagged(&[ON_FLOOR, ON_FLOOR]);
        let batch = Batch { a: &a, b: &b };
        let cost = rare_case_cost(2, &[batch]);
        assert_eq!((cost.pairs, cost.coplanar), (4, 4));
        assert_eq!(cost.stall_cycles, COPLANAR_STEPS as u64 - 1);
    }
}
