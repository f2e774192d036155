//! `tritri gen [--width W]... [--out DIR] [--synth]`
//!
//! Writes the synthesizable Verilog of the triangle pipeline for each
//! coordinate width W (default 24, the thesis's): one module per file, named
//! `tritri_pipeline_w<W>*.v`, with `filelist.f`, a FuseSoC core, Yosys
//! scripts and a README with the port table, latency and throughput.
//!
//! Output directory: with one width, `--out DIR` (default `rtl-out/w<W>`,
//! relative to the current directory); with several, `<DIR>/w<W>` for each
//! (default `rtl-out/w<W>`). A directory is updated in place: files of an
//! earlier emission that this one no longer produces are removed.
//!
//! `--synth` then runs Yosys (generic `synth` and `synth_xilinx`) in each
//! directory and prints a resource table (generic cells; LUT, FF, DSP48E1,
//! CARRY4, SRL for Xilinx 7-series), also written to `resources.md` next to
//! the Verilog, with Yosys' reports `stat_generic.txt` and `stat_xilinx.txt`.
//! `--synth xilinx` or `--synth generic` runs one of the two (the generic
//! flow maps the wide multipliers to gates and takes minutes).
//!
//! Exit status: 0 done; 1 a tool failed; 2 a width without a pipeline (the
//! message names it and lists the supported widths) or bad usage.

use anyhow::Context;
use std::path::PathBuf;
use std::process::ExitCode;
use tritri_rtl::configurations::SUPPORTED_WIDTHS;
use tritri_rtl::emit::{emit_pipeline, pipeline_unit_name};
use tritri_rtl::synth::{resource_table, synthesize, ResourceRow, Target};

#[derive(clap::Args)]
pub struct Args {
    /// Coordinate width in bits; repeat or separate with commas for several.
    #[arg(long, value_delimiter = ',', default_value = "24")]
    width: Vec<usize>,
    /// Output directory (one width) or parent directory (several widths).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Run Yosys and print a resource table: `all` (default when given
    /// without a value), `xilinx` or `generic`.
    #[arg(long, num_args = 0..=1, default_missing_value = "all", value_parser = ["all", "xilinx", "generic"])]
    synth: Option<String>,
}

/// Where width `width` goes.
fn out_dir(args: &Args, width: usize) -> PathBuf {
    match (&args.out, args.width.len()) {
        (Some(dir), 1) => dir.clone(),
        (Some(parent), _) => parent.join(format!("w{width}")),
        (None, _) => PathBuf::from("rtl-out").join(format!("w{width}")),
    }
}

pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    for &w in &args.width {
        if !SUPPORTED_WIDTHS.contains(&w) {
            eprintln!("error: no pipeline for width {w}: supported widths are {SUPPORTED_WIDTHS:?}");
            return Ok(ExitCode::from(2));
        }
    }
    let mut rows = Vec::new();
    for &w in &args.width {
        let dir = out_dir(&args, w);
        let design = emit_pipeline(w).with_context(|| format!("emitting the {w}-bit pipeline"))?;
        design.write_to(&dir).with_context(|| format!("writing {}", dir.display()))?;
        eprintln!(
            "wrote {} ({} modules, {} files) to {}",
            design.top,
            design.modules.len(),
            design.files.len(),
            dir.display()
        );
        if let Some(which) = &args.synth {
            let mut row = ResourceRow { unit: pipeline_unit_name(w), generic: None, xilinx: None };
            if which == "all" || which == "xilinx" {
                eprintln!("yosys synth_xilinx in {} ...", dir.display());
                row.xilinx = Some(synthesize(&dir, Target::Xilinx)?);
            }
            if which == "all" || which == "generic" {
                eprintln!("yosys synth (generic) in {} ...", dir.display());
                row.generic = Some(synthesize(&dir, Target::Generic)?);
            }
            std::fs::write(dir.join("resources.md"), resource_table(std::slice::from_ref(&row)))?;
            rows.push(row);
        }
    }
    if !rows.is_empty() {
        print!("{}", resource_table(&rows));
    }
    Ok(ExitCode::SUCCESS)
}
