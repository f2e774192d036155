//! PLY (Stanford polygon format), ASCII and binary (little or big endian).
//! Reads the `x y z` properties of `vertex` and the index list of `face`
//! (`vertex_indices` or `vertex_index`); other elements and properties are
//! skipped. Errors in the binary body name the element and its index.

use super::{line_error, parse_coordinate, LineError, Mesh};

#[derive(Clone, Copy, Debug, PartialEq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }
    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }
}

#[derive(Clone, Debug)]
enum Property {
    Scalar {
        name: String,
        ty: Scalar,
    },
    List {
        name: String,
        count: Scalar,
        item: Scalar,
    },
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: usize,
    properties: Vec<Property>,
}

#[derive(Clone, Copy, PartialEq)]
enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

pub(crate) fn parse(bytes: &[u8]) -> Result<Mesh, LineError> {
    let (elements, encoding, body_start, header_lines) = parse_header(bytes)?;
    let mut reader: Box<dyn ValueReader> = match encoding {
        Encoding::Ascii => Box::new(AsciiReader::new(&bytes[body_start..], header_lines)?),
        Encoding::LittleEndian => Box::new(BinaryReader {
            bytes: &bytes[body_start..],
            at: 0,
            big_endian: false,
            line: header_lines,
        }),
        Encoding::BigEndian => Box::new(BinaryReader {
            bytes: &bytes[body_start..],
            at: 0,
            big_endian: true,
            line: header_lines,
        }),
    };
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for element in &elements {
        for index in 0..element.count {
            let context = |e: LineError| {
                line_error(e.line, format!("{} {index}: {}", element.name, e.message))
            };
            reader.start_record().map_err(context)?;
            let line = reader.line();
            let mut xyz = [None; 3];
            let mut polygon = None;
            for property in &element.properties {
                match property {
                    Property::Scalar { name, ty } => {
                        let v = reader.read(*ty).map_err(context)?;
                        if element.name == "vertex" {
                            if let Some(k) = ["x", "y", "z"].iter().position(|c| c == name) {
                                xyz[k] = Some(v);
                            }
                        }
                    }
                    Property::List { name, count, item } => {
                        let n = reader.read(*count).map_err(context)?;
                        let left = reader.values_left(*item);
                        if n < 0.0 || n.fract() != 0.0 {
                            let why =
                                format!("list `{name}`: length {n} is not a non-negative integer");
                            return Err(context(line_error(line, why)));
                        }
                        if n > left as f64 {
                            let why = format!("list `{name}` claims {n} items, but the file holds at most {left} more");
                            return Err(context(line_error(line, why)));
                        }
                        let mut items = Vec::with_capacity(n as usize);
                        for _ in 0..n as usize {
                            items.push(reader.read(*item).map_err(context)?);
                        }
                        if element.name == "face"
                            && (name == "vertex_indices" || name == "vertex_index")
                        {
                            let mut ids = Vec::with_capacity(items.len());
                            for v in items {
                                if v < 0.0 || v.fract() != 0.0 {
                                    return Err(line_error(line, format!("face {index}: vertex index {v} is not a non-negative integer")));
                                }
                                ids.push(v as usize);
                            }
                            polygon = Some(ids);
                        }
                    }
                }
            }
            if element.name == "vertex" {
                let p = [0, 1, 2].map(|k| xyz[k]);
                match p {
                    [Some(x), Some(y), Some(z)] => {
                        for v in [x, y, z] {
                            if !v.is_finite() {
                                return Err(line_error(
                                    line,
                                    format!("vertex {index}: coordinate {v} is not finite"),
                                ));
                            }
                        }
                        vertices.push([x, y, z])
                    }
                    _ => {
                        return Err(line_error(
                            line,
                            "vertex element lacks an x, y or z property",
                        ))
                    }
                }
            } else if element.name == "face" {
                let polygon = polygon
                    .ok_or_else(|| line_error(line, "face element lacks a vertex_indices list"))?;
                faces.push((line, polygon));
            }
        }
    }
    reader.finish()?;
    Mesh::from_polygons(&vertices, &faces, 0)
}

