//! Multipliers onto a device's DSP blocks, where synthesis would not use
//! their registers.
//!
//! The default emission leaves `*` to synthesis (`MultiplierMapping::Inferred`),
//! which suits every flow. Yosys maps it onto ECP5's MULT18X18D without the
//! block's registers, so `MultiplierMapping::Ecp5` swaps the body of each
//! multiplier module for [`ecp5_verilog`]: the same ports, latency and
//! product, on MULT18X18D instances with all three registers. The emitted
//! directory then also holds [`ECP5_MODEL_FILE`], a simulation model of the
//! primitive that Yosys skips.

use super::modules::Module;
use super::tokens::tokenize;
use crate::arith::multiplier::{ecp5_maps, ecp5_verilog};

pub use crate::arith::multiplier::ECP5_MULT18X18D_MODEL;

/// The widest coordinate width whose products [`ecp5_maps`]: at W the
/// pipeline multiplies (W + 1) x (2W + 1) bits.
pub const MAX_ECP5_DSP_WIDTH: usize = 17;

/// The file that holds [`ECP5_MULT18X18D_MODEL`] in an emitted directory.
pub const ECP5_MODEL_FILE: &str = "ecp5_mult18x18d_model.v";

/// How multipliers reach the DSP blocks (`tritri gen --dsp`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum MultiplierMapping {
    /// `a * b` between registers, for synthesis to map.
    #[default]
    Inferred,
    /// Lattice ECP5 MULT18X18D instances with their registers.
    Ecp5,
}

impl MultiplierMapping {
    pub const NAMES: [&'static str; 2] = ["inferred", "ecp5"];

    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "inferred" => Some(MultiplierMapping::Inferred),
            "ecp5" => Some(MultiplierMapping::Ecp5),
            _ => None,
        }
    }
}

#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "module `{module}` multiplies {a} x {b} bits, which --dsp ecp5 does not map (one operand of at most 18 bits \
     and the other of at most 35: coordinate widths up to 17)"
)]
pub struct UnmappedMultiplier {
    pub module: String,
    pub a: usize,
    pub b: usize,
}

/// The multiplier's `A x B -> P` from the comment its body starts with.
fn multiplier_shape(text: &str) -> Option<(usize, usize, usize)> {
    let rest = text.split("// Registered signed multiplier ").nth(1)?;
    let line = rest.lines().next()?;
    let mut words = line.split_whitespace();
    let a = words.next()?.parse().ok()?;
    let _x = words.next()?;
    let b = words.next()?.parse().ok()?;
    let _arrow = words.next()?;
    let p = words.next()?.parse().ok()?;
    Some((a, b, p))
}

/// Swaps `module`'s body for its ECP5 form when it is a multiplier; returns
/// whether it was one.
pub fn map_ecp5(module: &mut Module) -> Result<bool, UnmappedMultiplier> {
    let text = module.text();
    let Some((a, b, p)) = multiplier_shape(&text) else {
        return Ok(false);
    };
    if !ecp5_maps(a, b) {
        return Err(UnmappedMultiplier {
            module: module.name.clone(),
            a,
            b,
        });
    }
    let marker = "// Update code (custom)";
    let (Some(start), Some(end)) = (text.find(marker), text.rfind("endmodule")) else {
        return Ok(false);
    };
    let head = &text[..start + marker.len()];
    let indented = indented_body(&ecp5_verilog(a, b, p).expect("ecp5_maps said yes"));
    module.tokens = tokenize(&format!("{head}\n{indented}{}", &text[end..]));
    Ok(true)
}

/// A module body as a custom body sits in an emitted module: every line
/// but the empty ones indented by four spaces.
pub(crate) fn indented_body(body: &str) -> String {
    body.lines()
        .map(|l| {
            if l.is_empty() {
                "\n".to_string()
            } else {
                format!("    {l}\n")
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn widest_width_is_the_widest_mapped() {
        let products = |w: usize| [(w + 1, w + 1), (w + 1, 2 * w + 1)];
        assert!(products(MAX_ECP5_DSP_WIDTH)
            .iter()
            .all(|&(a, b)| ecp5_maps(a, b)));
        assert!(!products(MAX_ECP5_DSP_WIDTH + 1)
            .iter()
            .all(|&(a, b)| ecp5_maps(a, b)));
    }

    #[test]
    fn shape_is_read_from_the_comment() {
        let text = "module m (\n);\n    // Update code (custom)\n    // Registered signed multiplier 17 x 33 -> 50 bits (product modulo 2^50).\nendmodule";
        assert_eq!(multiplier_shape(text), Some((17, 33, 50)));
        assert_eq!(multiplier_shape("module m ();\nendmodule"), None);
    }

    #[test]
    fn wide_operands_are_refused_by_name() {
        let mut m = Module {
            name: "tritri_pipeline_w24_multiplier_w74".into(),
            tokens: tokenize("module x ();\n    // Update code (custom)\n    // Registered signed multiplier 25 x 49 -> 74 bits\nendmodule"),
            instances: vec![],
            unit: None,
        };
        let e = map_ecp5(&mut m).unwrap_err();
        assert_eq!((e.a, e.b), (25, 49));
        assert!(
            e.to_string().contains("tritri_pipeline_w24_multiplier_w74"),
            "{e}"
        );
    }
}
