//! Bicubic Bezier patches (`.bpt` files, such as the Utah teapot) and their
//! tessellation into triangles; the level-of-detail machinery of
//! `bezier_lod_gpu.txt`:
//!
//! * [`evaluate`]: the point and derivatives by De Casteljau and by forward
//!   differencing; normals defined at collapsed corners;
//! * [`subdivide`]: De Casteljau subdivision (the teapot's 32 patches into
//!   64 to 512);
//! * [`cone`]: the cone of normals as a guarantee, the paper's back-facing
//!   and silhouette tests and their conservative forms; [`cone_fixed`]: the
//!   conservative test exactly in fixed point, the hardware cone unit's
//!   model;
//! * [`lod`]: the paper's distance levels and an error-driven level;
//! * [`view`]: each patch's treatment for one eye (culled, silhouette,
//!   samples);
//! * [`fixed`]: a patch on the collision grid tessellated exactly in fixed
//!   point, the hardware tessellation unit's model;
//! * [`query`]: tessellation driven by a collision query (only the pieces
//!   that can touch, each as fine as the tolerance asks).
//!
//! `.bpt` format: the patch count, then per patch a line `3 3` (the degrees)
//! and 16 lines `x y z`, the control net row by row.

use crate::triangle::Triangle;
use nalgebra::{Point3, Vector3};
use std::path::Path;

pub mod cone;
pub mod cone_fixed;
pub mod evaluate;
pub mod fixed;
pub mod lod;
pub mod query;
pub mod subdivide;
pub mod view;

/// Most samples per side of a patch (or of a piece of one) that the
/// tessellations take: the teapot's 32 patches at 256 are 4.2 M triangles.
pub const MAX_SAMPLES: usize = 256;

/// One bicubic patch: control points `net[row][column]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BezierPatch {
    pub net: [[Point3<f64>; 4]; 4],
}

#[derive(Debug, thiserror::Error)]
pub enum BptError {
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("{path}:{line}: {message}")]
    Parse {
        path: String,
        line: usize,
        message: String,
    },
}

/// Cubic Bernstein weights at `t`.
fn bernstein(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t]
}

impl BezierPatch {
    /// The surface point at parameters `(u, v)` in `[0, 1]^2` (u along rows).
    pub fn evaluate(&self, u: f64, v: f64) -> Point3<f64> {
        let (bu, bv) = (bernstein(u), bernstein(v));
        let mut p = Vector3::zeros();
        for (i, row) in self.net.iter().enumerate() {
            for (j, c) in row.iter().enumerate() {
                p += bu[i] * bv[j] * c.coords;
            }
        }
        Point3::from(p)
    }

    /// `n x n` quads of samples, two triangles each. Triangles with two
    /// identical vertices (where a row of the net collapses to a point, as on
    /// the teapot's lid and bottom) are left out: they add no surface.
    /// Triangles are the collision system's plain coordinate arrays.
    pub fn tessellate(&self, n: usize) -> Vec<Triangle> {
        let n = n.max(1);
        let sample = |i: usize, j: usize| {
            self.evaluate(i as f64 / n as f64, j as f64 / n as f64)
                .into()
        };
        let grid: Vec<Vec<[f64; 3]>> = (0..=n)
            .map(|i| (0..=n).map(|j| sample(i, j)).collect())
            .collect();
        let mut out = Vec::with_capacity(2 * n * n);
        for i in 0..n {
            for j in 0..n {
                let (a, b, c, d) = (
                    grid[i][j],
                    grid[i + 1][j],
                    grid[i + 1][j + 1],
                    grid[i][j + 1],
                );
                for t in [[a, b, c], [a, c, d]] {
                    if t[0] != t[1] && t[1] != t[2] && t[2] != t[0] {
                        out.push(t);
                    }
                }
            }
        }
        out
    }
}

impl BezierPatch {
    /// The same surface with `u` reversed: `d_u × d_v`, and so the side
    /// the cone of normals calls the outside, turns round.
    pub fn reversed(&self) -> BezierPatch {
        let mut net = self.net;
        net.reverse();
        BezierPatch { net }
    }
}

/// The volume the patches enclose, signed by their orientation: positive
/// when `d_u × d_v` points out of it (from a tessellation at 8 samples a
/// side, by the divergence theorem; for surfaces that are not quite closed,
/// such as the teapot, its sign still tells the orientation).
pub fn signed_volume(patches: &[BezierPatch]) -> f64 {
    patches
        .iter()
        .flat_map(|p| p.tessellate(8))
        .map(|[a, b, c]| {
            (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))
                / 6.0
        })
        .sum()
}

/// The patches oriented so that `d_u × d_v` points outwards (by
/// [`signed_volume`]), and whether they were turned round.
pub fn oriented_outwards(patches: &[BezierPatch]) -> (Vec<BezierPatch>, bool) {
    if signed_volume(patches) < 0.0 {
        (patches.iter().map(BezierPatch::reversed).collect(), true)
    } else {
        (patches.to_vec(), false)
    }
}

/// Reads a `.bpt` file.
pub fn read_bpt(path: &Path) -> Result<Vec<BezierPatch>, BptError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| BptError::Io {
        path: name.clone(),
        source,
    })?;
    let text = crate::text::utf8_text(&bytes).map_err(|line| BptError::Parse {
        path: name.clone(),
        line,
        message: "not UTF-8 text".to_string(),
    })?;
    parse_bpt(text).map_err(|(line, message)| BptError::Parse {
        path: name,
        line,
        message,
    })
}

