//! One name for each way of computing the verdicts, and a batch API over all
//! of them.
//!
//! | name | what |
//! |---|---|
//! | `exact` | [`crate::exact_f64`]: exact predicates on the f64 coordinates (ground truth) |
//! | `f64`, `f32` | [`crate::published_float`]: the published Guigue–Devillers C code in double / single precision |
//! | `moller` | [`crate::moller`]: Möller 1997 with its epsilon 1e-6 |
//! | `fixed<W>` | [`crate::fixed_point`]: the whole batch quantized into one W-bit frame, then exact integer predicates (the hardware's answer) |
//!
//! Rules of [`classify`]: every coordinate must be finite (else an error
//! naming the pair); the verdicts come in the order of the pairs; for
//! `fixed<W>` the frame ([`Frame::fit`] over every triangle of every pair) is
//! returned with the verdicts, so its step `h` can be reported.
//!
//! ```
//! use tritri_geom::arithmetic::{classify, Arithmetic};
//! use tritri_geom::TrianglePair;
//! let t1 = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! let t2 = [[0.2, 0.2, -1.0], [0.2, 0.2, 1.0], [0.9, 0.9, 0.5]];
//! let pairs = [TrianglePair::new(t1, t2)];
//! let arith: Arithmetic = "fixed:24".parse().unwrap();
//! let c = classify(arith, &pairs).unwrap();
//! assert_eq!(c.verdicts, vec![true]);
//! assert!(c.frame.unwrap().step < 1e-6);
//! assert_eq!(arith.to_string(), "fixed24");
//! ```

use crate::fixed_point::{self, FixedTriangle};
use crate::quantize::{Frame, QuantizeError};
use crate::triangle::TrianglePair;
use crate::widths::{FixedWidths, WidthOutOfRange};
use crate::{exact_f64, moller, published_float};
use std::fmt;
use std::str::FromStr;

/// The coordinate width of the thesis's hardware, the default for `fixed`.
pub const DEFAULT_WIDTH: u32 = 24;

/// An arithmetic that decides triangle pairs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Arithmetic {
    /// Exact predicates on the f64 coordinates: the ground truth.
    Exact,
    /// The published code in double precision.
    F64,
    /// The published code in single precision (inputs rounded to f32).
    F32,
    /// Möller 1997 in double precision with epsilon 1e-6.
    Moller,
    /// Quantized into one W-bit frame per batch, then exact integer predicates.
    Fixed(u32),
}

impl Arithmetic {
    /// `Fixed(width)`, refusing widths the project does not support.
    pub fn fixed(width: u32) -> Result<Arithmetic, WidthOutOfRange> {
        FixedWidths::new(width)?;
        Ok(Arithmetic::Fixed(width))
    }

    /// Exact, f64, f32, Möller, then fixed at each width: what `tritri eval`
    /// runs.
    pub fn all(widths: &[u32]) -> Result<Vec<Arithmetic>, WidthOutOfRange> {
        let mut v = vec![
            Arithmetic::Exact,
            Arithmetic::F64,
            Arithmetic::F32,
            Arithmetic::Moller,
        ];
        for &w in widths {
            v.push(Arithmetic::fixed(w)?);
        }
        Ok(v)
    }
}

impl fmt::Display for Arithmetic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Arithmetic::Exact => f.write_str("exact"),
            Arithmetic::F64 => f.write_str("f64"),
            Arithmetic::F32 => f.write_str("f32"),
            Arithmetic::Moller => f.write_str("moller"),
            Arithmetic::Fixed(w) => write!(f, "fixed{w}"),
        }
    }
}

/// Error for an unknown arithmetic name or a bad width.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ParseArithmeticError {
    #[error("unknown arithmetic `{0}`: expected exact, f64, f32, moller, fixed or fixed<W> (W in 8..=32)")]
    Unknown(String),
    #[error("`{0}`: the width after `fixed` is not a number")]
    BadWidth(String),
    #[error(transparent)]
    Width(#[from] WidthOutOfRange),
}

impl FromStr for Arithmetic {
    type Err = ParseArithmeticError;

    /// `exact`, `f64`, `f32`, `moller`, `fixed` (width 24), `fixed24`,
    /// `fixed:24` or `fixed-24`; case-insensitive.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let lower = s.trim().to_ascii_lowercase();
        match lower.as_str() {
            "exact" => return Ok(Arithmetic::Exact),
            "f64" | "double" => return Ok(Arithmetic::F64),
            "f32" | "float" | "single" => return Ok(Arithmetic::F32),
            "moller" | "möller" => return Ok(Arithmetic::Moller),
            "fixed" => return Ok(Arithmetic::Fixed(DEFAULT_WIDTH)),
            _ => {}
        }
        let Some(rest) = lower.strip_prefix("fixed") else {
            return Err(ParseArithmeticError::Unknown(s.to_string()));
        };
        let digits = rest.strip_prefix([':', '-', '=']).unwrap_or(rest);
        let width: u32 = digits
            .parse()
            .map_err(|_| ParseArithmeticError::BadWidth(s.to_string()))?;
        Ok(Arithmetic::fixed(width)?)
    }
}

/// Verdicts of one batch, and the frame when the arithmetic quantized.
#[derive(Clone, Debug, PartialEq)]
pub struct Classification {
    /// One verdict per pair, in order: true when the triangles intersect.
    pub verdicts: Vec<bool>,
    /// For `Fixed`: the batch's frame (its `step` is the grid step h).
    pub frame: Option<Frame>,
}

/// Why a batch could not be classified.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ClassifyError {
    #[error("pair {pair}: coordinate {value} is not finite")]
    NotFinite { pair: usize, value: f64 },
    #[error(transparent)]
    Width(#[from] WidthOutOfRange),
}

