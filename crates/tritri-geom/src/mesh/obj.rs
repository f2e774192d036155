//! Wavefront OBJ: `v x y z [w]` vertices and `f a b c ...` faces, where a
//! corner may be `v`, `v/vt`, `v//vn` or `v/vt/vn` and negative indices count
//! back from the last vertex read. Everything else is ignored.

use super::{line_error, numbered_lines, parse_coordinate, LineError, Mesh};

pub(crate) fn parse(bytes: &[u8]) -> Result<Mesh, LineError> {
    let text = crate::text::utf8_text(bytes).map_err(|line| line_error(line, "not UTF-8 text"))?;
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for (line, content) in numbered_lines(text, '#') {
        let mut fields = content.split_whitespace();
        match fields.next() {
            Some("v") => {
                let xyz: Vec<&str> = fields.collect();
                if xyz.len() < 3 || xyz.len() > 4 {
                    return Err(line_error(
                        line,
                        format!("vertex has {} numbers, expected 3 (or 4 with w)", xyz.len()),
                    ));
                }
                let mut p = [0.0; 3];
                for k in 0..3 {
                    p[k] = parse_coordinate(xyz[k], line)?;
                }
                vertices.push(p);
            }
            Some("f") => {
                let mut polygon = Vec::new();
                for corner in fields {
                    let index_text = corner.split('/').next().unwrap_or("");
                    let index: i64 = index_text.parse().map_err(|_| {
                        line_error(
                            line,
                            format!("face corner `{corner}` is not a vertex index"),
                        )
                    })?;
                    let resolved = match index {
                        0 => {
                            return Err(line_error(line, "vertex index 0 (OBJ indices start at 1)"))
                        }
                        i if i > 0 => (i - 1) as usize,
                        i => {
                            let back = i.unsigned_abs() as usize;
                            if back > vertices.len() {
                                return Err(line_error(
                                    line,
                                    format!(
                                        "relative vertex index {i} reaches before the first vertex"
                                    ),
                                ));
                            }
                            vertices.len() - back
                        }
                    };
                    polygon.push(resolved);
                }
                faces.push((line, polygon));
            }
            _ => {}
        }
    }
    Mesh::from_polygons(&vertices, &faces, 1)
}
