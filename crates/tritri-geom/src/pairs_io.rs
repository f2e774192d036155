//! Reading triangle pairs from a file.
//!
//! Two formats, told apart by the first non-space character:
//!
//! * `[`: a JSON array of objects, each with `t1` and `t2` (three vertices of
//!   three numbers each); other fields are ignored (the format of
//!   `peer_cases.json`);
//! * anything else: text, one pair per line as 18 whitespace-separated
//!   numbers (`x y z` of t1's three vertices, then t2's; the Shen format).
//!   Blank lines and lines whose first non-space character is `#` are
//!   skipped.
//!
//! Rules:
//!
//! * Parsing yields one [`Record`] per pair in file order, each either a
//!   pair or a [`RecordError`] naming the file, the line (and for JSON the
//!   array index). A bad record does not stop the others: callers print the
//!   verdicts of all good pairs and the errors of the bad ones, and fail at
//!   the end (the `tritri` CLI exits with status 2).
//! * Coordinates must be finite: `nan`, `inf` and overflowing literals such
//!   as `1e999` are errors (JSON itself has no NaN or infinity).
//! * Errors that leave no record to speak of (unreadable file, malformed
//!   JSON, a JSON document that is not an array) are a [`FileError`].
//!
//! ```
//! use tritri_geom::pairs_io::parse_pairs;
//! let text = "# two pairs, the second has 17 numbers\n\
//!             0 0 0 1 0 0 0 1 0  0 0 0 0 0 1 1 1 1\n\
//!             0 0 0 1 0 0 0 1 0  0 0 0 0 0 1 1 1\n";
//! let records = parse_pairs("pairs.txt", text).unwrap();
//! assert!(records[0].pair.is_ok());
//! let err = records[1].pair.as_ref().unwrap_err();
//! assert_eq!(err.to_string(), "pairs.txt:3: expected 18 numbers (x y z of 6 vertices), found 17");
//! ```

use crate::triangle::{Triangle, TrianglePair};
use serde_json::Value;
use std::fmt;
use std::path::Path;

/// Where a record is in its file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The file as the user named it.
    pub file: String,
    /// 1-based line (for JSON, the line where the array element starts).
    pub line: usize,
    /// For JSON: the 0-based index in the top-level array.
    pub index: Option<usize>,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.file, self.line)?;
        if let Some(i) = self.index {
            write!(f, ": element [{i}]")?;
        }
        Ok(())
    }
}

/// What is wrong with one record.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RecordErrorKind {
    #[error("expected 18 numbers (x y z of 6 vertices), found {found}")]
    WrongCount { found: usize },
    #[error("number {position} `{token}` is not a number")]
    NotANumber { position: usize, token: String },
    #[error("number {position} `{token}` is not finite")]
    NotFinite { position: usize, token: String },
    #[error("not an object with fields `t1` and `t2`")]
    NotAnObject,
    #[error("missing field `{field}`")]
    MissingField { field: &'static str },
    #[error("`{field}` must be 3 vertices of 3 numbers each: {problem}")]
    BadTriangle {
        field: &'static str,
        problem: String,
    },
}

/// One bad record: where and what.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{location}: {kind}")]
pub struct RecordError {
    pub location: Location,
    pub kind: RecordErrorKind,
}

/// A record of the file: a pair, or why there is none.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    pub location: Location,
    pub pair: Result<TrianglePair, RecordError>,
}

/// An error about the file as a whole: no records can be read from it.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    #[error("{file}: cannot read: {source}")]
    Io {
        file: String,
        source: std::io::Error,
    },
    #[error("{file}:{line}:{column}: malformed JSON: {message}")]
    MalformedJson {
        file: String,
        line: usize,
        column: usize,
        message: String,
    },
    #[error("{file}: the JSON document must be an array of objects with `t1` and `t2`")]
    NotAnArray { file: String },
    #[error("{file}:{line}: not UTF-8 text")]
    NotText { file: String, line: usize },
}

/// The records of one file.
#[derive(Clone, Debug, PartialEq)]
pub struct PairsFile {
    pub file: String,
    pub records: Vec<Record>,
}

impl PairsFile {
    /// The pairs that were read, in file order.
    pub fn good_pairs(&self) -> Vec<TrianglePair> {
        self.records
            .iter()
            .filter_map(|r| r.pair.as_ref().ok().copied())
            .collect()
    }

    /// The records that could not be read, in file order.
    pub fn errors(&self) -> impl Iterator<Item = &RecordError> {
        self.records.iter().filter_map(|r| r.pair.as_ref().err())
    }
}

