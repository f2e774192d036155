//! `tritri classify [--arith A] [--width W] FILE`
//!
//! Prints one line per pair that could be read, in file order: `1` when the
//! closed triangles intersect, `0` when not. A record that cannot be read
//! gets no line on stdout but an error on stderr naming the file and line
//! (so stdout has exactly one line per good pair), and the exit status is 2.
//! With `--arith fixed` the whole file is quantized into one W-bit frame,
//! whose step is printed on stderr as a note.

use crate::input;
use anyhow::Context;
use clap::ValueEnum;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use tritri_geom::arithmetic::{classify, Arithmetic, DEFAULT_WIDTH};

#[derive(clap::Args)]
pub struct Args {
    /// Arithmetic that decides the pairs.
    #[arg(long, value_enum, default_value_t = ArithName::Exact)]
    arith: ArithName,
    /// Coordinate width for `--arith fixed` (8 to 32 bits) [default: 24].
    #[arg(long, value_parser = input::parse_width)]
    width: Option<u32>,
    /// Pair file: 18 numbers per line, or a JSON array of {t1, t2}.
    file: PathBuf,
}

#[derive(Clone, Copy, ValueEnum)]
enum ArithName {
    /// Exact predicates on the f64 coordinates (ground truth).
    Exact,
    /// The published Guigue-Devillers code in double precision.
    F64,
    /// The published code in single precision.
    F32,
    /// Moller 1997 with its epsilon 1e-6.
    Moller,
    /// Quantized to W-bit integers (one frame per file), exact integer predicates.
    Fixed,
}

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let arith = match (args.arith, args.width) {
        (ArithName::Fixed, width) => Arithmetic::Fixed(width.unwrap_or(DEFAULT_WIDTH)),
        (_, Some(w)) => {
            eprintln!("error: --width {w} applies only to --arith fixed");
            return Ok(ExitCode::from(2));
        }
        (ArithName::Exact, None) => Arithmetic::Exact,
        (ArithName::F64, None) => Arithmetic::F64,
        (ArithName::F32, None) => Arithmetic::F32,
        (ArithName::Moller, None) => Arithmetic::Moller,
    };
    let loaded = input::load(&args.file);
    let pairs = loaded.good_pairs();
    let result = classify(arith, &pairs).with_context(|| format!("{}", args.file.display()))?;
    if let Some(frame) = result.frame {
        eprintln!(
            "note: {}: {arith}: {} pairs quantized into one frame, step h = {:e}, centre {:?}",
            args.file.display(),
            pairs.len(),
            frame.step,
            frame.centre
        );
    }
    let mut out = BufWriter::new(std::io::stdout().lock());
    for v in &result.verdicts {
        writeln!(out, "{}", u8::from(*v))?;
    }
    out.flush()?;
    Ok(if loaded.errors > 0 { ExitCode::from(2) } else { ExitCode::SUCCESS })
}
