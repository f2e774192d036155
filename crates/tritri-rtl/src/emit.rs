//! Verilog emission: from rust-hdl's single string to a directory an FPGA
//! flow can take as is.
//!
//! rust-hdl's `generate_verilog` prints one string with a top module `top`
//! and one module per instance, named by instance path (`top$stage$reg`),
//! with `$` inside identifiers. [`emit`] turns it into:
//!
//! * one module per file, `<module>.v`, named after the unit and its
//!   parameters (`tritri_pipeline_w24`, `tritri_pipeline_w24_<child>`), no
//!   `$` anywhere, each file with a header comment (purpose, parameters,
//!   generator) between `` `default_nettype none `` and
//!   `` `default_nettype wire ``;
//! * identifiers: rust-hdl's `a$b` becomes `a_b` (or `a__b` where `a_b`
//!   exists too), a field named like a SystemVerilog keyword (`table`,
//!   `cross`) gets the suffix `_kw`, instances get the prefix `u_`;
//! * modules that rust-hdl printed once per instance but are the same
//!   circuit merged into one (see [`modules`]);
//! * expressions re-printed with explicit widths where rust-hdl relies on
//!   Verilog's context widths (see [`widths`]), so the files are clean under
//!   `verilator --lint-only -Wall`;
//! * ports declared in the module header, Verilog-2001 style (see
//!   [`ansi_ports`]);
//! * unconditional assignments of rust-hdl's combinational block written as
//!   continuous `assign`s (see [`continuous_assigns`]), so that Verilator
//!   sees no false combinational loop through the children;
//! * on request, the multipliers on a device's DSP blocks with their
//!   registers, and a simulation model of the primitive (see
//!   [`dsp_mapping`]; `tritri gen --dsp ecp5`);
//! * `filelist.f`, a FuseSoC CAPI2 `<unit>.core`, a `README.md` with the
//!   port table, latency and throughput, and Yosys scripts
//!   `synth_generic.ys` / `synth_xilinx.ys` (run by [`crate::synth`]).
//!
//! ```
//! use rust_hdl::prelude::*;
//! use tritri_rtl::emit::{emit, UnitDescription};
//! use tritri_rtl::unit::{RawDesign, Unit};
//!
//! #[derive(LogicBlock, Default)]
//! struct Inverter {
//!     pub a: Signal<In, Bit>,
//!     pub y: Signal<Out, Bit>,
//! }
//! impl Logic for Inverter {
//!     #[hdl_gen]
//!     fn update(&mut self) {
//!         self.y.next = !self.a.val();
//!     }
//! }
//! impl Unit for Inverter {}
//! let mut uut = Inverter::default();
//! uut.connect_all();
//! let unit = UnitDescription::new("inverter", "Inverts a bit.")
//!     .port("a", "input bit")
//!     .port("y", "not a");
//! let design = emit(&RawDesign::of(&uut), &unit).unwrap();
//! assert_eq!(design.top, "inverter");
//! assert!(design.file("inverter.v").unwrap().contents.contains("`default_nettype none"));
//! ```

pub mod ansi_ports;
pub mod axi_copy_unit;
pub mod binning_unit_unit;
pub mod block_ram_mapping;
pub mod broad_phase_system_unit;
pub mod cell_classifier_unit;
pub mod cone_unit_unit;
pub mod continuous_assigns;
pub mod dram_binning_unit_unit;
pub mod dram_broad_phase_unit;
pub mod dsp_mapping;
pub mod leaf_reader_unit;
pub mod list_pass_unit;
pub mod memory_mapping;
pub mod modules;
pub mod octree_builder_unit;
pub mod owner_chain_filter_unit;
pub mod owner_filter_unit;
pub mod package;
pub mod part_selects;
pub mod patch_tessellator_unit;
pub mod plane_traversal_unit;
pub mod shared_rare_cases_unit;
pub mod statements;
pub mod tokens;
pub mod triangle_setup_unit;
pub mod triangle_voxelizer_unit;
pub mod voxel_units;
pub mod widths;

pub use crate::pipeline::pipeline_unit::{
    emit_pipeline, pipeline_unit, pipeline_unit_name, PipelineEmitError,
};

use crate::unit::RawDesign;
use std::path::Path;

/// What the emitter needs to know about a unit besides its Verilog.
#[derive(Clone, Debug, Default)]
pub struct UnitDescription {
    /// Top module name, lower_snake_case, with its parameters
    /// (`tritri_pipeline_w24`); children are named `<name>_<child>`.
    pub name: String,
    /// One line: what the unit computes.
    pub summary: String,
    /// Further paragraphs for the README and the top's header.
    pub details: Vec<String>,
    /// (name, value and meaning) of each generator parameter.
    pub parameters: Vec<(String, String)>,
    /// (port name, meaning); every port of the top must be described.
    pub ports: Vec<(String, String)>,
    /// Clock edges from an input to its result, if fixed.
    pub latency: Option<u64>,
    /// Throughput statement (`one triangle pair per clock`).
    pub throughput: String,
    /// FuseSoC VLNV vendor:library (`tritri:rtl`).
    pub vendor_library: String,
    /// `tritri-rtl 0.1.0 (rust-hdl 0.46.0)`, written in every header.
    pub generator: String,
}

