//! The vector and output files of the Verilog testbench
//! (`testbenches/tb_triangle_pipeline.sv`; format in `testbenches/README.md`).
//!
//! Vectors: one line per input cycle, `valid bset id x0 y0 z0 x1 y1 z1 x2 y2 z2`,
//! `valid` and `bset` one digit each, the id and the coordinates in hex
//! (coordinates as W-bit two's complement). Lines starting with `#` are
//! comments.
//!
//! Outputs (written by the testbench, and by [`write_expected`] for the
//! expected run): one line per verdict, `cycle base_id stream_id hit`, the
//! cycle in decimal, the ids in hex, `hit` 0 or 1; then `# cycles N`.

use crate::stream::{PairVerdict, StreamResult, TriangleStream};
use std::fmt::Write as _;
use tritri_rtl::pipeline::pipeline_for_width::PipelineInput;

/// Hex digits for `bits` bits.
fn digits(bits: u32) -> usize {
    bits.div_ceil(4) as usize
}

/// `v` as a `bits`-bit two's-complement hex number, zero-padded.
pub fn hex_twos_complement(v: i64, bits: u32) -> String {
    let mask = if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    };
    format!("{:0width$x}", (v as u64) & mask, width = digits(bits))
}

/// One vector line (no newline).
pub fn vector_line(c: &PipelineInput, width: u32, id_bits: u32) -> String {
    let mut line = format!(
        "{} {} {:0w$x}",
        c.valid as u8,
        c.bset as u8,
        c.id,
        w = digits(id_bits)
    );
    for v in c.vertices {
        line.push(' ');
        line.push_str(&hex_twos_complement(v, width));
    }
    line
}

/// The whole vector file for `stream`, with a comment header.
pub fn vectors(stream: &TriangleStream, width: u32, id_bits: u32) -> String {
    let mut text =
        String::with_capacity((stream.input_cycles() as usize + 4) * (12 + 10 * digits(width)));
    let _ = writeln!(
        text,
        "# tritri vectors: W={width} ID_WIDTH={id_bits} N1={} N2={} (testbenches/README.md)",
        stream.bases.len(),
        stream.streamed.len()
    );
    schedule_vectors(text, stream.schedule(), width, id_bits)
}

/// The vector file for an arbitrary schedule of input cycles (for example one
/// `bset` cycle and one test cycle per pair), with a comment header.
pub fn vectors_for_schedule(schedule: &[PipelineInput], width: u32, id_bits: u32) -> String {
    let mut text = String::with_capacity((schedule.len() + 4) * (12 + 10 * digits(width)));
    let _ = writeln!(text, "# tritri vectors: W={width} ID_WIDTH={id_bits} schedule of {} cycles (testbenches/README.md)", schedule.len());
    schedule_vectors(text, schedule.iter().copied(), width, id_bits)
}

fn schedule_vectors(
    mut text: String,
    schedule: impl Iterator<Item = PipelineInput>,
    width: u32,
    id_bits: u32,
) -> String {
    text.push_str("# valid bset id x0 y0 z0 x1 y1 z1 x2 y2 z2\n");
    for c in schedule {
        text.push_str(&vector_line(&c, width, id_bits));
        text.push('\n');
    }
    text
}

/// The output file a correct pipeline of latency `latency` writes for
/// `stream`, given the expected verdicts in output order.
pub fn expected_outputs(stream: &TriangleStream, expected: &[PairVerdict], latency: u64) -> String {
    let n2 = stream.streamed.len() as u64;
    let mut text = String::new();
    for (k, v) in expected.iter().enumerate() {
        let (base, stream_index) = (k as u64 / n2.max(1), k as u64 % n2.max(1));
        let input_cycle = base * (n2 + 1) + 1 + stream_index;
        let _ = writeln!(
            text,
            "{} {:x} {:x} {} {}",
            input_cycle + latency,
            v.base_id,
            v.stream_id,
            v.hit as u8,
            v.certain as u8
        );
    }
    let _ = writeln!(text, "# cycles {}", stream.expected_cycles(latency));
    text
}

#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum OutputError {
    #[error(
        "output line {line}: cannot read `{text}` (expected `cycle base_id stream_id hit certain`)"
    )]
    Malformed { line: usize, text: String },
    #[error("the testbench timed out waiting for verdicts ({verdicts} received)")]
    Timeout { verdicts: usize },
    #[error("the output has no `# cycles N` line: the simulation did not finish")]
    Unfinished,
}

