//! The cone-of-normals test in fixed point, exactly: what the hardware cone
//! unit (`tritri_rtl::bezier::cone_unit`) computes, one patch and eye a
//! clock.
//!
//! **Inputs.** The patch's control points on the grid of a [`PatchFrame`]
//! (a [`FixedNet`]), the eye on the same grid, and the patch's cone as
//! integers ([`FixedCone`]): the axis `a` rounded on a lattice of
//! [`AXIS_SCALE`] per unit, and a threshold `S >= sin²α' 2^F`, rounded up,
//! where `α'` is the cone's half-angle widened by the angle the axis's
//! rounding can turn it (`asin(√3 / 2 / AXIS_SCALE)`), so the integer cone
//! holds every direction the f64 cone holds. A cone of 90° or more gets
//! `S = 2^F + 1`, which nothing passes.
//!
//! **Test.** With `d = c - e` for each control point `c` (the patch lies in
//! their hull), the patch is *back-facing* (culled) when every `c` has
//! `a · d > 0` and `(a · d)² 2^F > S |a|² |d|²`, that is `cos∠(a, d) >
//! sin α'`: every point of the patch is then seen from behind
//! (`tritri_geom::bezier::cone::back_facing`, module docs there, on the
//! integers). *Front-facing* is the same with `a · d < 0`. A patch that is
//! neither may hold a silhouette. Every product is exact in `i128` for
//! [`EYE_EXTRA_BITS`]-wider eyes than the net's `W <= 24` bits.
//!
//! **Against the f64 test.** The axis and threshold are widened, never
//! narrowed; what can differ is the net and the eye, rounded to the grid
//! by half a step per coordinate. So a patch may be culled in fixed point
//! and not in f64 (or the reverse) only when some control point's
//! direction from the eye lies within about `√3 / |d|` radians of the
//! cone's boundary; `tritri-geom/tests/shared_testdata.rs` counts them on
//! the teapot and checks that no culled patch has a sampled point facing
//! the eye.

use super::cone::NormalCone;
use super::fixed::FixedNet;

/// Fraction bits of the threshold: `S` is `sin²α'` in units of `2^-F`.
pub const THRESHOLD_FRACTION_BITS: u32 = 16;
/// The axis is rounded on a lattice of this many steps per unit length,
/// so its components fit 16-bit two's complement.
pub const AXIS_SCALE: f64 = 16384.0;
/// Bits of an axis component.
pub const AXIS_BITS: usize = 16;
/// Bits of the threshold `S` (up to `2^F + 1`).
pub const THRESHOLD_BITS: usize = 18;
/// The eye may lie up to `2^EYE_EXTRA_BITS` times farther out than the
/// net's grid reaches: its coordinates have `W + EYE_EXTRA_BITS` bits.
pub const EYE_EXTRA_BITS: usize = 4;

/// A patch's cone as the hardware takes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FixedCone {
    pub axis: [i64; 3],
    pub threshold: i64,
}

/// The test's answer for one patch and eye.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Facing {
    /// Every point faces the eye.
    Front = 0,
    /// Every point faces away: the patch is culled.
    Back = 1,
    /// Neither is guaranteed: the patch may hold a silhouette.
    Silhouette = 2,
}

impl Facing {
    pub fn from_code(code: u64) -> Option<Facing> {
        match code {
            0 => Some(Facing::Front),
            1 => Some(Facing::Back),
            2 => Some(Facing::Silhouette),
            _ => None,
        }
    }
}

impl FixedCone {
    /// The integer cone holding `cone` (module docs); `None` (no cone: a
    /// patch without normals) gives the cone that never decides.
    pub fn of(cone: Option<&NormalCone>) -> FixedCone {
        let never = 1i64 << THRESHOLD_FRACTION_BITS | 1;
        let Some(cone) = cone else {
            return FixedCone {
                axis: [0, 0, 1],
                threshold: never,
            };
        };
        let axis = [0, 1, 2].map(|k| (cone.axis[k] * AXIS_SCALE).round() as i64);
        // The rounding moves the scaled axis by at most √3/2; the angle it
        // turns is at most asin(√3/2 / (scale - √3/2)). A margin of 1e-9
        // covers the f64 arithmetic here.
        let turn = (0.75f64.sqrt() / (AXIS_SCALE - 0.75f64.sqrt())).asin();
        let widened = cone.half_angle + turn + 1e-9;
        let threshold = if widened >= std::f64::consts::FRAC_PI_2 || axis == [0; 3] {
            never
        } else {
            let s2 = widened.sin().powi(2) * (1u64 << THRESHOLD_FRACTION_BITS) as f64;
            // Rounded up, and one more for the rounding of sin and powi.
            (s2.ceil() as i64 + 1).min(never)
        };
        FixedCone { axis, threshold }
    }
}

/// Which way the patch faces from `eye` (module docs), exactly.
pub fn facing(net: &FixedNet, eye: [i64; 3], cone: &FixedCone) -> Facing {
    let a = cone.axis.map(i128::from);
    let aa: i128 = a.iter().map(|x| x * x).sum();
    let bound = cone.threshold as i128 * aa;
    let (mut back, mut front) = (true, true);
    for c in net.iter().flatten() {
        let d = [0, 1, 2].map(|k| (c[k] - eye[k]) as i128);
        let p: i128 = (0..3).map(|k| a[k] * d[k]).sum();
        let dd: i128 = d.iter().map(|x| x * x).sum();
        let narrow = (p * p) << THRESHOLD_FRACTION_BITS > bound * dd;
        back &= p > 0 && narrow;
        front &= p < 0 && narrow;
    }
    match (back, front) {
        (true, _) => Facing::Back,
        (_, true) => Facing::Front,
        _ => Facing::Silhouette,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    fn flat_net() -> FixedNet {
        std::array::from_fn(|i| std::array::from_fn(|j| [100 * i as i64, 100 * j as i64, 0]))
    }

    /// A flat patch with its normal along +z: seen from below it faces
    /// away, from above it faces the eye, from its plane neither.
    #[test]
    fn a_flat_patch_faces_one_way() {
        let cone = FixedCone::of(Some(&NormalCone {
            axis: Vector3::new(0.0, 0.0, 1.0),
            half_angle: 0.0,
        }));
        assert_eq!(facing(&flat_net(), [150, 150, -1000], &cone), Facing::Back);
        assert_eq!(facing(&flat_net(), [150, 150, 1000], &cone), Facing::Front);
        assert_eq!(
            facing(&flat_net(), [5000, 150, 0], &cone),
            Facing::Silhouette
        );
    }

    /// A cone of 90° or more, or none, never decides.
    #[test]
    fn wide_or_missing_cones_never_decide() {
        let wide = FixedCone::of(Some(&NormalCone {
            axis: Vector3::new(0.0, 0.0, 1.0),
            half_angle: std::f64::consts::PI,
        }));
        for cone in [wide, FixedCone::of(None)] {
            assert_eq!(
                facing(&flat_net(), [150, 150, -1000], &cone),
                Facing::Silhouette
            );
        }
    }

    /// The widened threshold is at least sin² of the f64 half-angle.
    #[test]
    fn the_threshold_widens_the_cone() {
        for degrees in [0.0, 1.0, 30.0, 60.0, 89.0] {
            let alpha: f64 = (degrees as f64).to_radians();
            let cone = FixedCone::of(Some(&NormalCone {
                axis: Vector3::new(0.6, 0.0, 0.8),
                half_angle: alpha,
            }));
            assert!(
                cone.threshold as f64 >= alpha.sin().powi(2) * 65536.0,
                "{degrees}°"
            );
        }
    }
}