impl UnitDescription {
    pub fn new(name: &str, summary: &str) -> Self {
        UnitDescription {
            name: name.to_string(),
            summary: summary.to_string(),
            vendor_library: "tritri:rtl".to_string(),
            generator: generator_name(),
            throughput: String::new(),
            ..Default::default()
        }
    }
    pub fn detail(mut self, paragraph: &str) -> Self {
        self.details.push(paragraph.to_string());
        self
    }
    pub fn parameter(mut self, name: &str, meaning: &str) -> Self {
        self.parameters
            .push((name.to_string(), meaning.to_string()));
        self
    }
    pub fn port(mut self, name: &str, meaning: &str) -> Self {
        self.ports.push((name.to_string(), meaning.to_string()));
        self
    }
    /// The three control ports every pipelined unit of the octree engine
    /// and the pipeline share, described once.
    pub fn pipelined_control_ports(self) -> Self {
        self.port("clock", "Clock; every register updates on the rising edge.")
            .port("reset", "Synchronous reset, active high: clears the valid bits (the datapath has no reset).")
            .port("advance", "Clock enable: while low, every register holds (back-pressure).")
    }
    pub fn latency(mut self, cycles: u64) -> Self {
        self.latency = Some(cycles);
        self
    }
    pub fn throughput(mut self, text: &str) -> Self {
        self.throughput = text.to_string();
        self
    }
}

/// `tritri-rtl <version> (rust-hdl 0.46.0)`.
pub fn generator_name() -> String {
    format!("tritri-rtl {} (rust-hdl 0.46.0)", env!("CARGO_PKG_VERSION"))
}

/// A port of the emitted top module.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Port {
    pub name: String,
    pub direction: String,
    pub bits: usize,
    pub signed: bool,
}

/// One file of an emitted design, by path relative to the output directory.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EmittedFile {
    pub path: String,
    pub contents: String,
}

/// The emitted directory, in memory.
#[derive(Clone, Debug)]
pub struct EmittedDesign {
    /// Top module name.
    pub top: String,
    /// Module names, top first.
    pub modules: Vec<String>,
    pub ports: Vec<Port>,
    /// Every file: the Verilog (top first), then filelist.f, the core, the
    /// Yosys scripts and the README.
    pub files: Vec<EmittedFile>,
}

