//! What the emitter knows of each rust-hdl unit: which Rust type sits at
//! each instance path, the type's doc and its latency.
//!
//! rust-hdl prints one Verilog module per instance, named after the
//! instance's path (`top$orient3d_0$normal`), and its visitor does not tell
//! which Rust type an instance is. Every unit therefore implements [`Unit`]:
//! its latency constant, and ([`sub_units!`](crate::sub_units)) the fields that hold other
//! units. [`RawDesign::of`] walks a top this way beside rust-hdl's Verilog,
//! and the emitter names each module after its type
//! (`certified_orient3d`, `delay_line`) and heads its file with the type's
//! doc (collected by `build.rs`), parameters and latency. A module whose
//! path the walk did not reach is an emission error that names the path.

use rust_hdl::prelude::*;
use std::collections::BTreeMap;

/// A rust-hdl unit.
pub trait Unit {
    /// Clock edges from the unit's inputs to its outputs, for a unit that is
    /// a fixed pipeline.
    const LATENCY: Option<usize> = None;
    /// This unit's latency, where a setting given at construction changes
    /// it (a setup sharing its products over several clocks).
    fn latency(&self) -> Option<usize> {
        Self::LATENCY
    }
    /// Records the units in this unit's fields ([`sub_units!`](crate::sub_units)).
    fn sub_units(&self, _units: &mut UnitWalk) {}
    /// Values given at construction that shape the circuit beside the
    /// type's parameters (a memory's depth), by name.
    fn settings(&self) -> Vec<(&'static str, String)> {
        Vec::new()
    }
}

/// A field that holds a unit, or an array of them (`field$0`, `field$1`, ...
/// in rust-hdl's paths).
pub trait UnitField {
    fn record(&self, name: &str, units: &mut UnitWalk);
}

impl<T: Unit> UnitField for T {
    fn record(&self, name: &str, units: &mut UnitWalk) {
        units.enter(name, UnitInfo::of(self));
        self.sub_units(units);
        units.leave();
    }
}

impl<T: Unit, const N: usize> UnitField for [T; N] {
    fn record(&self, name: &str, units: &mut UnitWalk) {
        for (i, unit) in self.iter().enumerate() {
            unit.record(&format!("{name}${i}"), units);
        }
    }
}

impl<T: Unit> UnitField for Vec<T> {
    fn record(&self, name: &str, units: &mut UnitWalk) {
        for (i, unit) in self.iter().enumerate() {
            unit.record(&format!("{name}${i}"), units);
        }
    }
}

/// `sub_units!(self, units, a, b, c)` records fields `a`, `b` and `c` (units
/// or arrays of units) of `self` in `units`: the body of
/// [`Unit::sub_units`].
#[macro_export]
macro_rules! sub_units {
    ($self: ident, $units: ident, $($field: ident),+) => {
        $($crate::unit::UnitField::record(&$self.$field, stringify!($field), $units);)+
    };
}

/// rust-hdl's register.
impl<T: Synth> Unit for DFF<T> {
    const LATENCY: Option<usize> = Some(1);
}

/// A unit's type, as the emitter names and describes it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnitInfo {
    /// The type's name without path or parameters: `CertifiedOrient3d`.
    pub type_name: String,
    /// Its generic parameters' names and values (`W = 24`, `T = Bits<25>`),
    /// then its [`Unit::settings`].
    pub parameters: Vec<(String, String)>,
    pub latency: Option<usize>,
}

impl UnitInfo {
    pub fn of<T: Unit>(unit: &T) -> UnitInfo {
        let (type_name, arguments) = parse_type_name(std::any::type_name::<T>());
        let names = UNIT_DOCS
            .iter()
            .find(|d| d.name == type_name)
            .map(|d| d.parameters)
            .unwrap_or(&[]);
        let mut parameters: Vec<(String, String)> = arguments
            .into_iter()
            .enumerate()
            .map(|(i, value)| {
                (
                    names
                        .get(i)
                        .map(|n| n.to_string())
                        .unwrap_or_else(|| format!("P{i}")),
                    value,
                )
            })
            .collect();
        parameters.extend(unit.settings().into_iter().map(|(n, v)| (n.to_string(), v)));
        UnitInfo {
            type_name,
            parameters,
            latency: unit.latency(),
        }
    }

    /// The module name stem: `CertifiedOrient3d` → `certified_orient3d`, `DelayLine` →
    /// `delay_line`, `CrossProduct2d` → `cross_product2d`.
    pub fn module_stem(&self) -> String {
        let mut stem = String::new();
        for (i, c) in self.type_name.chars().enumerate() {
            if c.is_ascii_uppercase() {
                if i > 0 {
                    stem.push('_');
                }
                stem.push(c.to_ascii_lowercase());
            } else {
                stem.push(c);
            }
        }
        stem
    }