/// Reads and parses `path`; the file is named in errors as given.
pub fn read_pairs(path: impl AsRef<Path>) -> Result<PairsFile, FileError> {
    let path = path.as_ref();
    let file = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| FileError::Io {
        file: file.clone(),
        source,
    })?;
    let text = crate::text::utf8_text(&bytes).map_err(|line| FileError::NotText {
        file: file.clone(),
        line,
    })?;
    let records = parse_pairs(&file, text)?;
    Ok(PairsFile { file, records })
}

/// Parses the text of a file named `file` (used in error messages).
pub fn parse_pairs(file: &str, text: &str) -> Result<Vec<Record>, FileError> {
    // A JSON document of any other shape (an object, say) is told as
    // JSON, not as a text line whose first "number" is a brace.
    if text.trim_start().starts_with(['[', '{']) {
        parse_json(file, text)
    } else {
        Ok(parse_text(file, text))
    }
}

fn parse_text(file: &str, text: &str) -> Vec<Record> {
    let mut records = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        let location = Location {
            file: file.to_string(),
            line: i + 1,
            index: None,
        };
        let pair = parse_text_line(trimmed).map_err(|kind| RecordError {
            location: location.clone(),
            kind,
        });
        records.push(Record { location, pair });
    }
    records
}

fn parse_text_line(line: &str) -> Result<TrianglePair, RecordErrorKind> {
    let tokens: Vec<&str> = line.split_whitespace().collect();
    let mut values = [0.0f64; 18];
    // Report a bad token before a bad count: "1 2 x" is better told as `x`.
    for (k, token) in tokens.iter().enumerate() {
        let position = k + 1;
        let v: f64 = token.parse().map_err(|_| RecordErrorKind::NotANumber {
            position,
            token: token.to_string(),
        })?;
        if !v.is_finite() {
            return Err(RecordErrorKind::NotFinite {
                position,
                token: token.to_string(),
            });
        }
        if k < 18 {
            values[k] = v;
        }
    }
    if tokens.len() != 18 {
        return Err(RecordErrorKind::WrongCount {
            found: tokens.len(),
        });
    }
    let point = |k: usize| [values[3 * k], values[3 * k + 1], values[3 * k + 2]];
    Ok(TrianglePair::new(
        [point(0), point(1), point(2)],
        [point(3), point(4), point(5)],
    ))
}

fn parse_json(file: &str, text: &str) -> Result<Vec<Record>, FileError> {
    let doc: Value = serde_json::from_str(text).map_err(|e| FileError::MalformedJson {
        file: file.to_string(),
        line: e.line(),
        column: e.column(),
        message: strip_position(&e.to_string()),
    })?;
    let Value::Array(items) = doc else {
        return Err(FileError::NotAnArray {
            file: file.to_string(),
        });
    };
    let lines = top_level_element_lines(text);
    Ok(items
        .iter()
        .enumerate()
        .map(|(i, item)| {
            let location = Location {
                file: file.to_string(),
                line: lines.get(i).copied().unwrap_or(1),
                index: Some(i),
            };
            let pair = json_pair(item).map_err(|kind| RecordError {
                location: location.clone(),
                kind,
            });
            Record { location, pair }
        })
        .collect())
}

/// serde_json appends " at line L column C"; the message carries them already.
fn strip_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(k) => message[..k].to_string(),
        None => message.to_string(),
    }
}

fn json_pair(item: &Value) -> Result<TrianglePair, RecordErrorKind> {
    let Value::Object(map) = item else {
        return Err(RecordErrorKind::NotAnObject);
    };
    let triangle = |field: &'static str| -> Result<Triangle, RecordErrorKind> {
        let v = map
            .get(field)
            .ok_or(RecordErrorKind::MissingField { field })?;
        json_triangle(v).map_err(|problem| RecordErrorKind::BadTriangle { field, problem })
    };
    Ok(TrianglePair::new(triangle("t1")?, triangle("t2")?))
}

