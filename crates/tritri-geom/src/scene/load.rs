//! Loading the two objects of a scene and posing object B.
//!
//! An object is named by a string:
//!
//! * a path ending in `.obj`, `.ply` or `.off`: read with [`Mesh::read`];
//! * a path ending in `.bpt`: bicubic Bezier patches, each tessellated into
//!   `2 n^2` triangles at the level `n` given to [`load_object`] (triangles
//!   with two coincident vertices are left out, see [`BezierPatch::tessellate`]);
//! * `@torus` or `@sphere`: the two objects of the built-in default scene
//!   ([`crate::builtin_scene::default_scene`]); `@default` is the torus.
//!
//! **Triangle indices.** Pairs are reported with the index of the triangle
//! in the object's triangle list: the file's faces in file order, each
//! polygon split into a fan (a quad gives two triangles, so indices are
//! *triangles*, not faces; for an all-triangle file they coincide with face
//! indices). [`SceneObject::face_of`] maps a triangle back to its face (for
//! `.bpt`, to its patch).

use crate::bezier::{read_bpt, BptError};
use crate::builtin_scene;
use crate::mesh::{Mesh, MeshError};
use crate::triangle::{Point, Triangle};
use nalgebra::{IsometryMatrix3, Matrix3, Point3, Rotation3, Translation3, Vector3};
use std::fmt;
use std::path::Path;
use std::str::FromStr;

/// One object of a scene: its triangles, and the face each came from.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneObject {
    /// What the user named (a path or `@torus`).
    pub name: String,
    pub triangles: Vec<Triangle>,
    /// `face_of[i]`: the face (or Bezier patch) triangle `i` was cut from.
    pub face_of: Vec<usize>,
}

/// Why an object could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    #[error(transparent)]
    Mesh(#[from] MeshError),
    #[error(transparent)]
    Bezier(#[from] BptError),
    #[error("unknown built-in object `{0}`: expected @torus, @sphere or @default")]
    UnknownBuiltin(String),
    #[error("{name}: has {count} triangles, more than the 2^32 that triangle ids can name")]
    TooManyTriangles { name: String, count: usize },
    #[error("{0}: has no triangles (an empty mesh collides with nothing; check the file)")]
    Empty(String),
}

impl SceneObject {
    pub fn from_triangles(name: impl Into<String>, triangles: Vec<Triangle>) -> SceneObject {
        let face_of = (0..triangles.len()).collect();
        SceneObject {
            name: name.into(),
            triangles,
            face_of,
        }
    }

    /// The same object scaled by `factor` about its origin.
    pub fn scaled(&self, factor: f64) -> SceneObject {
        let triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|p| p.map(|c| c * factor)))
            .collect();
        SceneObject {
            name: self.name.clone(),
            triangles,
            face_of: self.face_of.clone(),
        }
    }

    /// The same surface cut into `4^levels` times as many triangles: each
    /// triangle into four by its edge midpoints, `levels` times (a face
    /// index still names the original face). For scaling studies: the
    /// geometry, and so the contact, stays the same.
    pub fn subdivided(&self, levels: u32) -> SceneObject {
        let mut triangles = self.triangles.clone();
        let mut face_of = self.face_of.clone();
        for _ in 0..levels {
            let mid = |p: Point, q: Point| [0, 1, 2].map(|k| (p[k] + q[k]) / 2.0);
            triangles = triangles
                .iter()
                .flat_map(|&[a, b, c]| {
                    let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
                    [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
                })
                .collect();
            face_of = face_of.iter().flat_map(|&f| [f; 4]).collect();
        }
        SceneObject {
            name: self.name.clone(),
            triangles,
            face_of,
        }
    }

    /// The same object moved by `pose`.
    pub fn posed(&self, pose: &Pose) -> SceneObject {
        let motion = pose.isometry();
        let triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|p| motion.transform_point(&Point3::from(p)).coords.into()))
            .collect();
        SceneObject {
            name: self.name.clone(),
            triangles,
            face_of: self.face_of.clone(),
        }
    }
}

