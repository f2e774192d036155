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
        self.file
            .as_ref()
            .map(PairsFile::good_pairs)
            .unwrap_or_default()
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
            Loaded {
                file: Some(file),
                errors,
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            Loaded {
                file: None,
                errors: 1,
            }
        }
    }
}

/// A whole number in `range`, in digits. The refusal names the range:
/// Rust's own parse messages ("invalid digit found in string") do not,
/// and clap's ranged parsers use them for text that is not a number.
pub fn whole<T>(
    range: std::ops::RangeInclusive<T>,
) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync + 'static
where
    T: std::str::FromStr + PartialOrd + std::fmt::Display + Clone + Send + Sync + 'static,
{
    move |s: &str| match s.trim().parse::<T>() {
        Ok(v) if range.contains(&v) => Ok(v),
        _ => Err(format!(
            "`{s}` is not a whole number from {} to {} (in digits)",
            range.start(),
            range.end()
        )),
    }
}

/// clap value parser for a coordinate width: names the value when it is
/// out of range.
pub fn parse_width(s: &str) -> Result<u32, String> {
    let w: u32 = s.trim().parse().map_err(|_| {
        format!("`{s}` is not a width (an integer from {MIN_WIDTH} to {MAX_WIDTH})")
    })?;
    FixedWidths::new(w).map_err(|e| e.to_string())?;
    Ok(w)
}

/// A tolerance: a finite distance > 0.
pub fn parse_tolerance(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!(
            "`{s}` is not a tolerance (a finite distance greater than 0)"
        )),
    }
}

/// A scale factor: a finite number > 0.
pub fn parse_scale(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!(
            "`{s}` is not a scale factor (a finite number greater than 0)"
        )),
    }
}

/// A count of clocks: a whole number written in digits, so `1e3` and `-1`
/// are refused with the range instead of "invalid digit found in string".
pub fn parse_cycles(s: &str) -> Result<u64, String> {
    s.trim().parse::<u64>().map_err(|_| {
        format!(
            "`{s}` is not a count of clocks (a whole number from 0 to {}, in digits)",
            u64::MAX
        )
    })
}

/// The longest `--min-time-ms` taken: ten minutes per arithmetic and file
/// (a larger value runs for hours or, near u64::MAX, without end).
pub const MAX_MIN_TIME_MS: u64 = 600_000;

/// A minimum timing time in ms: a whole number from 0 to
/// [`MAX_MIN_TIME_MS`].
pub fn parse_min_time_ms(s: &str) -> Result<u64, String> {
    match s.trim().parse::<u64>() {
        Ok(v) if v <= MAX_MIN_TIME_MS => Ok(v),
        _ => Err(format!(
            "`{s}` is not a timing time in ms (a whole number from 0 to {MAX_MIN_TIME_MS}, ten minutes)"
        )),
    }
}

/// A clock frequency in MHz: a finite number from 0.001 (1 kHz) to 100000
/// (100 GHz), so every time printed is a finite duration.
pub fn parse_clock_mhz(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.001..=100_000.0).contains(&v) => Ok(v),
        _ => Err(format!(
            "`{s}` is not a clock frequency in MHz (a number from 0.001 to 100000)"
        )),
    }
}

/// A bandwidth in GB/s, from 0.001 to 10000.
pub fn parse_gbytes(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.001..=10_000.0).contains(&v) => Ok(v),
        _ => Err(format!(
            "`{s}` is not a bandwidth in GB/s (a number from 0.001 to 10000)"
        )),
    }
}

/// An AXI4 port's data width the DRAM top is built for: 64, 128 or 256.
pub fn parse_port_bits(s: &str) -> Result<usize, String> {
    use tritri_rtl::broad_phase::list_pass_machine::PASS_DATA_BITS;
    match s.trim().parse::<usize>() {
        Ok(v) if PASS_DATA_BITS.contains(&v) => Ok(v),
        _ => Err(format!(
            "`{s}` is not a port width the DRAM top is built for ({})",
            PASS_DATA_BITS.map(|b| b.to_string()).join(", ")
        )),
    }
}

/// A percentage in (0, 100].
pub fn parse_percentage(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v <= 100.0 => Ok(v),
        _ => Err(format!("`{s}` is not a percentage in (0, 100]")),
    }
}

/// A voxel grid's resolution: a power of two from 2 to 1024.
pub fn parse_resolution(s: &str) -> Result<u64, String> {
    let n: u64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a resolution (a power of two from 2 to 1024)"))?;
    tritri_geom::octree::voxelize::level_of_resolution(n).map_err(|e| e.to_string())?;
    Ok(n)
}

/// `N` comma-separated numbers of type `T`, named in the error.
fn parse_list<T: std::str::FromStr, const N: usize>(s: &str, what: &str) -> Result<[T; N], String> {
    let fields: Vec<&str> = s.split(',').map(str::trim).collect();
    if fields.len() != N {
        return Err(format!("`{s}` is not {what} ({N} comma-separated numbers)"));
    }
    let values: Vec<T> = fields
        .iter()
        .map(|f| {
            f.parse::<T>()
                .map_err(|_| format!("`{f}` in `{s}` is not a number ({what})"))
        })
        .collect::<Result<_, _>>()?;
    values
        .try_into()
        .map_err(|_| format!("`{s}` is not {what}"))
}

/// A point `x,y,z`: three finite numbers.
pub fn parse_point(s: &str) -> Result<[f64; 3], String> {
    let v: [f64; 3] = parse_list(s, "a point x,y,z")?;
    if !v.iter().all(|c| c.is_finite()) {
        return Err(format!("`{s}` is not a point x,y,z (three finite numbers)"));
    }
    Ok(v)
}

/// A viewing direction `x,y,z`: finite, not zero.
pub fn parse_eye(s: &str) -> Result<[f64; 3], String> {
    let v: [f64; 3] = parse_list(s, "an eye direction x,y,z")?;
    if !v.iter().all(|c| c.is_finite()) || v == [0.0; 3] {
        return Err(format!("`{s}` is not an eye direction (finite, not 0,0,0)"));
    }
    Ok(v)
}

/// A plane's integer normal `a,b,c`, not zero, each at most 2^20 in size
/// (the classification's values stay far inside i128).
pub fn parse_normal(s: &str) -> Result<[i64; 3], String> {
    let v: [i64; 3] = parse_list(s, "an integer normal a,b,c")?;
    if v == [0; 3] || v.iter().any(|c| c.unsigned_abs() > 1 << 20) {
        return Err(format!(
            "`{s}` is not a plane normal (integers up to 2^20 in size, not all 0)"
        ));
    }
    Ok(v)
}

/// A box of voxels `x0,y0,z0,x1,y1,z1`, half-open, `x0 < x1` etc.
pub fn parse_voxel_box(s: &str) -> Result<[i64; 6], String> {
    let v: [i64; 6] = parse_list(s, "a voxel box x0,y0,z0,x1,y1,z1")?;
    if (0..3).any(|k| v[k] >= v[k + 3]) || v.iter().any(|c| c.unsigned_abs() > 1 << 20) {
        return Err(format!(
            "`{s}` is not a voxel box (x0 < x1, y0 < y1, z0 < z1, each at most 2^20 in size)"
        ));
    }
    Ok(v)
}