/// Parses `.bpt` text; errors are `(line, message)`.
pub fn parse_bpt(text: &str) -> Result<Vec<BezierPatch>, (usize, String)> {
    // A truncated file is reported at the line after its last.
    let end = text.lines().count() + 1;
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty());
    let mut next = |what: &str| {
        lines
            .next()
            .ok_or_else(|| (end, format!("file ends where {what} was expected")))
    };
    let (line, count) = next("the patch count")?;
    let count: usize = count
        .parse()
        .map_err(|_| (line, format!("patch count `{count}` is not an integer")))?;
    let mut patches = Vec::with_capacity(count.min(1 << 16));
    for _ in 0..count {
        let (line, degrees) = next("`3 3`")?;
        if degrees.split_whitespace().collect::<Vec<_>>() != ["3", "3"] {
            return Err((
                line,
                format!("only bicubic patches (`3 3`) are supported, found `{degrees}`"),
            ));
        }
        let mut net = [[Point3::origin(); 4]; 4];
        for row in net.iter_mut() {
            for point in row.iter_mut() {
                let (line, xyz) = next("a control point")?;
                let values: Vec<&str> = xyz.split_whitespace().collect();
                if values.len() != 3 {
                    return Err((
                        line,
                        format!("control point has {} numbers, expected 3", values.len()),
                    ));
                }
                for k in 0..3 {
                    let v: f64 = values[k]
                        .parse()
                        .map_err(|_| (line, format!("`{}` is not a number", values[k])))?;
                    if !v.is_finite() {
                        return Err((line, format!("coordinate `{}` is not finite", values[k])));
                    }
                    point[k] = v;
                }
            }
        }
        patches.push(BezierPatch { net });
    }
    // A file that holds more than it declares is not what its writer
    // meant: reading the first `count` would drop the rest in silence.
    if let Some((line, _)) = lines.next() {
        return Err((
            line,
            format!("more data after the {count} patch(es) the first line declares"),
        ));
    }
    Ok(patches)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A curved, twisted patch for the submodules' tests.
    pub(crate) fn wavy_patch() -> BezierPatch {
        let mut net = [[Point3::origin(); 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                let (x, y) = (i as f64, j as f64);
                net[i][j] = Point3::new(
                    x + 0.3 * y,
                    y - 0.2 * x,
                    (x * 1.3).sin() + 0.5 * (y * 0.9).cos() + 0.1 * x * y,
                );
            }
        }
        BezierPatch { net }
    }

    fn flat_patch() -> BezierPatch {
        let mut net = [[Point3::origin(); 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                net[i][j] = Point3::new(i as f64, j as f64, 0.0);
            }
        }
        BezierPatch { net }
    }

    #[test]
    fn corners_interpolate_the_net() {
        let p = flat_patch();
        assert_eq!(p.evaluate(0.0, 0.0), Point3::new(0.0, 0.0, 0.0));
        assert_eq!(p.evaluate(1.0, 1.0), Point3::new(3.0, 3.0, 0.0));
        assert_eq!(p.evaluate(0.5, 0.5), Point3::new(1.5, 1.5, 0.0));
    }

    #[test]
    fn collapsed_row_gives_no_zero_area_triangles() {
        let mut p = flat_patch();
        p.net[0] = [Point3::origin(); 4];
        let tris = p.tessellate(4);
        assert_eq!(
            tris.len(),
            2 * 16 - 4,
            "one triangle per quad of the collapsed row is dropped"
        );
        assert!(tris
            .iter()
            .all(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]));
    }

    #[test]
    fn parse_errors_name_the_line() {
        assert_eq!(
            parse_bpt("1\n3 2\n").unwrap_err(),
            (
                2,
                "only bicubic patches (`3 3`) are supported, found `3 2`".into()
            )
        );
        let mut text = String::from("1\n3 3\n");
        for _ in 0..15 {
            text.push_str("0 0 0\n");
        }
        text.push_str("0 nan 0\n");
        assert_eq!(
            parse_bpt(&text).unwrap_err(),
            (18, "coordinate `nan` is not finite".into())
        );
    }

    #[test]
    fn a_file_with_more_patches_than_it_declares_is_refused() {
        let patch = format!("3 3\n{}", "0 0 0\n".repeat(16));
        assert_eq!(parse_bpt(&format!("1\n{patch}")).unwrap().len(), 1);
        assert_eq!(
            parse_bpt(&format!("1\n{patch}{patch}")).unwrap_err(),
            (
                19,
                "more data after the 1 patch(es) the first line declares".into()
            )
        );
    }

    #[test]
    fn a_file_that_is_not_utf8_is_refused_at_its_line() {
        let path = std::env::temp_dir().join(format!("tritri-bpt-{}.bpt", std::process::id()));
        std::fs::write(&path, b"1\n3 3\n0 0 \xff\n").unwrap();
        let e = read_bpt(&path).unwrap_err().to_string();
        std::fs::remove_file(&path).ok();
        assert!(e.ends_with(":3: not UTF-8 text"), "{e}");
    }
}