/// Loads an object named as in the module documentation; `.bpt` patches are
/// tessellated at level `bezier_level`.
pub fn load_object(spec: &str, bezier_level: usize) -> Result<SceneObject, LoadError> {
    let object = if let Some(builtin) = spec.strip_prefix('@') {
        let (torus, sphere) = builtin_scene::default_scene();
        match builtin.to_ascii_lowercase().as_str() {
            "torus" | "default" | "default-a" => SceneObject::from_triangles(spec, torus),
            "sphere" | "default-b" => SceneObject::from_triangles(spec, sphere),
            _ => return Err(LoadError::UnknownBuiltin(spec.to_string())),
        }
    } else {
        let path = Path::new(spec);
        let is_bpt = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("bpt"));
        if is_bpt {
            let mut object = SceneObject {
                name: spec.to_string(),
                triangles: Vec::new(),
                face_of: Vec::new(),
            };
            for (index, patch) in read_bpt(path)?.iter().enumerate() {
                let ts = patch.tessellate(bezier_level);
                object.face_of.extend(std::iter::repeat_n(index, ts.len()));
                object.triangles.extend(ts);
            }
            object
        } else {
            let Mesh { triangles, face_of } = Mesh::read(path)?;
            SceneObject {
                name: spec.to_string(),
                triangles,
                face_of,
            }
        }
    };
    if object.triangles.is_empty() {
        return Err(LoadError::Empty(object.name));
    }
    if u32::try_from(object.triangles.len()).is_err() {
        return Err(LoadError::TooManyTriangles {
            name: object.name,
            count: object.triangles.len(),
        });
    }
    Ok(object)
}

/// A rigid motion of object B: `p' = Rz(rz) · Ry(ry) · Rx(rx) · p + t`.
///
/// The rotations are in degrees about the fixed x, y and z axes through the
/// origin of B's own coordinates, applied in that order (x first), then the
/// translation. Multiples of 90 degrees use exact sines and cosines, so a
/// quarter turn moves grid-aligned geometry exactly.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pose {
    pub translation: [f64; 3],
    pub rotation_degrees: [f64; 3],
}

/// Error for a pose that is not `tx,ty,tz[,rx,ry,rz]`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "bad pose `{text}`: {reason} (expected tx,ty,tz or tx,ty,tz,rx,ry,rz, rotations in degrees)"
)]
pub struct PoseError {
    pub text: String,
    pub reason: String,
}

impl Pose {
    pub fn translation(t: [f64; 3]) -> Pose {
        Pose {
            translation: t,
            rotation_degrees: [0.0; 3],
        }
    }

    pub fn is_identity(&self) -> bool {
        self.translation == [0.0; 3] && self.rotation_degrees == [0.0; 3]
    }

    /// The rigid motion: rotation `Rz · Ry · Rx` (fixed axes: about x
    /// first), then the translation. The rotation is kept as a matrix, not
    /// a quaternion, so that quarter turns stay exact.
    pub fn isometry(&self) -> IsometryMatrix3<f64> {
        let [(sx, cx), (sy, cy), (sz, cz)] = self.rotation_degrees.map(sin_cos_degrees);
        let rx = Matrix3::new(1.0, 0.0, 0.0, 0.0, cx, -sx, 0.0, sx, cx);
        let ry = Matrix3::new(cy, 0.0, sy, 0.0, 1.0, 0.0, -sy, 0.0, cy);
        let rz = Matrix3::new(cz, -sz, 0.0, sz, cz, 0.0, 0.0, 0.0, 1.0);
        let rotation = Rotation3::from_matrix_unchecked(rz * ry * rx);
        IsometryMatrix3::from_parts(
            Translation3::from(Vector3::from(self.translation)),
            rotation,
        )
    }

    /// The posed point.
    pub fn apply(&self, p: Point) -> Point {
        self.isometry()
            .transform_point(&Point3::from(p))
            .coords
            .into()
    }
}