    /// The type's doc and the names of its parameters (`build.rs`).
    pub fn doc(&self) -> Option<&'static UnitDoc> {
        UNIT_DOCS.iter().find(|d| d.name == self.type_name)
    }

    /// `CertifiedOrient3d<W = 24, D = 25, C = 49, O = 74>`, `SimpleDualPortRam<T =
    /// Bits<32>, A = 16>, depth = 512`.
    pub fn signature(&self) -> String {
        let generics = self
            .doc()
            .map_or(0, |d| d.parameters.len())
            .min(self.parameters.len());
        let list = |ps: &[(String, String)]| {
            ps.iter()
                .map(|(n, v)| format!("{n} = {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let mut text = self.type_name.clone();
        if generics > 0 {
            text.push_str(&format!("<{}>", list(&self.parameters[..generics])));
        }
        if generics < self.parameters.len() {
            text.push_str(&format!(", {}", list(&self.parameters[generics..])));
        }
        text
    }
}

/// A unit type's doc, from its source (`build.rs`).
#[derive(Debug)]
pub struct UnitDoc {
    pub name: &'static str,
    /// The generic parameters' names, in order.
    pub parameters: &'static [&'static str],
    /// The first paragraph of the struct's doc, or of its file's doc.
    pub purpose: &'static str,
}

include!(concat!(env!("OUT_DIR"), "/unit_docs.rs"));

/// `a::b::Name<c::Bits<25>, 4>` → (`Name`, [`Bits<25>`, `4`]).
fn parse_type_name(full: &str) -> (String, Vec<String>) {
    let (path, arguments) = match full.find('<') {
        Some(i) => (&full[..i], &full[i + 1..full.len() - 1]),
        None => (full, ""),
    };
    let name = path.rsplit("::").next().unwrap_or(path).to_string();
    let mut list = Vec::new();
    let (mut depth, mut current) = (0, String::new());
    for c in arguments.chars() {
        match c {
            '<' => depth += 1,
            '>' => depth -= 1,
            ',' if depth == 0 => {
                list.push(strip_paths(current.trim()));
                current.clear();
                continue;
            }
            _ => {}
        }
        current.push(c);
    }
    if !current.trim().is_empty() {
        list.push(strip_paths(current.trim()));
    }
    (name, list)
}

/// `rust_hdl_core::bits::Bits<25>` → `Bits<25>`.
fn strip_paths(argument: &str) -> String {
    let mut out = String::new();
    let mut word = String::new();
    for c in argument.chars() {
        if c.is_alphanumeric() || c == '_' || c == ':' {
            word.push(c);
        } else {
            out.push_str(word.rsplit("::").next().unwrap_or(&word));
            word.clear();
            out.push(c);
        }
    }
    out.push_str(word.rsplit("::").next().unwrap_or(&word));
    out
}

/// The units of a design by rust-hdl instance path (`top`, `top$a$b$0`).
pub type UnitMap = BTreeMap<String, UnitInfo>;

/// A walk over a top's units, recording each under its path.
pub struct UnitWalk {
    path: Vec<String>,
    units: UnitMap,
}

impl UnitWalk {
    fn enter(&mut self, name: &str, info: UnitInfo) {
        self.path.push(name.to_string());
        self.units.insert(self.path.join("$"), info);
    }

    fn leave(&mut self) {
        self.path.pop();
    }
}

/// rust-hdl's Verilog of a top, with the units at its instance paths.
#[derive(Debug)]
pub struct RawDesign {
    pub verilog: String,
    pub units: UnitMap,
}

impl RawDesign {
    /// `top` (connected) printed by rust-hdl and walked.
    pub fn of<T: Block + Unit>(top: &T) -> RawDesign {
        RawDesign {
            verilog: generate_verilog(top),
            units: unit_map(top),
        }
    }
}

/// The units of `top`, the top itself at `top`.
pub fn unit_map<T: Unit>(top: &T) -> UnitMap {
    let mut walk = UnitWalk {
        path: Vec::new(),
        units: UnitMap::new(),
    };
    top.record("top", &mut walk);
    walk.units
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn type_names() {
        let (name, args) = parse_type_name(
            "tritri_rtl::arith::delay_line::DelayLine<rust_hdl_core::bits::Bits<25>, 4>",
        );
        assert_eq!(name, "DelayLine");
        assert_eq!(args, vec!["Bits<25>", "4"]);
        let info = UnitInfo {
            type_name: "CrossProduct2d".into(),
            parameters: vec![],
            latency: None,
        };
        assert_eq!(info.module_stem(), "cross_product2d");
        assert_eq!(
            parse_type_name("a::Decision"),
            ("Decision".to_string(), vec![])
        );
    }

    /// Every unit type has a doc, and its parameters are named.
    #[test]
    fn docs_are_collected() {
        let orient = UNIT_DOCS
            .iter()
            .find(|d| d.name == "CertifiedOrient3d")
            .unwrap();
        assert_eq!(orient.parameters, &["W", "D", "C", "O"]);
        assert!(
            orient.purpose.starts_with("Orientation determinant"),
            "{}",
            orient.purpose
        );
        let delay = UNIT_DOCS.iter().find(|d| d.name == "DelayLine").unwrap();
        assert_eq!(delay.parameters, &["T", "N"]);
    }
}
