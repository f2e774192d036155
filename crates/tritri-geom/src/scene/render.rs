//! A picture of a collision query: both objects shaded in their own
//! colours, and the triangles of the intersecting pairs in red (A's) and
//! magenta (B's), their edges drawn over everything so that a contact
//! hidden behind an object still shows.
//!
//! The camera looks from a direction (the voxel renders' [`View`]) at the
//! centre of both objects' box, far enough for the box's sphere to fit a
//! 40° field of view, with the chosen axis up; the scene is drawn scaled
//! to that sphere, so its size in units does not matter.

use super::reference::PairSet;
use crate::octree::render::View;
use crate::raster::{Camera, Canvas, Image};
use crate::triangle::Triangle;
use nalgebra::{Point3, Vector3};

/// A's triangles, B's, and those of either in an intersecting pair.
pub const COLOUR_A: [u8; 3] = [140, 175, 225];
pub const COLOUR_B: [u8; 3] = [235, 195, 140];
pub const COLOUR_HIT_A: [u8; 3] = [225, 30, 30];
pub const COLOUR_HIT_B: [u8; 3] = [200, 30, 190];

/// Field of view, degrees.
const FOV: f64 = 40.0;

/// The objects `a` and `b` with the triangles of `pairs` (`(i, j)`: A's
/// triangle `i`, B's `j`) highlighted. `view.eye` must not be zero.
pub fn render_pairs(a: &[Triangle], b: &[Triangle], pairs: &PairSet, view: &View) -> Image {
    let (mut lo, mut hi) = (
        Vector3::repeat(f64::INFINITY),
        Vector3::repeat(f64::NEG_INFINITY),
    );
    for p in a.iter().chain(b).flatten() {
        let p = Vector3::from(*p);
        lo = lo.inf(&p);
        hi = hi.sup(&p);
    }
    if lo.x > hi.x {
        return Image::background(view.size, view.size);
    }
    // The picture is drawn in the box's own frame, centred and scaled to a
    // unit sphere: perspective does not change with scale, and the
    // rasterizer's depths and areas then stay in range for a model of
    // 1e-12 units or of 1e300 (computed by halves, so that nothing
    // overflows on the way).
    let centre = lo / 2.0 + hi / 2.0;
    let half = hi / 2.0 - lo / 2.0;
    let largest = half.amax();
    let radius = if largest > 0.0 {
        largest * (half / largest).norm()
    } else {
        1.0
    };
    let frame =
        |t: &Triangle| -> Triangle { t.map(|p| ((Vector3::from(p) - centre) / radius).into()) };
    let a: Vec<Triangle> = a.iter().map(frame).collect();
    let b: Vec<Triangle> = b.iter().map(frame).collect();
    let distance = 1.0 / (0.5 * FOV.to_radians()).sin();
    let mut up = Vector3::zeros();
    up[view.up.min(2)] = 1.0;
    let camera = Camera {
        eye: Point3::origin() + view.eye.normalize() * distance,
        target: Point3::origin(),
        up,
        fov_degrees: FOV,
    };
    let mut canvas = Canvas::new(view.size, view.size, camera);
    let hit_a: std::collections::BTreeSet<u32> = pairs.iter().map(|p| p.0).collect();
    let hit_b: std::collections::BTreeSet<u32> = pairs.iter().map(|p| p.1).collect();
    for (i, t) in a.iter().enumerate() {
        canvas.triangle(
            t,
            if hit_a.contains(&(i as u32)) {
                COLOUR_HIT_A
            } else {
                COLOUR_A
            },
        );
    }
    for (j, t) in b.iter().enumerate() {
        canvas.triangle(
            t,
            if hit_b.contains(&(j as u32)) {
                COLOUR_HIT_B
            } else {
                COLOUR_B
            },
        );
    }
    // The contact is often hidden by one of the objects: the hit
    // triangles' edges are drawn over everything.
    let hits = hit_a
        .iter()
        .map(|&i| (a[i as usize], COLOUR_HIT_A))
        .chain(hit_b.iter().map(|&j| (b[j as usize], COLOUR_HIT_B)));
    for (t, colour) in hits {
        for k in 0..3 {
            canvas.line_through(Point3::from(t[k]), Point3::from(t[(k + 1) % 3]), colour);
        }
    }
    canvas.image
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two crossing squares: their hit triangles are drawn in the hit
    /// colours, the others in the objects' colours, and nothing is drawn
    /// for an empty scene.
    #[test]
    fn hits_are_drawn_in_their_colours() {
        let a: Vec<Triangle> = vec![
            [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0]],
            [[-1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]],
        ];
        let b: Vec<Triangle> = vec![
            [[0.0, -1.0, -1.0], [0.0, 1.0, -1.0], [0.0, 1.0, 1.0]],
            [[0.0, -1.0, -1.0], [0.0, 1.0, 1.0], [0.0, -1.0, 1.0]],
        ];
        let view = View {
            eye: Vector3::new(1.0, 0.5, 2.0),
            size: 96,
            up: 2,
        };
        let none = render_pairs(&a, &b, &PairSet::new(), &view);
        let some = render_pairs(&a, &b, &PairSet::from([(0, 1)]), &view);
        let reddish = |img: &Image| {
            img.pixels
                .iter()
                .filter(|p| p[0] as u32 > 3 * p[1] as u32)
                .count()
        };
        assert_eq!(reddish(&none), 0);
        assert!(reddish(&some) > 50, "{}", reddish(&some));
        assert_eq!(
            render_pairs(&[], &[], &PairSet::new(), &view),
            Image::background(96, 96)
        );
    }

    /// The picture does not depend on the model's units: scaled by a power
    /// of two it is the same to the pixel, and a model of 1e-12 or 1e300
    /// units (which rendered background only, issue 68) is drawn.
    #[test]
    fn a_model_of_any_size_is_drawn() {
        let a: Vec<Triangle> = vec![[[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0]]];
        let b: Vec<Triangle> = vec![[[0.0, -1.0, -1.0], [0.0, 1.0, -1.0], [0.0, 1.0, 1.0]]];
        let view = View {
            size: 64,
            ..View::default()
        };
        let scaled = |s: f64, shift: f64| {
            let f = |t: &Triangle| t.map(|p| p.map(|c| c * s + shift));
            (
                a.iter().map(f).collect::<Vec<_>>(),
                b.iter().map(f).collect::<Vec<_>>(),
            )
        };
        let unit = render_pairs(&a, &b, &PairSet::from([(0, 0)]), &view);
        let drawn = |img: &Image| {
            let background = Image::background(64, 64);
            img.pixels
                .iter()
                .zip(&background.pixels)
                .filter(|(p, q)| p != q)
                .count()
        };
        assert!(drawn(&unit) > 200, "{} pixels drawn", drawn(&unit));
        for s in [2f64.powi(-40), 2f64.powi(500)] {
            let (sa, sb) = scaled(s, 0.0);
            assert_eq!(
                render_pairs(&sa, &sb, &PairSet::from([(0, 0)]), &view),
                unit,
                "scale {s}"
            );
        }
        for (s, shift) in [(1e-12, 3e-12), (1e300, -2e300)] {
            let (sa, sb) = scaled(s, shift);
            let n = drawn(&render_pairs(&sa, &sb, &PairSet::from([(0, 0)]), &view));
            let m = drawn(&unit);
            assert!(
                n.abs_diff(m) * 50 <= m,
                "scale {s}: {n} pixels drawn, {m} at unit scale"
            );
        }
    }
}
