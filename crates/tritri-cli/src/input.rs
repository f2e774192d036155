//! Reading pair files for the subcommands, with the project's error rules:
//! every bad record is reported on stderr (naming file and line) and
//! skipped; the caller finishes its work on the good pairs and exits with
//! status 2 when anything was skipped.

use std::path::Path;
use tritri_geom::pairs_io::{self, PairsFile};
use tritri_geom::widths::{FixedWidths, MAX_WIDTH, MIN_WIDTH};
use tritri_geom::TrianglePair;

/// The good pairs of a file, and how many records or files could not be read.
pub struct Loaded {
    pub file: Option<PairsFile>,
    pub errors: usize,
}

impl Loaded {
    pub fn good_pairs(&self) -> Vec<TrianglePair> {
        self.file.as_ref().map(PairsFile::good_pairs).unwrap_or_default()
    }
}

/// Reads `path` (`-`: standard input), printing `error: FILE:LINE: ...`
/// for each bad record.
pub fn load(path: &Path) -> Loaded {
    let read = if path == Path::new("-") {
        let file = "<stdin>".to_string();
        let mut text = String::new();
        match std::io::Read::read_to_string(&mut std::io::stdin(), &mut text) {
            Ok(_) => pairs_io::parse_pairs(&file, &text).map(|records| PairsFile { file, records }),
            Err(source) => Err(pairs_io::FileError::Io { file, source }),
        }
    } else {
        pairs_io::read_pairs(path)
    };
    match read {
        Ok(file) => {
            let mut errors = 0;
            for e in file.errors() {
                eprintln!("error: {e}");
                errors += 1;
            }
            Loaded { file: Some(file), errors }
        }
        Err(e) => {
            eprintln!("error: {e}");
            Loaded { file: None, errors: 1 }
        }
    }
}

/// clap value parser for a coordinate width: names the value when it is
/// out of range.
pub fn parse_width(s: &str) -> Result<u32, String> {
    let w: u32 =
        s.trim().parse().map_err(|_| format!("`{s}` is not a width (an integer from {MIN_WIDTH} to {MAX_WIDTH})"))?;
    FixedWidths::new(w).map_err(|e| e.to_string())?;
    Ok(w)
}

/// A scale factor: a finite number > 0.
pub fn parse_scale(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("`{s}` is not a scale factor (a finite number greater than 0)")),
    }
}

/// A clock frequency in MHz: a finite number from 0.001 (1 kHz) to 100000
/// (100 GHz), so every time printed is a finite duration.
pub fn parse_clock_mhz(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.001..=100_000.0).contains(&v) => Ok(v),
        _ => Err(format!("`{s}` is not a clock frequency in MHz (a number from 0.001 to 100000)")),
    }
}

/// A percentage in (0, 100].
pub fn parse_percentage(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v <= 100.0 => Ok(v),
        _ => Err(format!("`{s}` is not a percentage in (0, 100]")),
    }
}