#[derive(Debug, thiserror::Error)]
pub enum EmitError {
    #[error(transparent)]
    Modules(#[from] modules::ModuleError),
    #[error("port `{0}` of the top module has no description")]
    UndescribedPort(String),
    #[error("the description names port `{0}`, which the top module does not have")]
    UnknownPort(String),
    #[error(transparent)]
    UnmappedMultiplier(#[from] dsp_mapping::UnmappedMultiplier),
    #[error("unit name `{0}` is not a lower_snake_case Verilog identifier")]
    BadUnitName(String),
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// Post-processes rust-hdl's Verilog for `unit` (see the module docs).
pub fn emit(raw: &RawDesign, unit: &UnitDescription) -> Result<EmittedDesign, EmitError> {
    emit_with(raw, unit, EmitOptions::default())
}

/// Switches for [`emit_with`].
#[derive(Clone, Copy, Debug)]
pub struct EmitOptions {
    /// Run the [`widths`] pass (on by default). Off, the output differs from
    /// the default only in its expressions: the formal equivalence check of
    /// the pass compares the two.
    pub explicit_widths: bool,
    /// Run the [`continuous_assigns`] pass (on by default); the same formal
    /// check covers it.
    pub continuous_assigns: bool,
    /// Declare the ports in the module headers ([`ansi_ports`], on by
    /// default); the same formal check covers it.
    pub ansi_ports: bool,
    /// How the multipliers reach the DSP blocks ([`dsp_mapping`]; inferred
    /// by default).
    pub multipliers: dsp_mapping::MultiplierMapping,
}

impl EmitOptions {
    /// rust-hdl's text, only split, renamed and merged: the reference the
    /// formal equivalence check compares the default emission with.
    pub fn no_rewrites() -> Self {
        EmitOptions {
            explicit_widths: false,
            continuous_assigns: false,
            ansi_ports: false,
            multipliers: dsp_mapping::MultiplierMapping::Inferred,
        }
    }
}

impl Default for EmitOptions {
    fn default() -> Self {
        EmitOptions {
            explicit_widths: true,
            continuous_assigns: true,
            ansi_ports: true,
            multipliers: dsp_mapping::MultiplierMapping::Inferred,
        }
    }
}

/// [`emit`] with options.
pub fn emit_with(
    raw: &RawDesign,
    unit: &UnitDescription,
    options: EmitOptions,
) -> Result<EmittedDesign, EmitError> {
    let valid_name = unit
        .name
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_lowercase())
        && unit
            .name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
    if !valid_name {
        return Err(EmitError::BadUnitName(unit.name.clone()));
    }
    let rust_hdl_verilog = part_selects::constant_part_selects(&raw.verilog);
    let mut modules = modules::normalize(&rust_hdl_verilog, &unit.name, &raw.units)?;
    if options.explicit_widths {
        for m in modules.iter_mut() {
            widths::fix_module(m);
        }
    }
    if options.continuous_assigns {
        for m in modules.iter_mut() {
            continuous_assigns::continuous_assigns(m);
        }
    }
    let ports = package::top_ports(&modules[0]);
    if options.ansi_ports {
        for m in modules.iter_mut() {
            ansi_ports::ansi_ports(m);
        }
    }
    for p in &ports {
        if !unit.ports.iter().any(|(n, _)| n == &p.name) {
            return Err(EmitError::UndescribedPort(p.name.clone()));
        }
    }
    for (n, _) in &unit.ports {
        if !ports.iter().any(|p| &p.name == n) {
            return Err(EmitError::UnknownPort(n.clone()));
        }
    }
    let mut models = Vec::new();
    // The ECP5 primitives with their registers: the multipliers on
    // MULT18X18D, and the memories with an output register on DP16KD.
    if options.multipliers == dsp_mapping::MultiplierMapping::Ecp5 {
        let mut mapped = false;
        for m in modules.iter_mut() {
            mapped |= dsp_mapping::map_ecp5(m)?;
        }
        if mapped {
            models.push(EmittedFile {
                path: dsp_mapping::ECP5_MODEL_FILE.into(),
                contents: dsp_mapping::ECP5_MULT18X18D_MODEL.into(),
            });
        }
        let mut mapped = false;
        for m in modules.iter_mut() {
            mapped |= block_ram_mapping::map_ecp5(m);
        }
        if mapped {
            models.push(EmittedFile {
                path: block_ram_mapping::ECP5_DP16KD_MODEL_FILE.into(),
                contents: block_ram_mapping::ECP5_DP16KD_MODEL.into(),
            });
        }
    }
    let files = package::files(&modules, &ports, unit, &models);
    Ok(EmittedDesign {
        top: unit.name.clone(),
        modules: modules.iter().map(|m| m.name.clone()).collect(),
        ports,
        files,
    })
}

impl EmittedDesign {
    pub fn file(&self, path: &str) -> Option<&EmittedFile> {
        self.files.iter().find(|f| f.path == path)
    }

    /// The Verilog files, top first.
    pub fn verilog_files(&self) -> impl Iterator<Item = &EmittedFile> {
        self.files.iter().filter(|f| f.path.ends_with(".v"))
    }

    /// Writes every file into `dir` (created if needed). Files that a
    /// previous emission listed in `dir/filelist.f` and this one does not
    /// produce are removed, and so is that emission's FuseSoC core (named
    /// by its top, the list's shortest name), so the directory never holds
    /// stale modules or a core listing them. A README.md that no emission
    /// wrote (there is no `filelist.f` beside it) is the user's: an error,
    /// and nothing is written.
    pub fn write_to(&self, dir: &Path) -> std::io::Result<()> {
        let old = std::fs::read_to_string(dir.join("filelist.f")).ok();
        let readme = dir.join("README.md");
        if old.is_none() && readme.exists() && self.file("README.md").is_some() {
            return Err(std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                format!(
                    "{} was not written by tritri (no filelist.f beside it): not overwriting it; write into another directory",
                    readme.display()
                ),
            ));
        }
        std::fs::create_dir_all(dir)?;
        if let Some(old) = old {
            let listed: Vec<&str> = old
                .lines()
                .map(str::trim)
                .filter(|l| l.ends_with(".v"))
                .collect();
            for line in &listed {
                let stale = !self.files.iter().any(|f| f.path == *line);
                if stale && !line.contains('/') {
                    let _ = std::fs::remove_file(dir.join(line));
                }
            }
            // Every module's file is `<top>_<module>.v`: the top's is the
            // shortest name.
            let top = listed.iter().min_by_key(|l| l.len());
            if let Some(top) = top.and_then(|l| l.strip_suffix(".v")) {
                let core = format!("{top}.core");
                if !top.contains('/') && self.file(&core).is_none() {
                    let _ = std::fs::remove_file(dir.join(core));
                }
            }
        }
        for f in &self.files {
            std::fs::write(dir.join(&f.path), &f.contents)?;
        }
        Ok(())
    }
}