/// A verdict with the cycle it appeared in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TimedVerdict {
    pub cycle: u64,
    pub verdict: PairVerdict,
}

/// Parses a testbench output file.
pub fn parse_outputs(text: &str) -> Result<(StreamResult, Vec<TimedVerdict>), OutputError> {
    let mut timed = Vec::new();
    let mut cycles = None;
    let mut held = 0;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        if let Some(rest) = line.strip_prefix('#') {
            let rest = rest.trim();
            if let Some(n) = rest.strip_prefix("cycles") {
                cycles = Some(n.trim().parse().map_err(|_| OutputError::Malformed {
                    line: i + 1,
                    text: line.into(),
                })?);
            } else if let Some(n) = rest.strip_prefix("held") {
                held = n.trim().parse().map_err(|_| OutputError::Malformed {
                    line: i + 1,
                    text: line.into(),
                })?;
            } else if rest.starts_with("timeout") {
                return Err(OutputError::Timeout {
                    verdicts: timed.len(),
                });
            }
            continue;
        }
        let bad = || OutputError::Malformed {
            line: i + 1,
            text: line.to_string(),
        };
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.len() != 5 {
            return Err(bad());
        }
        let cycle = fields[0].parse().map_err(|_| bad())?;
        let base_id = u32::from_str_radix(fields[1], 16).map_err(|_| bad())?;
        let stream_id = u32::from_str_radix(fields[2], 16).map_err(|_| bad())?;
        let flag = |field: &str| match field {
            "0" => Ok(false),
            "1" => Ok(true),
            _ => Err(bad()),
        };
        let (hit, certain) = (flag(fields[3])?, flag(fields[4])?);
        timed.push(TimedVerdict {
            cycle,
            verdict: PairVerdict {
                base_id,
                stream_id,
                hit,
                certain,
            },
        });
    }
    let cycles = cycles.ok_or(OutputError::Unfinished)?;
    let result = StreamResult {
        verdicts: timed.iter().map(|t| t.verdict).collect(),
        cycles,
        held,
    };
    Ok((result, timed))
}

#[cfg(test)]
mod tests {
    use super::*;
    use tritri_geom::certificate::CertifiedVerdict;

    #[test]
    fn negative_coordinates_are_twos_complement() {
        assert_eq!(hex_twos_complement(-1, 24), "ffffff");
        assert_eq!(hex_twos_complement(-(1 << 23), 24), "800000");
        assert_eq!(hex_twos_complement(5, 10), "005");
        assert_eq!(hex_twos_complement(-1, 32), "ffffffff");
    }

    #[test]
    fn vector_lines() {
        let c = PipelineInput {
            valid: true,
            bset: false,
            id: 0x2a,
            vertices: [-1, 0, 1, 2, 3, 4, 5, 6, -8],
        };
        assert_eq!(
            vector_line(&c, 8, 32),
            "1 0 0000002a ff 00 01 02 03 04 05 06 f8"
        );
    }

    /// The expected file parses back into the same verdicts and cycle count.
    #[test]
    fn expected_round_trips() {
        let t = [[0, 0, 0], [1, 0, 0], [0, 1, 0]];
        let s = TriangleStream::from_triangles(&[t, t], &[t, t, t]);
        let expected = s.expected(|_, _| CertifiedVerdict {
            hit: true,
            certain: false,
        });
        let text = expected_outputs(&s, &expected, 5);
        let (result, timed) = parse_outputs(&text).unwrap();
        assert_eq!(result.verdicts, expected);
        assert_eq!(result.cycles, 2 + 6 + 5);
        // Base 1's first pair is input cycle 5 (cycles 0..3 are base 0 and its stream, 4 is bset).
        assert_eq!(timed[3].cycle, 5 + 5);
    }

    #[test]
    fn unfinished_runs_are_errors() {
        assert_eq!(parse_outputs("3 0 0 1 1\n"), Err(OutputError::Unfinished));
        assert!(matches!(
            parse_outputs("3 0 0 1 0\n# timeout\n"),
            Err(OutputError::Timeout { verdicts: 1 })
        ));
    }
}