/// Decides every pair with `arith`. See the module documentation for the rules.
pub fn classify(
    arith: Arithmetic,
    pairs: &[TrianglePair],
) -> Result<Classification, ClassifyError> {
    if !matches!(arith, Arithmetic::Fixed(_)) {
        // (Frame::fit checks it for Fixed.)
        check_finite(pairs)?;
    }
    Ok(match arith {
        Arithmetic::Exact => Classification {
            verdicts: verdicts_of(pairs, exact_f64::intersects),
            frame: None,
        },
        Arithmetic::F64 => Classification {
            verdicts: verdicts_of(pairs, published_float::intersects_f64),
            frame: None,
        },
        Arithmetic::F32 => Classification {
            verdicts: verdicts_of(pairs, published_float::intersects_f32),
            frame: None,
        },
        Arithmetic::Moller => Classification {
            verdicts: verdicts_of(pairs, moller::intersects),
            frame: None,
        },
        Arithmetic::Fixed(width) => {
            let frame = fit_frame(pairs, width)?;
            let verdicts = pairs
                .iter()
                .map(|p| fixed_point::intersects(&frame.quantize(&p.t1), &frame.quantize(&p.t2)))
                .collect();
            Classification {
                verdicts,
                frame: Some(frame),
            }
        }
    })
}

/// Generic over the test (a distinct type per function), so that each
/// arithmetic's loop is its own function with its test inlined.
#[inline(never)]
fn verdicts_of<F: Fn(&crate::Triangle, &crate::Triangle) -> bool>(
    pairs: &[TrianglePair],
    test: F,
) -> Vec<bool> {
    pairs.iter().map(|p| test(&p.t1, &p.t2)).collect()
}

/// The one frame of a batch: fitted over every triangle of every pair.
pub fn fit_frame(pairs: &[TrianglePair], width: u32) -> Result<Frame, ClassifyError> {
    Frame::fit(pairs.iter().flat_map(|p| [&p.t1, &p.t2]), width).map_err(|e| match e {
        QuantizeError::Width(w) => ClassifyError::Width(w),
        QuantizeError::NotFinite { triangle, value } => ClassifyError::NotFinite {
            pair: triangle / 2,
            value,
        },
    })
}

/// The batch quantized into its one frame, as `[t1, t2]` per pair.
pub fn quantize_pairs(
    pairs: &[TrianglePair],
    width: u32,
) -> Result<(Frame, Vec<[FixedTriangle; 2]>), ClassifyError> {
    let frame = fit_frame(pairs, width)?;
    let q = pairs
        .iter()
        .map(|p| [frame.quantize(&p.t1), frame.quantize(&p.t2)])
        .collect();
    Ok((frame, q))
}

fn check_finite(pairs: &[TrianglePair]) -> Result<(), ClassifyError> {
    for (i, p) in pairs.iter().enumerate() {
        let mut finite = true;
        for t in [&p.t1, &p.t2] {
            for v in t {
                for c in v {
                    finite &= c.is_finite();
                }
            }
        }
        if !finite {
            let value = p.coordinates().find(|v| !v.is_finite()).unwrap_or(f64::NAN);
            return Err(ClassifyError::NotFinite { pair: i, value });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for a in Arithmetic::all(&[8, 24, 32]).unwrap() {
            assert_eq!(a.to_string().parse::<Arithmetic>(), Ok(a));
        }
        assert_eq!("fixed".parse(), Ok(Arithmetic::Fixed(24)));
        assert_eq!("FIXED-12".parse(), Ok(Arithmetic::Fixed(12)));
        assert_eq!("Moller".parse(), Ok(Arithmetic::Moller));
    }

    #[test]
    fn bad_names_and_widths_are_named_in_the_error() {
        assert_eq!(
            "fixed40".parse::<Arithmetic>(),
            Err(ParseArithmeticError::Width(WidthOutOfRange(40)))
        );
        assert!("fixed40"
            .parse::<Arithmetic>()
            .unwrap_err()
            .to_string()
            .contains("40"));
        assert_eq!(
            "fixedx".parse::<Arithmetic>(),
            Err(ParseArithmeticError::BadWidth("fixedx".into()))
        );
        assert_eq!(
            "f16".parse::<Arithmetic>(),
            Err(ParseArithmeticError::Unknown("f16".into()))
        );
        assert_eq!(Arithmetic::fixed(7), Err(WidthOutOfRange(7)));
    }

    /// Every arithmetic refuses a non-finite coordinate and names the pair.
    #[test]
    fn non_finite_coordinates_are_refused() {
        let t: crate::Triangle = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let mut bad = t;
        bad[2][1] = f64::INFINITY;
        let pairs = [TrianglePair::new(t, t), TrianglePair::new(t, bad)];
        for a in Arithmetic::all(&[24]).unwrap() {
            match classify(a, &pairs) {
                Err(ClassifyError::NotFinite { pair: 1, value }) => assert!(value.is_infinite()),
                other => panic!("{a}: {other:?}"),
            }
        }
    }

    /// One frame for the batch: a pair far from the others coarsens the step
    /// for all of them.
    #[test]
    fn fixed_quantizes_the_whole_batch_into_one_frame() {
        let t: crate::Triangle = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let far = t.map(|p| p.map(|c| c + 1000.0));
        let one = classify(Arithmetic::Fixed(16), &[TrianglePair::new(t, t)]).unwrap();
        let two = classify(
            Arithmetic::Fixed(16),
            &[TrianglePair::new(t, t), TrianglePair::new(far, far)],
        )
        .unwrap();
        assert!(two.frame.unwrap().step > 500.0 * one.frame.unwrap().step);
        assert_eq!(two.verdicts, vec![true, true]);
    }
}
