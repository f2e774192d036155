//! Pictures: an 8-bit RGB image, and a software rasterizer for triangles
//! (a z-buffer, flat shading by each triangle's normal), for renders of
//! Bezier tessellations and scenes. Voxel models have their own ray caster
//! (`octree::render`).

use crate::triangle::Triangle;
use nalgebra::{Point3, Vector3};

/// An 8-bit RGB picture, rows from the top.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[u8; 3]>,
}

impl Image {
    /// A picture of one colour, with a soft vertical gradient.
    pub fn background(width: u32, height: u32) -> Image {
        let mut pixels = Vec::with_capacity((width * height) as usize);
        for y in 0..height {
            let g = (236.0 - 24.0 * y as f64 / height.max(1) as f64) as u8;
            pixels.extend(std::iter::repeat([g, g, g.saturating_add(6)]).take(width as usize));
        }
        Image {
            width,
            height,
            pixels,
        }
    }
}

/// A perspective camera at `eye` looking at `target`, `up` roughly up,
/// with a vertical field of view of `fov_degrees`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: Point3<f64>,
    pub target: Point3<f64>,
    pub up: Vector3<f64>,
    pub fov_degrees: f64,
}

/// A z-buffered canvas.
pub struct Canvas {
    pub image: Image,
    depth: Vec<f64>,
    camera: Camera,
    forward: Vector3<f64>,
    right: Vector3<f64>,
    up: Vector3<f64>,
    focal: f64,
}

impl Canvas {
    pub fn new(width: u32, height: u32, camera: Camera) -> Canvas {
        let forward = unit(camera.target - camera.eye);
        let mut right = unit(forward.cross(&camera.up));
        if right == Vector3::zeros() {
            right = unit(forward.cross(&Vector3::x()));
        }
        let up = right.cross(&forward);
        let focal = 0.5 * height as f64 / (0.5 * camera.fov_degrees.to_radians()).tan();
        Canvas {
            image: Image::background(width, height),
            depth: vec![f64::INFINITY; (width * height) as usize],
            camera,
            forward,
            right,
            up,
            focal,
        }
    }

    /// Screen position (x right, y down, pixels) and depth along the view.
    fn project(&self, p: Point3<f64>) -> Option<(f64, f64, f64)> {
        let d = p - self.camera.eye;
        let z = d.dot(&self.forward);
        if z <= 1e-9 {
            return None;
        }
        let x = 0.5 * self.image.width as f64 + self.focal * d.dot(&self.right) / z;
        let y = 0.5 * self.image.height as f64 - self.focal * d.dot(&self.up) / z;
        Some((x, y, z))
    }

