//! Long delay lines onto memories (`tritri gen --delay-lines memory`, the
//! default with `--synth ecp5`).
//!
//! A pipeline carries its pairs' vertices, ids and values beside the
//! arithmetic in delay lines (`crate::arith::delay_line`), one register
//! per stage and bit: at W = 16 with the rare cases shared, about 8,500 of
//! the pipeline's 24,000 flip-flops. ECP5 has no shift-register LUTs, so
//! they stay flip-flops, spread the design over the device and lengthen
//! every route between its arithmetic. `DelayLineMapping::Memory` swaps
//! the body of each delay line of at least
//! [`MEMORY_MIN_STAGES`](crate::arith::delay_line::MEMORY_MIN_STAGES)
//! stages for a memory of at least `N - 1` words (a power of two) with two
//! counters (`delay_line_memory_verilog`): the same ports, latency and
//! values from the first clock, and synthesis puts the words in
//! distributed RAM (the memory's `ram_style` attribute asks for it).
//! (ECP5, W = 16, shared rare cases, heap placement, router1: 20,310
//! flip-flops placed became 15,047, with 344 `TRELLIS_DPR16X4`; seed 1
//! went from 109.3 to 123.7 MHz and from 940 register inputs short of
//! 150 MHz to 323 (seed 2: 103.8 MHz, 407), and router1 took about a
//! quarter of the time; rtl-out/README.md.) The valid bits' lines
//! (`ValidLine`, with a reset) stay registers.

use super::dsp_mapping::indented_body;
use super::EmittedDesign;
use crate::arith::delay_line::{delay_line_memory_verilog, MEMORY_MIN_STAGES};

/// Where the delay lines' stages are (`tritri gen --delay-lines`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DelayLineMapping {
    /// One register per stage, for synthesis to map (Xilinx: SRL LUTs).
    #[default]
    Registers,
    /// Lines of at least `MEMORY_MIN_STAGES` stages in a memory.
    Memory,
}

impl DelayLineMapping {
    pub const NAMES: [&'static str; 2] = ["registers", "memory"];

    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "registers" => Some(DelayLineMapping::Registers),
            "memory" => Some(DelayLineMapping::Memory),
            _ => None,
        }
    }
}

/// The header line naming a delay line's Rust unit (`package::files`).
const DELAY_LINE_UNIT: &str = "// Rust unit:  DelayLine<";
/// Where a custom body starts, and the delay line's first line in it.
const BODY_MARKER: &str = "    // Update code (custom)\n";
const SHAPE_PREFIX: &str = "    // Delay line: ";

/// `(stages, bits)` of a delay line's body, from its first comment.
fn delay_line_shape(text: &str) -> Option<(usize, usize)> {
    let rest = text.split(SHAPE_PREFIX).nth(1)?;
    let line = rest.lines().next()?;
    let mut words = line.split_whitespace();
    let n = words.next()?.parse().ok()?;
    let _stages = words.next()?;
    let _of = words.next()?;
    let bits = words.next()?.parse().ok()?;
    Some((n, bits))
}

/// Applies `mapping` to every delay-line module of `design`; returns how
/// many went into memories.
pub fn map_delay_lines(design: &mut EmittedDesign, mapping: DelayLineMapping) -> usize {
    if mapping == DelayLineMapping::Registers {
        return 0;
    }
    let mut mapped = 0;
    for file in design.files.iter_mut().filter(|f| f.path.ends_with(".v")) {
        if let Some(text) = in_memory(&file.contents) {
            file.contents = text;
            mapped += 1;
        }
    }
    let readme = design.files.iter_mut().find(|f| f.path == "README.md");
    if let Some(readme) = readme.filter(|_| mapped > 0) {
        if let Some(at) = readme.contents.find("\n## Use") {
            let note = format!(
                "- The {mapped} delay-line modules of {MEMORY_MIN_STAGES} stages or more keep their stages in a memory of \
                 at least N - 1 words (a power of two) with two pointers (`tritri gen --delay-lines memory`): the same latency and values as \
                 registers, in distributed RAM on ECP5.\n"
            );
            readme.contents.insert_str(at, &note);
        }
    }
    mapped
}

/// The text of one emitted delay-line module with its body in memory, or
/// `None` if it is not a delay line or too short for one.
fn in_memory(text: &str) -> Option<String> {
    if !text.contains(DELAY_LINE_UNIT) {
        return None;
    }
    let (n, bits) = delay_line_shape(text)?;
    if n < MEMORY_MIN_STAGES {
        return None;
    }
    let start = text.find(BODY_MARKER)? + BODY_MARKER.len();
    let end = text.rfind("endmodule")?;
    let body = indented_body(&delay_line_memory_verilog(bits, n));
    Some(format!("{}{body}{}", &text[..start], &text[end..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse() {
        for name in DelayLineMapping::NAMES {
            assert!(DelayLineMapping::parse(name).is_some(), "{name}");
        }
        assert_eq!(DelayLineMapping::parse("srl"), None);
    }

    #[test]
    fn shape_is_read_from_the_comment() {
        let text = "module m (\n);\n    // Update code (custom)\n    // Delay line: 10 stage(s) of 16 bit(s).\nendmodule\n";
        assert_eq!(delay_line_shape(text), Some((10, 16)));
        assert_eq!(delay_line_shape("module m ();\nendmodule"), None);
    }

    #[test]
    fn only_long_delay_lines_are_mapped() {
        let module = |unit: &str, n: usize| {
            format!(
                "// Rust unit:  {unit}\nmodule m (\n);\n{BODY_MARKER}{SHAPE_PREFIX}{n} stage(s) of 16 bit(s).\n    reg x;\nendmodule\n"
            )
        };
        let long = in_memory(&module("DelayLine<T = Bits<16>, N = 10>", 10)).unwrap();
        assert!(
            long.contains("(* ram_style = \"distributed\" *)\n    reg [15:0] words [0:15];"),
            "{long}"
        );
        assert!(
            long.ends_with("endmodule\n") && !long.contains("reg x;"),
            "{long}"
        );
        let short = MEMORY_MIN_STAGES - 1;
        assert_eq!(
            in_memory(&module("DelayLine<T = Bits<16>, N = 5>", short)),
            None
        );
        assert_eq!(in_memory(&module("ValidLine<N = 10>", 10)), None);
    }
}