fn json_triangle(v: &Value) -> Result<Triangle, String> {
    let vertices = v
        .as_array()
        .ok_or_else(|| format!("found {}", describe(v)))?;
    if vertices.len() != 3 {
        return Err(format!("found {} vertices", vertices.len()));
    }
    let mut t = [[0.0; 3]; 3];
    for (i, vertex) in vertices.iter().enumerate() {
        let coords = vertex
            .as_array()
            .ok_or_else(|| format!("vertex {i} is {}", describe(vertex)))?;
        if coords.len() != 3 {
            return Err(format!("vertex {i} has {} coordinates", coords.len()));
        }
        for (k, c) in coords.iter().enumerate() {
            let x = c
                .as_f64()
                .ok_or_else(|| format!("vertex {i} coordinate {k} is {}", describe(c)))?;
            if !x.is_finite() {
                return Err(format!("vertex {i} coordinate {k} is not finite"));
            }
            t[i][k] = x;
        }
    }
    Ok(t)
}

fn describe(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::Bool(b) => format!("`{b}`"),
        Value::Number(n) => format!("the number {n}"),
        Value::String(s) => format!("the string {s:?}"),
        Value::Array(a) => format!("an array of {}", a.len()),
        Value::Object(_) => "an object".into(),
    }
}

/// The 1-based line on which each element of the top-level array starts, for
/// a document already known to be valid JSON.
fn top_level_element_lines(text: &str) -> Vec<usize> {
    let mut lines = Vec::new();
    let (mut line, mut depth) = (1usize, 0usize);
    let (mut in_string, mut escaped, mut expecting_element) = (false, false, false);
    for c in text.chars() {
        if c == '\n' {
            line += 1;
        }
        if in_string {
            match (escaped, c) {
                (true, _) => escaped = false,
                (false, '\\') => escaped = true,
                (false, '"') => in_string = false,
                _ => {}
            }
            continue;
        }
        if depth == 1 && expecting_element && !c.is_whitespace() && c != ']' {
            lines.push(line);
            expecting_element = false;
        }
        match c {
            '"' => in_string = true,
            '[' | '{' => {
                depth += 1;
                if depth == 1 {
                    expecting_element = true;
                }
            }
            ']' | '}' => depth -= 1,
            ',' if depth == 1 => expecting_element = true,
            _ => {}
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "0 0 0 1 0 0 0 1 0 0 0 0 0 0 1 1 1 1";

    fn text_error(line: &str) -> RecordError {
        let records = parse_pairs("f.txt", line).unwrap();
        assert_eq!(records.len(), 1);
        records[0].pair.clone().unwrap_err()
    }

    #[test]
    fn text_lines_give_pairs_in_order_skipping_comments_and_blanks() {
        let text = format!(
            "# header\n\n  {GOOD}\n   # indented comment\n0 0 0 1 0 0 0 1 0 0 0 0 0 0 1 2 2 2\n"
        );
        let records = parse_pairs("f.txt", &text).unwrap();
        assert_eq!(
            records.iter().map(|r| r.location.line).collect::<Vec<_>>(),
            vec![3, 5]
        );
        let p = records[1].pair.as_ref().unwrap();
        assert_eq!(p.t1, [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(p.t2, [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [2.0, 2.0, 2.0]]);
    }

    #[test]
    fn wrong_count_names_file_line_and_count() {
        let e = text_error(&format!("{GOOD} 5"));
        assert_eq!(e.kind, RecordErrorKind::WrongCount { found: 19 });
        assert_eq!(
            e.to_string(),
            "f.txt:1: expected 18 numbers (x y z of 6 vertices), found 19"
        );
    }

    #[test]
    fn non_number_is_named() {
        let e = text_error(&GOOD.replacen("1", "1,5", 1));
        assert_eq!(
            e.kind,
            RecordErrorKind::NotANumber {
                position: 4,
                token: "1,5".into()
            }
        );
        assert_eq!(e.to_string(), "f.txt:1: number 4 `1,5` is not a number");
    }

    #[test]
    fn nan_and_infinity_are_refused() {
        for bad in ["nan", "NaN", "inf", "-inf", "infinity", "1e999"] {
            let e = text_error(&GOOD.replacen("0", bad, 1));
            assert_eq!(
                e.kind,
                RecordErrorKind::NotFinite {
                    position: 1,
                    token: bad.into()
                },
                "{bad}"
            );
        }
    }

    #[test]
    fn bad_lines_do_not_stop_good_ones() {
        let text = format!("{GOOD}\n1 2 3\n{GOOD}\n");
        let records = parse_pairs("f.txt", &text).unwrap();
        assert_eq!(records.len(), 3);
        assert!(records[0].pair.is_ok() && records[2].pair.is_ok());
        assert_eq!(records[1].pair.as_ref().unwrap_err().location.line, 2);
        let file = PairsFile {
            file: "f.txt".into(),
            records,
        };
        assert_eq!(file.good_pairs().len(), 2);
        assert_eq!(file.errors().count(), 1);
    }

    const JSON: &str = r#"[
  {"name": "a", "t1": [[0,0,0],[1,0,0],[0,1,0]], "t2": [[0,0,0],[0,0,1],[1,1,1]], "extra": [1, "]"]},
  {"t1": [[0,0,0],[1,0,0],[0,1,0]],
   "t2": [[0,0,0],[0,0,1]]},
  {"t1": [[0,0,0],[1,0,0],[0,1,0]], "t2": [[0,0,0],[0,0,"1"],[1,1,1]]},
  {"t2": [[0,0,0],[0,0,1],[1,1,1]]},
  [1, 2],
  {"t1": [[0,0,0],[1,0,0],[0,1]], "t2": [[0,0,0],[0,0,1],[1,1,1]]}
]"#;

    fn json_errors() -> Vec<Record> {
        parse_pairs("p.json", JSON).unwrap()
    }

    #[test]
    fn json_objects_give_pairs_and_other_fields_are_ignored() {
        let r = json_errors();
        assert_eq!(r.len(), 6);
        let p = r[0].pair.as_ref().unwrap();
        assert_eq!(p.t2[2], [1.0, 1.0, 1.0]);
        assert_eq!(r[0].location.line, 2);
    }

    #[test]
    fn json_errors_name_index_and_line() {
        let r = json_errors();
        let e = r[1].pair.as_ref().unwrap_err();
        assert_eq!(
            e.location,
            Location {
                file: "p.json".into(),
                line: 3,
                index: Some(1)
            }
        );
        assert_eq!(
            e.to_string(),
            "p.json:3: element [1]: `t2` must be 3 vertices of 3 numbers each: found 2 vertices"
        );
        let e = r[2].pair.as_ref().unwrap_err();
        assert_eq!(e.location.line, 5);
        assert!(
            e.to_string()
                .contains("vertex 1 coordinate 2 is the string \"1\""),
            "{e}"
        );
        assert_eq!(
            r[3].pair.as_ref().unwrap_err().kind,
            RecordErrorKind::MissingField { field: "t1" }
        );
        assert_eq!(
            r[4].pair.as_ref().unwrap_err().kind,
            RecordErrorKind::NotAnObject
        );
        assert!(r[5]
            .pair
            .as_ref()
            .unwrap_err()
            .to_string()
            .contains("vertex 2 has 2 coordinates"));
    }

    #[test]
    fn malformed_json_is_a_file_error_with_position() {
        // JSON has no NaN: the literal is a syntax error.
        let e = parse_pairs("p.json", "[\n {\"t1\": [[NaN, 0, 0]]}\n]").unwrap_err();
        match &e {
            FileError::MalformedJson { line, .. } => assert_eq!(*line, 2),
            other => panic!("{other:?}"),
        }
        assert!(e.to_string().starts_with("p.json:2:"), "{e}");
        let e = parse_pairs("p.json", "[1, 2").unwrap_err();
        assert!(matches!(e, FileError::MalformedJson { .. }), "{e}");
    }

    #[test]
    fn json_overflowing_number_is_refused() {
        let e = parse_pairs(
            "p.json",
            r#"[{"t1": [[1e999,0,0],[1,0,0],[0,1,0]], "t2": [[0,0,0],[0,0,1],[1,1,1]]}]"#,
        );
        // serde_json refuses out-of-range numbers while parsing.
        assert!(matches!(e, Err(FileError::MalformedJson { .. })), "{e:?}");
    }

    #[test]
    fn missing_file_is_named() {
        let e = read_pairs("/nonexistent/pairs.txt").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("/nonexistent/pairs.txt: cannot read"),
            "{e}"
        );
    }

    #[test]
    fn a_json_object_is_told_as_json_not_as_a_number() {
        let e = parse_pairs("p.json", r#"{"t1": 1}"#).unwrap_err();
        assert_eq!(
            e.to_string(),
            "p.json: the JSON document must be an array of objects with `t1` and `t2`"
        );
    }

    #[test]
    fn a_file_that_is_not_utf8_is_refused_at_its_line() {
        let path = std::env::temp_dir().join(format!("tritri-pairs-{}.txt", std::process::id()));
        std::fs::write(&path, b"# pairs\n0 0 0 \xff\n").unwrap();
        let e = read_pairs(&path).unwrap_err().to_string();
        std::fs::remove_file(&path).ok();
        assert!(e.ends_with(":2: not UTF-8 text"), "{e}");
    }
}
