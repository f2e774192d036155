//! `tritri demo`: the main job on a built-in default, for a first run on a
//! fresh machine. It is a script of ordinary subcommands, run through the
//! same dispatcher as the command line, so it shows what a user would type:
//!
//! 1. `tritri gen --width 24 --out DIR/rtl`: the pipeline's Verilog, and
//!    `tritri gen --system ... --out DIR/system-rtl`: the system's, the one
//!    step 3 simulates;
//! 2. `tritri sim --engine model`: the built-in torus/sphere scene through
//!    the octree broad phase and the bounding-volume-aware system,
//!    bit-exact model and cycle model, compared with the exact software
//!    models;
//! 3. `tritri sim --engine verilator`: the same scene through the emitted
//!    system Verilog in Verilator, which must give the same pairs.

use std::path::PathBuf;
use std::process::ExitCode;
use tritri_rtl::system::DEFAULT_TRIANGLES_PER_BANK;

#[derive(clap::Args)]
pub struct Args {
    /// Where the RTL and the pair files go.
    #[arg(long, default_value = "build/demo")]
    out: PathBuf,
    /// Skip the Verilator run (it builds the system model first, about a minute).
    #[arg(long)]
    no_verilator: bool,
}

/// Runs each step as if typed after `tritri`; stops at the first failure.
pub fn run(
    args: Args,
    dispatch: impl Fn(Vec<String>) -> anyhow::Result<ExitCode>,
) -> anyhow::Result<ExitCode> {
    let out = args.out.display().to_string();
    let mut steps = vec![
        format!("gen --width 24 --out {out}/rtl"),
        format!("gen --system --width 24 --pipelines 2 --depth {DEFAULT_TRIANGLES_PER_BANK} --out {out}/system-rtl"),
        format!("sim --width 24 --pipelines 2 --engine model --out {out}/pairs_model.txt"),
    ];
    if !args.no_verilator {
        steps.push(format!(
            "sim --width 24 --pipelines 2 --engine verilator --out {out}/pairs_verilator.txt"
        ));
    }
    for step in &steps {
        eprintln!("\n$ tritri {step}");
        let code = dispatch(step.split_whitespace().map(String::from).collect())?;
        if code != ExitCode::SUCCESS {
            eprintln!("demo: step `tritri {step}` failed");
            return Ok(code);
        }
    }
    if !args.no_verilator {
        let read = |name: &str| {
            std::fs::read_to_string(args.out.join(name))
                .map_err(|e| anyhow::anyhow!("{out}/{name}: {e}"))
        };
        let (model, verilator) = (read("pairs_model.txt")?, read("pairs_verilator.txt")?);
        if model != verilator {
            eprintln!("demo: the Verilator pairs differ from the model's");
            return Ok(ExitCode::from(1));
        }
        eprintln!(
            "\ndemo: Verilator and the bit-exact model give the same {} pairs",
            model.lines().count()
        );
    }
    Ok(ExitCode::SUCCESS)
}
