//! Built-in scenes, generated in code, for runs that need no files: a torus
//! and a sphere in contact, tessellated at a chosen resolution.

use crate::triangle::{Point, Triangle};
use std::f64::consts::TAU;

/// Tessellates a closed parametric surface `f(u, v)`, `u, v` in `[0, 1)`,
/// into `2 * nu * nv` triangles (periodic in both parameters).
fn periodic_surface(nu: usize, nv: usize, f: impl Fn(f64, f64) -> Point) -> Vec<Triangle> {
    let p = |i: usize, j: usize| f((i % nu) as f64 / nu as f64, (j % nv) as f64 / nv as f64);
    let mut out = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            out.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            out.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    out
}

/// A torus around the z axis: major radius `big`, minor radius `small`.
pub fn torus(centre: Point, big: f64, small: f64, nu: usize, nv: usize) -> Vec<Triangle> {
    periodic_surface(nu, nv, |u, v| {
        let (a, b) = (TAU * u, TAU * v);
        let r = big + small * b.cos();
        [
            centre[0] + r * a.cos(),
            centre[1] + r * a.sin(),
            centre[2] + small * b.sin(),
        ]
    })
}

/// A UV sphere; the poles are rings of zero-radius avoided by sampling
/// latitudes strictly inside (0, pi) and closing them with fans.
pub fn sphere(centre: Point, radius: f64, nu: usize, nv: usize) -> Vec<Triangle> {
    let point = |lat: f64, lon: f64| {
        [
            centre[0] + radius * lat.sin() * lon.cos(),
            centre[1] + radius * lat.sin() * lon.sin(),
            centre[2] + radius * lat.cos(),
        ]
    };
    let lat = |i: usize| std::f64::consts::PI * i as f64 / nv as f64;
    let lon = |j: usize| TAU * (j % nu) as f64 / nu as f64;
    let (north, south) = (
        [centre[0], centre[1], centre[2] + radius],
        [centre[0], centre[1], centre[2] - radius],
    );
    let mut out = Vec::new();
    for j in 0..nu {
        out.push([north, point(lat(1), lon(j)), point(lat(1), lon(j + 1))]);
        out.push([
            south,
            point(lat(nv - 1), lon(j + 1)),
            point(lat(nv - 1), lon(j)),
        ]);
    }
    for i in 1..nv - 1 {
        for j in 0..nu {
            let (a, b, c, d) = (
                point(lat(i), lon(j)),
                point(lat(i + 1), lon(j)),
                point(lat(i + 1), lon(j + 1)),
                point(lat(i), lon(j + 1)),
            );
            out.push([a, b, c]);
            out.push([a, c, d]);
        }
    }
    out
}

/// The default scene: object A a torus, object B a sphere that dips into
/// the torus's tube, so a fraction of each mesh lies in the common box.
pub fn default_scene() -> (Vec<Triangle>, Vec<Triangle>) {
    let a = torus([0.0, 0.0, 0.0], 1.0, 0.35, 48, 24);
    let b = sphere([1.0, 0.0, 0.55], 0.4, 32, 16);
    (a, b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact_f64;

    #[test]
    fn default_scene_objects_touch() {
        let (a, b) = default_scene();
        assert_eq!(a.len(), 2 * 48 * 24);
        assert_eq!(b.len(), 2 * 32 * 15);
        let hits = a
            .iter()
            .flat_map(|ta| b.iter().map(move |tb| (ta, tb)))
            .filter(|(ta, tb)| exact_f64::intersects(ta, tb))
            .count();
        assert!(
            hits > 10,
            "the sphere must cut the torus's tube: {hits} intersecting pairs"
        );
    }
}