    /// Draws a triangle in `colour`, shaded by the angle between its normal
    /// and the view (both sides lit; back sides darker).
    pub fn triangle(&mut self, t: &Triangle, colour: [u8; 3]) {
        let [p, q, r] = t.map(Point3::from);
        let n = unit((q - p).cross(&(r - p)));
        let to_eye = unit(self.camera.eye - p);
        let light = unit(to_eye + 0.5 * self.up - 0.3 * self.right);
        let facing = n.dot(&to_eye);
        let lambert = if facing >= 0.0 {
            n.dot(&light).abs()
        } else {
            0.5 * n.dot(&light).abs()
        };
        let shade = 0.3 + 0.7 * lambert;
        let colour = colour.map(|c| (c as f64 * shade).round().clamp(0.0, 255.0) as u8);
        let (Some(a), Some(b), Some(c)) = (self.project(p), self.project(q), self.project(r))
        else {
            return;
        };
        let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
        if area.abs() < 1e-12 {
            return;
        }
        let (w, h) = (self.image.width as i64, self.image.height as i64);
        let x0 = a.0.min(b.0).min(c.0).floor().max(0.0) as i64;
        let x1 = (a.0.max(b.0).max(c.0).ceil() as i64).min(w - 1);
        let y0 = a.1.min(b.1).min(c.1).floor().max(0.0) as i64;
        let y1 = (a.1.max(b.1).max(c.1).ceil() as i64).min(h - 1);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                let w0 = ((b.0 - px) * (c.1 - py) - (b.1 - py) * (c.0 - px)) / area;
                let w1 = ((c.0 - px) * (a.1 - py) - (c.1 - py) * (a.0 - px)) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                // Perspective-correct depth: interpolate 1/z.
                let inv = w0 / a.2 + w1 / b.2 + w2 / c.2;
                let z = 1.0 / inv;
                let i = (y * w + x) as usize;
                if z < self.depth[i] {
                    self.depth[i] = z;
                    self.image.pixels[i] = colour;
                }
            }
        }
    }

    /// Draws a line segment (1 pixel) where it is not behind a drawn
    /// surface (a depth test with a 1 % allowance, so lines on a surface
    /// show).
    pub fn line(&mut self, a: Point3<f64>, b: Point3<f64>, colour: [u8; 3]) {
        self.segment(a, b, colour, true)
    }

    /// Draws a line segment over everything drawn so far (what is hidden
    /// shows through, as in an X-ray).
    pub fn line_through(&mut self, a: Point3<f64>, b: Point3<f64>, colour: [u8; 3]) {
        self.segment(a, b, colour, false)
    }

    fn segment(&mut self, a: Point3<f64>, b: Point3<f64>, colour: [u8; 3], depth_test: bool) {
        let (Some(p), Some(q)) = (self.project(a), self.project(b)) else {
            return;
        };
        let steps = ((q.0 - p.0).abs().max((q.1 - p.1).abs()).ceil() as usize).max(1);
        for s in 0..=steps {
            let t = s as f64 / steps as f64;
            let (x, y) = (p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1));
            // 1/z is linear along the screen-space segment.
            let z = 1.0 / ((1.0 - t) / p.2 + t / q.2);
            if x >= 0.0
                && y >= 0.0
                && (x as u32) < self.image.width
                && (y as u32) < self.image.height
            {
                let i = (y as u32 * self.image.width + x as u32) as usize;
                if !depth_test || z <= self.depth[i] * 1.01 {
                    self.image.pixels[i] = colour;
                }
            }
        }
    }
}

/// `v / |v|`; the zero vector stays zero (a degenerate triangle's normal,
/// an up vector along the view).
pub(crate) fn unit(v: Vector3<f64>) -> Vector3<f64> {
    v.try_normalize(0.0).unwrap_or(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A triangle in front of the camera covers the centre pixel; a nearer
    /// one hides it; one behind the camera draws nothing.
    #[test]
    fn the_nearer_triangle_wins() {
        let camera = Camera {
            eye: Point3::new(0.0, 0.0, 5.0),
            target: Point3::origin(),
            up: Vector3::y(),
            fov_degrees: 40.0,
        };
        let mut canvas = Canvas::new(64, 64, camera);
        let background = canvas.image.pixels[32 * 64 + 32];
        canvas.triangle(
            &[[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0]],
            [200, 0, 0],
        );
        let red = canvas.image.pixels[32 * 64 + 32];
        assert!(red[0] > 0 && red[1] == 0 && red != background);
        canvas.triangle(
            &[[-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [0.0, 1.0, 1.0]],
            [0, 200, 0],
        );
        assert!(canvas.image.pixels[32 * 64 + 32][1] > 0);
        canvas.triangle(
            &[[-1.0, -1.0, -0.5], [1.0, -1.0, -0.5], [0.0, 1.0, -0.5]],
            [0, 0, 200],
        );
        assert!(
            canvas.image.pixels[32 * 64 + 32][2] == 0,
            "hidden behind the green one"
        );
        canvas.triangle(
            &[[-1.0, -1.0, 9.0], [1.0, -1.0, 9.0], [0.0, 1.0, 9.0]],
            [0, 0, 200],
        );
        assert!(
            canvas.image.pixels[32 * 64 + 32][2] == 0,
            "behind the camera"
        );
    }
}
