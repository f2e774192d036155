//! What the paper's display does with each patch for one eye
//! (`bezier_lod_gpu.txt`, section 3): cull it when it faces away
//! ([`super::cone::back_facing`], the conservative form), refine it when it
//! may hold a silhouette, and otherwise sample it by its distance from the
//! eye.

use super::cone::{back_facing, may_hold_silhouette, NormalCone};
use super::lod::{distance_level, DISTANCE_LEVELS};
use super::BezierPatch;
use nalgebra::{Point3, Vector3};

/// One patch's treatment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchView {
    pub culled: bool,
    pub silhouette: bool,
    /// Samples per side (0 when culled).
    pub samples: usize,
}

/// The centre of the net's control points.
fn centre(patch: &BezierPatch) -> Point3<f64> {
    let mut c = Vector3::zeros();
    for p in patch.net.iter().flatten() {
        c += p.coords / 16.0;
    }
    Point3::from(c)
}

/// The treatment of every patch seen from `eye`; `near` is the distance
/// within which patches get the finest distance level. A silhouette patch
/// takes the next finer level than its distance gives (20 stays 20); a
/// patch without a cone (no normal anywhere) is drawn at its distance
/// level.
pub fn plan(patches: &[BezierPatch], eye: Point3<f64>, near: f64) -> Vec<PatchView> {
    patches
        .iter()
        .map(|p| {
            let samples = distance_level((centre(p) - eye).norm(), near);
            match NormalCone::of(p) {
                Some(cone) if back_facing(&cone, p, eye) => PatchView {
                    culled: true,
                    silhouette: false,
                    samples: 0,
                },
                Some(cone) if may_hold_silhouette(&cone, p, eye) => {
                    let finer = DISTANCE_LEVELS
                        .iter()
                        .copied()
                        .find(|&l| l > samples)
                        .unwrap_or(samples);
                    PatchView {
                        culled: false,
                        silhouette: true,
                        samples: finer,
                    }
                }
                _ => PatchView {
                    culled: false,
                    silhouette: false,
                    samples,
                },
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
        let behind = c - 50.0 * cone.axis;
        let in_front = c + 50.0 * cone.axis;
        assert_eq!(
            plan(&[p], behind, 1.0)[0],
            PatchView {
                culled: true,
                silhouette: false,
                samples: 0
            }
        );
        let front = plan(&[p], in_front, 1.0)[0];
        assert!(!front.culled && front.samples == 5);
        assert_eq!(plan(&[p], in_front, 100.0)[0].samples, 20);
    }
}
