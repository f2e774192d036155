//! Display data for voxel models (`octree_engine.txt`, function 4): a
//! shaded picture from a chosen viewpoint, by casting one ray per pixel
//! through the voxel grid (a 3D digital differential analyser, so a ray
//! visits exactly the voxels it passes through, in order).
//!
//! The view is orthographic, looking from `eye` (a direction, any length)
//! towards the centre of the occupied voxels' bounding box, which fills
//! the picture, with the chosen axis up. A voxel
//! face is shaded by the angle between its normal and a light above and to
//! the left of the eye, darkened with depth, and tinted by its axis so the
//! three face orientations stay apart even under the same light.

use super::voxels::VoxelGrid;
pub use crate::raster::Image;
use nalgebra::{Point3, Vector3};

/// Where the picture is taken from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// From the grid's centre towards the eye.
    pub eye: Vector3<f64>,
    /// Pixels on a side (the picture is square).
    pub size: u32,
    /// The axis that points up in the picture (0, 1 or 2: x, y or z).
    pub up: usize,
}

impl Default for View {
    fn default() -> View {
        View {
            eye: Vector3::new(1.0, 0.7, 1.6),
            size: 512,
            up: 1,
        }
    }
}

/// The box `[lo, hi]` (voxel corners) around the occupied voxels.
fn occupied_box(grid: &VoxelGrid) -> Option<([f64; 3], [f64; 3])> {
    let n = grid.side();
    let (mut lo, mut hi) = ([usize::MAX; 3], [0usize; 3]);
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                if grid.get([x, y, z]) {
                    for (k, c) in [x, y, z].into_iter().enumerate() {
                        lo[k] = lo[k].min(c);
                        hi[k] = hi[k].max(c + 1);
                    }
                }
            }
        }
    }
    (lo[0] <= hi[0]).then(|| (lo.map(|c| c as f64), hi.map(|c| c as f64)))
}

/// The picture of the model. `eye` must not be the zero vector.
pub fn render(grid: &VoxelGrid, view: &View) -> Image {
    let (lo, hi) = occupied_box(grid).unwrap_or(([0.0; 3], [grid.side() as f64; 3]));
    let forward = -view.eye.normalize();
    let mut up_hint = Vector3::zeros();
    up_hint[view.up.min(2)] = 1.0;
    if forward.dot(&up_hint).abs() > 0.99 {
        up_hint = Vector3::new(up_hint[2], up_hint[0], up_hint[1]);
    }
    let right = forward.cross(&up_hint).normalize();
    let up = right.cross(&forward);
    let light = (-forward + 0.8 * up - 0.5 * right).normalize();
    let centre = Point3::from([0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0));
    // A margin of 4 % around the box's bounding sphere.
    let radius = 1.04 * (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt() / 2.0;
    let size = view.size.max(1);
    let background = Image::background(size, size);
    let mut pixels = Vec::with_capacity((size * size) as usize);
    for py in 0..size {
        for px in 0..size {
            let x = ((px as f64 + 0.5) / size as f64 * 2.0 - 1.0) * radius;
            let y = (1.0 - (py as f64 + 0.5) / size as f64 * 2.0) * radius;
            let origin = centre + x * right + y * up - 2.0 * radius * forward;
            let colour = match first_hit(grid, origin, forward) {
                Some((t, axis)) => {
                    let mut normal = Vector3::zeros();
                    normal[axis] = -forward[axis].signum();
                    let lambert = normal.dot(&light).max(0.0);
                    // Depth from the front of the bounding sphere, 0 to 1.
                    let depth = ((t - radius) / (2.0 * radius)).clamp(0.0, 1.0);
                    let tint = [[0.93, 0.78, 0.62], [0.80, 0.84, 0.93], [0.95, 0.92, 0.85]][axis];
                    let shade = (0.36 + 0.64 * lambert) * (1.0 - 0.35 * depth);
                    tint.map(|c| (255.0 * c * shade).round().clamp(0.0, 255.0) as u8)
                }
                None => background.pixels[(py * size + px) as usize],
            };
            pixels.push(colour);
        }
    }
    Image {
        width: size,
        height: size,
        pixels,
    }
}

/// The distance along the ray to the first occupied voxel and the axis of
/// the face it enters through.
fn first_hit(grid: &VoxelGrid, origin: Point3<f64>, dir: Vector3<f64>) -> Option<(f64, usize)> {
    let n = grid.side() as f64;
    // Clip the ray to the grid's box (slabs).
    let (mut t_in, mut t_out, mut axis_in) = (0.0f64, f64::INFINITY, 0usize);
    for k in 0..3 {
        if dir[k] == 0.0 {
            if origin[k] < 0.0 || origin[k] > n {
                return None;
            }
            continue;
        }
        let (a, b) = ((0.0 - origin[k]) / dir[k], (n - origin[k]) / dir[k]);
        let (near, far) = if a < b { (a, b) } else { (b, a) };
        if near > t_in {
            t_in = near;
            axis_in = k;
        }
        t_out = t_out.min(far);
    }
    if t_in > t_out {
        return None;
    }
    let side = grid.side() as i64;
    let entry = origin + t_in * dir;
    let mut cell = [0, 1, 2].map(|k| {
        // Nudged inward along the ray, so a ray entering on a face starts
        // in the voxel behind it.
        (entry[k] + dir[k] * 1e-9).floor().clamp(0.0, n - 1.0) as i64
    });
    let step = dir.map(|d| if d > 0.0 { 1i64 } else { -1 });
    let mut t_next = [0, 1, 2].map(|k| {
        if dir[k] == 0.0 {
            f64::INFINITY
        } else {
            let boundary = (cell[k] + i64::from(dir[k] > 0.0)) as f64;
            (boundary - origin[k]) / dir[k]
        }
    });
    let t_delta = dir.map(|d| {
        if d == 0.0 {
            f64::INFINITY
        } else {
            1.0 / d.abs()
        }
    });
    let (mut t, mut axis) = (t_in, axis_in);
    loop {
        if grid.get(cell.map(|c| c as usize)) {
            return Some((t, axis));
        }
        axis = (0..3)
            .min_by(|&a, &b| t_next[a].total_cmp(&t_next[b]))
            .unwrap_or(0);
        t = t_next[axis];
        cell[axis] += step[axis];
        if cell[axis] < 0 || cell[axis] >= side {
            return None;
        }
        t_next[axis] += t_delta[axis];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A block in the middle: seen from +x only its x face (the pixels at
    /// the centre; the block fills the picture up to the margin), the
    /// background at the corners.
    #[test]
    fn a_voxel_shows_the_face_towards_the_eye() {
        let mut g = VoxelGrid::empty(3);
        g.fill_cube([2, 2, 2], 2);
        let image = render(
            &g,
            &View {
                eye: Vector3::new(1.0, 0.0, 0.0),
                size: 64,
                up: 2,
            },
        );
        let centre = image.pixels[32 * 64 + 32];
        let corner = image.pixels[0];
        assert_ne!(centre, corner);
        // The x-face tint: red above blue.
        assert!(centre[0] > centre[2], "{centre:?}");
        let empty = render(
            &VoxelGrid::empty(3),
            &View {
                eye: Vector3::new(1.0, 0.0, 0.0),
                size: 64,
                up: 2,
            },
        );
        assert_eq!(empty.pixels[32 * 64 + 32], empty.pixels[32 * 64 + 1]);
    }
}
