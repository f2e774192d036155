//! Triangle meshes read from OBJ, PLY and OFF files.
//!
//! Every reader returns the triangles in file order (polygons are split into
//! fans, so a quad gives two triangles) together with, for each triangle, the
//! index of the face it came from: pairs are reported with those indices.
//! Errors name the file and the line (or, for binary PLY, the element).

mod obj;
mod off;
mod ply;

use crate::triangle::{Point, Triangle};
use std::path::{Path, PathBuf};

/// A triangle soup with the face each triangle came from.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub triangles: Vec<Triangle>,
    /// `face_of[i]` is the index, in the file, of the face triangle `i` was cut from.
    pub face_of: Vec<usize>,
}

/// Why a mesh file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{path}:{line}: {message}")]
    Parse {
        path: PathBuf,
        line: usize,
        message: String,
    },
    #[error("{path}: unknown mesh format (expected .obj, .ply or .off)")]
    UnknownFormat { path: PathBuf },
}

/// A parse error before the path is known; the reader adds it.
#[derive(Debug)]
pub(crate) struct LineError {
    pub line: usize,
    pub message: String,
}

pub(crate) fn line_error(line: usize, message: impl Into<String>) -> LineError {
    LineError {
        line,
        message: message.into(),
    }
}

impl Mesh {
    /// Reads a mesh, choosing the format by the file extension.
    pub fn read(path: &Path) -> Result<Mesh, MeshError> {
        let bytes = std::fs::read(path).map_err(|source| MeshError::Io {
            path: path.to_owned(),
            source,
        })?;
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let parsed = parse_as(ext.as_deref().unwrap_or(""), &bytes).ok_or_else(|| {
            MeshError::UnknownFormat {
                path: path.to_owned(),
            }
        })?;
        parsed.map_err(|e| MeshError::Parse {
            path: path.to_owned(),
            line: e.line,
            message: e.message,
        })
    }

    /// Builds a mesh from vertices and polygons, checking indices and
    /// coordinates; each face's line tells errors where it was. Indices
    /// are 0-based here; errors number them from `first_index`, as the
    /// file does (OBJ counts from 1).
    pub(crate) fn from_polygons(
        vertices: &[Point],
        faces: &[(usize, Vec<usize>)],
        first_index: usize,
    ) -> Result<Mesh, LineError> {
        let mut mesh = Mesh::default();
        for (face_index, (line, polygon)) in faces.iter().enumerate() {
            if polygon.len() < 3 {
                return Err(line_error(
                    *line,
                    format!("face has {} vertices, at least 3 needed", polygon.len()),
                ));
            }
            for &v in polygon {
                if v >= vertices.len() {
                    return Err(line_error(
                        *line,
                        format!(
                            "vertex index {} out of range (the file has {} vertices, numbered from {first_index})",
                            v + first_index,
                            vertices.len()
                        ),
                    ));
                }
            }
            for k in 1..polygon.len() - 1 {
                mesh.triangles.push([
                    vertices[polygon[0]],
                    vertices[polygon[k]],
                    vertices[polygon[k + 1]],
                ]);
                mesh.face_of.push(face_index);
            }
        }
        Ok(mesh)
    }
}

/// Parses `bytes` as the format of `extension` (lower case, no dot);
/// `None` for an extension that names no mesh format.
pub(crate) fn parse_as(extension: &str, bytes: &[u8]) -> Option<Result<Mesh, LineError>> {
    match extension {
        "obj" => Some(obj::parse(bytes)),
        "off" => Some(off::parse(bytes)),
        "ply" => Some(ply::parse(bytes)),
        _ => None,
    }
}

/// Parses a finite f64, with a message that names the text.
pub(crate) fn parse_coordinate(text: &str, line: usize) -> Result<f64, LineError> {
    let v: f64 = text
        .parse()
        .map_err(|_| line_error(line, format!("`{text}` is not a number")))?;
    if !v.is_finite() {
        return Err(line_error(
            line,
            format!("coordinate `{text}` is not finite"),
        ));
    }
    Ok(v)
}

/// Iterates over text lines with 1-based line numbers, without comments.
pub(crate) fn numbered_lines(text: &str, comment: char) -> impl Iterator<Item = (usize, &str)> {
    text.lines().enumerate().filter_map(move |(i, l)| {
        let l = l.split(comment).next().unwrap_or("").trim();
        (!l.is_empty()).then_some((i + 1, l))
    })
}

#[cfg(test)]
mod tests;
