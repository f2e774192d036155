//! OFF (Object File Format): an `OFF` header line, then `nv nf ne`, `nv`
//! vertex lines and `nf` face lines `k i1 ... ik` (0-based). Also accepts the
//! counts on the header line (`OFF nv nf ne`) and ignores `#` comments and
//! per-face colours.

use super::{line_error, numbered_lines, parse_coordinate, LineError, Mesh};

pub(crate) fn parse(bytes: &[u8]) -> Result<Mesh, LineError> {
    let text = std::str::from_utf8(bytes).map_err(|_| line_error(1, "not UTF-8 text"))?;
    let mut lines = numbered_lines(text, '#');
    let (line, header) = lines
        .next()
        .ok_or_else(|| line_error(1, "empty file, expected `OFF`"))?;
    let rest = header
        .strip_prefix("OFF")
        .ok_or_else(|| line_error(line, format!("expected `OFF`, found `{header}`")))?;
    let (counts_line, counts) = if rest.trim().is_empty() {
        lines
            .next()
            .ok_or_else(|| line_error(line + 1, "missing `vertices faces edges` counts"))?
    } else {
        (line, rest)
    };
    let count = |field: Option<&str>, what: &str| -> Result<usize, LineError> {
        field
            .ok_or_else(|| line_error(counts_line, format!("missing {what} count")))?
            .parse()
            .map_err(|_| {
                line_error(
                    counts_line,
                    format!("{what} count is not a non-negative integer"),
                )
            })
    };
    let mut fields = counts.split_whitespace();
    let vertex_count = count(fields.next(), "vertex")?;
    let face_count = count(fields.next(), "face")?;

    let mut vertices = Vec::with_capacity(vertex_count.min(1 << 24));
    for _ in 0..vertex_count {
        let (line, content) = lines.next().ok_or_else(|| {
            line_error(
                counts_line,
                format!(
                    "file ends after {} of {vertex_count} vertices",
                    vertices.len()
                ),
            )
        })?;
        let xyz: Vec<&str> = content.split_whitespace().collect();
        if xyz.len() < 3 {
            return Err(line_error(
                line,
                format!("vertex has {} numbers, expected 3", xyz.len()),
            ));
        }
        vertices.push([
            parse_coordinate(xyz[0], line)?,
            parse_coordinate(xyz[1], line)?,
            parse_coordinate(xyz[2], line)?,
        ]);
    }
    let mut faces = Vec::with_capacity(face_count.min(1 << 24));
    for _ in 0..face_count {
        let (line, content) = lines.next().ok_or_else(|| {
            line_error(
                counts_line,
                format!("file ends after {} of {face_count} faces", faces.len()),
            )
        })?;
        let mut fields = content.split_whitespace();
        let k: usize = fields
            .next()
            .and_then(|f| f.parse().ok())
            .ok_or_else(|| line_error(line, "face must start with its vertex count"))?;
        let polygon: Result<Vec<usize>, LineError> = (0..k)
            .map(|_| {
                fields
                    .next()
                    .ok_or_else(|| {
                        line_error(line, format!("face announces {k} vertices but has fewer"))
                    })?
                    .parse()
                    .map_err(|_| {
                        line_error(line, "face vertex index is not a non-negative integer")
                    })
            })
            .collect();
        // A bad index is told as that, before what follows it.
        let polygon = polygon?;
        // What may follow the indices is a colour: a colour-map index, or
        // 3 or 4 components. Anything else is not OFF, and dropping it in
        // silence could hide a face written wrong.
        let colour: Vec<&str> = fields.collect();
        if !matches!(colour.len(), 0 | 1 | 3 | 4)
            || colour.iter().any(|c| c.parse::<f64>().is_err())
        {
            return Err(line_error(
                line,
                format!(
                    "`{}` after the face's {k} vertex indices is not a colour (1, 3 or 4 numbers)",
                    colour.join(" ")
                ),
            ));
        }
        faces.push((line, polygon));
    }
    if let Some((line, _)) = lines.next() {
        return Err(line_error(
            line,
            format!("more lines after the {face_count} faces the counts declare"),
        ));
    }
    Mesh::from_polygons(&vertices, &faces, 0)
}