/// `(sin, cos)` of an angle in degrees, exact at multiples of 90.
fn sin_cos_degrees(deg: f64) -> (f64, f64) {
    let quarter = deg / 90.0;
    if quarter == quarter.round() {
        match (quarter.round() as i64).rem_euclid(4) {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        }
    } else {
        deg.to_radians().sin_cos()
    }
}

impl FromStr for Pose {
    type Err = PoseError;

    /// `tx,ty,tz` or `tx,ty,tz,rx,ry,rz` (commas or spaces).
    fn from_str(s: &str) -> Result<Pose, PoseError> {
        let err = |reason: String| PoseError {
            text: s.to_string(),
            reason,
        };
        let fields: Vec<&str> = s
            .split([',', ' '])
            .map(str::trim)
            .filter(|f| !f.is_empty())
            .collect();
        if fields.len() != 3 && fields.len() != 6 {
            return Err(err(format!("{} numbers", fields.len())));
        }
        let mut values = [0.0f64; 6];
        for (v, f) in values.iter_mut().zip(&fields) {
            *v = f
                .parse()
                .map_err(|_| err(format!("`{f}` is not a number")))?;
            if !v.is_finite() {
                return Err(err(format!("`{f}` is not finite")));
            }
        }
        Ok(Pose {
            translation: [values[0], values[1], values[2]],
            rotation_degrees: [values[3], values[4], values[5]],
        })
    }
}

impl fmt::Display for Pose {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [tx, ty, tz] = self.translation;
        let [rx, ry, rz] = self.rotation_degrees;
        write!(f, "{tx},{ty},{tz},{rx},{ry},{rz}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pose_parses_three_or_six_numbers_and_names_bad_input() {
        assert_eq!("1,2,3".parse(), Ok(Pose::translation([1.0, 2.0, 3.0])));
        let p: Pose = "0, 0, 0, 90, 0, 0".parse().unwrap();
        assert_eq!(p.rotation_degrees, [90.0, 0.0, 0.0]);
        let e = "1,2".parse::<Pose>().unwrap_err();
        assert!(e.to_string().contains("2 numbers"), "{e}");
        let e = "1,2,x".parse::<Pose>().unwrap_err();
        assert!(e.to_string().contains("`x` is not a number"), "{e}");
        assert!("1,2,inf".parse::<Pose>().is_err());
    }

    /// Rotations are about x, then y, then z (fixed axes), then the translation.
    #[test]
    fn pose_rotates_x_then_y_then_z_then_translates() {
        let quarter_x = Pose {
            translation: [0.0; 3],
            rotation_degrees: [90.0, 0.0, 0.0],
        };
        assert_eq!(quarter_x.apply([0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]);
        // x then z: (0,1,0) -x-> (0,0,1) -z-> (0,0,1); z then x would give (0,0,-1)... order matters.
        let xz = Pose {
            translation: [10.0, 0.0, 0.0],
            rotation_degrees: [90.0, 0.0, 90.0],
        };
        assert_eq!(xz.apply([1.0, 0.0, 0.0]), [10.0, 1.0, 0.0]);
        assert_eq!(xz.apply([0.0, 1.0, 0.0]), [10.0, 0.0, 1.0]);
        let xy = Pose {
            translation: [0.0; 3],
            rotation_degrees: [90.0, 90.0, 0.0],
        };
        // (0,1,0) -x-> (0,0,1) -y-> (1,0,0)
        assert_eq!(xy.apply([0.0, 1.0, 0.0]), [1.0, 0.0, 0.0]);
        let general = Pose {
            translation: [0.0; 3],
            rotation_degrees: [30.0, 0.0, 0.0],
        };
        let q = general.apply([0.0, 1.0, 0.0]);
        assert!((q[1] - 30f64.to_radians().cos()).abs() < 1e-15 && (q[2] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn builtins_and_unknown_builtins() {
        assert_eq!(
            load_object("@torus", 4).unwrap().triangles.len(),
            2 * 48 * 24
        );
        assert_eq!(
            load_object("@sphere", 4).unwrap().triangles.len(),
            2 * 32 * 15
        );
        assert!(matches!(
            load_object("@cube", 4),
            Err(LoadError::UnknownBuiltin(_))
        ));
    }
}