/// Returns the elements, the encoding, where the body starts and how many
/// lines the header has.
fn parse_header(bytes: &[u8]) -> Result<(Vec<Element>, Encoding, usize, usize), LineError> {
    let mut at = 0;
    let mut line = 0;
    let mut elements: Vec<Element> = Vec::new();
    let mut encoding = None;
    loop {
        let end = bytes[at..]
            .iter()
            .position(|&b| b == b'\n')
            .ok_or_else(|| line_error(line + 1, "header does not end with `end_header`"))?;
        let text = std::str::from_utf8(&bytes[at..at + end])
            .map_err(|_| line_error(line + 1, "header is not text"))?
            .trim();
        at += end + 1;
        line += 1;
        let fields: Vec<&str> = text.split_whitespace().collect();
        match fields.as_slice() {
            ["ply"] if line == 1 => {}
            _ if line == 1 => {
                return Err(line_error(
                    1,
                    "not a PLY file: the first line must be `ply`",
                ))
            }
            ["format", format, _version] => {
                encoding = Some(match *format {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::LittleEndian,
                    "binary_big_endian" => Encoding::BigEndian,
                    other => return Err(line_error(line, format!("unknown PLY format `{other}`"))),
                })
            }
            ["comment", ..] | ["obj_info", ..] | [] => {}
            ["element", name, count] => elements.push(Element {
                name: name.to_string(),
                count: count.parse().map_err(|_| {
                    line_error(line, format!("element count `{count}` is not an integer"))
                })?,
                properties: Vec::new(),
            }),
            ["property", "list", count, item, name] => {
                let ty = |t: &str| {
                    Scalar::parse(t)
                        .ok_or_else(|| line_error(line, format!("unknown property type `{t}`")))
                };
                let property = Property::List {
                    name: name.to_string(),
                    count: ty(count)?,
                    item: ty(item)?,
                };
                elements
                    .last_mut()
                    .ok_or_else(|| line_error(line, "property before any element"))?
                    .properties
                    .push(property);
            }
            ["property", ty, name] => {
                let ty = Scalar::parse(ty)
                    .ok_or_else(|| line_error(line, format!("unknown property type `{ty}`")))?;
                let property = Property::Scalar {
                    name: name.to_string(),
                    ty,
                };
                elements
                    .last_mut()
                    .ok_or_else(|| line_error(line, "property before any element"))?
                    .properties
                    .push(property);
            }
            ["end_header"] => break,
            _ => return Err(line_error(line, format!("unexpected header line `{text}`"))),
        }
    }
    let encoding = encoding.ok_or_else(|| line_error(line, "header has no `format` line"))?;
    Ok((elements, encoding, at, line))
}

trait ValueReader {
    /// Called before each element record (ASCII moves to the next line).
    fn start_record(&mut self) -> Result<(), LineError>;
    fn read(&mut self, ty: Scalar) -> Result<f64, LineError>;
    fn line(&self) -> usize;
    /// How many more values of `ty` the record can hold at most: a list's
    /// length is checked against it before anything is allocated, so a
    /// file that claims 4294967295 items fails with an error, not an abort.
    fn values_left(&self, ty: Scalar) -> usize;
    /// After the last element: nothing may be left. Faces beyond the
    /// declared count would otherwise be dropped in silence.
    fn finish(&mut self) -> Result<(), LineError>;
}

struct AsciiReader<'a> {
    lines: std::iter::Peekable<std::iter::Enumerate<std::str::Lines<'a>>>,
    fields: Vec<&'a str>,
    next_field: usize,
    first_line: usize,
    line: usize,
}

