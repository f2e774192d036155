//! What the paper's display does with each patch for one eye
//! (`bezier_lod_gpu.txt`, section 3): cull it when it faces away
//! ([`super::cone::back_facing`], the conservative form), refine it when it
//! may hold a silhouette, and otherwise sample it by its distance from the
//! eye.

use super::cone::{back_facing, may_hold_silhouette, NormalCone};
use crate::vector::{length, sub};
use super::lod::{distance_level, DISTANCE_LEVELS};
use super::BezierPatch;
use crate::triangle::Point;

/// One patch's treatment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchView {
    pub culled: bool,
    pub silhouette: bool,
    /// Samples per side (0 when culled).
    pub samples: usize,
}

/// The centre of the net's control points.
fn centre(patch: &BezierPatch) -> Point {
    let mut c = [0.0; 3];
    for p in patch.net.iter().flatten() {
        for k in 0..3 {
            c[k] += p[k] / 16.0;
        }
    }
    c
}

/// The treatment of every patch seen from `eye`; `near` is the distance
/// within which patches get the finest distance level. A silhouette patch
/// takes the next finer level than its distance gives (20 stays 20); a
/// patch without a cone (no normal anywhere) is drawn at its distance
/// level.
pub fn plan(patches: &[BezierPatch], eye: Point, near: f64) -> Vec<PatchView> {
    patches
        .iter()
        .map(|p| {
            let samples = distance_level(length(sub(centre(p), eye)), near);
            match NormalCone::of(p) {
                Some(cone) if back_facing(&cone, p, eye) => PatchView { culled: true, silhouette: false, samples: 0 },
                Some(cone) if may_hold_silhouette(&cone, p, eye) => {
                    let finer = DISTANCE_LEVELS.iter().copied().find(|&l| l > samples).unwrap_or(samples);
                    PatchView { culled: false, silhouette: true, samples: finer }
                }
                _ => PatchView { culled: false, silhouette: false, samples },
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::tests::wavy_patch;
    use super::*;

    #[test]
    fn far_patches_are_coarse_and_hidden_ones_culled() {
        let p = wavy_patch();
        let cone = NormalCone::of(&p).unwrap();
        let c = centre(&p);
        // The normals point towards an eye in front, away from one behind.
        let behind = [0, 1, 2].map(|k| c[k] - 50.0 * cone.axis[k]);
        let in_front = [0, 1, 2].map(|k| c[k] + 50.0 * cone.axis[k]);
        assert_eq!(plan(&[p], behind, 1.0)[0], PatchView { culled: true, silhouette: false, samples: 0 });
        let front = plan(&[p], in_front, 1.0)[0];
        assert!(!front.culled && front.samples == 5);
        assert_eq!(plan(&[p], in_front, 100.0)[0].samples, 20);
    }
}