impl<'a> AsciiReader<'a> {
    fn new(body: &'a [u8], header_lines: usize) -> Result<Self, LineError> {
        let text = std::str::from_utf8(body)
            .map_err(|_| line_error(header_lines + 1, "ASCII body is not text"))?;
        Ok(AsciiReader {
            lines: text.lines().enumerate().peekable(),
            fields: Vec::new(),
            next_field: 0,
            first_line: header_lines + 1,
            line: header_lines,
        })
    }
}

impl AsciiReader<'_> {
    /// A record's line holds its values and no more.
    fn line_used_up(&self) -> Result<(), LineError> {
        if self.next_field < self.fields.len() {
            return Err(line_error(
                self.line,
                format!(
                    "{} extra values on the line",
                    self.fields.len() - self.next_field
                ),
            ));
        }
        Ok(())
    }
}

impl ValueReader for AsciiReader<'_> {
    fn start_record(&mut self) -> Result<(), LineError> {
        self.line_used_up()?;
        loop {
            let (i, l) = self.lines.next().ok_or_else(|| {
                line_error(self.line + 1, "file ends before all elements are read")
            })?;
            self.line = self.first_line + i;
            let l = l.trim();
            if !l.is_empty() && !l.starts_with("comment") {
                self.fields = l.split_whitespace().collect();
                self.next_field = 0;
                return Ok(());
            }
        }
    }
    fn read(&mut self, _ty: Scalar) -> Result<f64, LineError> {
        let text = self
            .fields
            .get(self.next_field)
            .ok_or_else(|| line_error(self.line, "too few values on the line"))?;
        self.next_field += 1;
        let v: f64 = text
            .parse()
            .map_err(|_| line_error(self.line, format!("`{text}` is not a number")))?;
        if v.is_nan() || v.is_infinite() {
            // Reported by the caller for coordinates; reject everywhere else too.
            return parse_coordinate(text, self.line);
        }
        Ok(v)
    }
    fn line(&self) -> usize {
        self.line
    }
    fn values_left(&self, _ty: Scalar) -> usize {
        self.fields.len() - self.next_field
    }
    fn finish(&mut self) -> Result<(), LineError> {
        // The last record's line must be used up, like every other's.
        self.line_used_up()?;
        for (i, l) in self.lines.by_ref() {
            let l = l.trim();
            if !l.is_empty() && !l.starts_with("comment") {
                return Err(line_error(
                    self.first_line + i,
                    "more data after the elements the header declares",
                ));
            }
        }
        Ok(())
    }
}

struct BinaryReader<'a> {
    bytes: &'a [u8],
    at: usize,
    big_endian: bool,
    /// Binary bodies have no lines: errors point at the end of the header.
    line: usize,
}

impl ValueReader for BinaryReader<'_> {
    fn values_left(&self, ty: Scalar) -> usize {
        (self.bytes.len() - self.at) / ty.size()
    }
    fn finish(&mut self) -> Result<(), LineError> {
        let left = self.bytes.len() - self.at;
        if left == 0 {
            Ok(())
        } else {
            Err(line_error(
                self.line,
                format!("{left} bytes after the elements the header declares"),
            ))
        }
    }
    fn start_record(&mut self) -> Result<(), LineError> {
        Ok(())
    }
    fn read(&mut self, ty: Scalar) -> Result<f64, LineError> {
        let n = ty.size();
        let raw = self.bytes.get(self.at..self.at + n).ok_or_else(|| {
            line_error(
                self.line,
                format!("binary body ends at byte {} of the body", self.bytes.len()),
            )
        })?;
        self.at += n;
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(raw);
        if self.big_endian {
            b[..n].reverse();
        }
        Ok(match ty {
            Scalar::I8 => b[0] as i8 as f64,
            Scalar::U8 => b[0] as f64,
            Scalar::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F64 => f64::from_le_bytes(b),
        })
    }
    fn line(&self) -> usize {
        self.line
    }
}
