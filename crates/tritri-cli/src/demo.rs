//! `tritri demo`: the main job on a built-in default, for a first run on a
//! fresh machine. It is a script of ordinary subcommands, run through the
//! same dispatcher as the command line, so it shows what a user would type:
//!
//! 1. `tritri gen --dram-broad-phase ... --out DIR/rtl`: the Verilog of the
//!    accelerator that fits the ECP5-85 (the scene in DRAM behind an AXI4
//!    port, binned, tested and reported once in hardware), the design
//!    step 3 simulates;
//! 2. `tritri sim --engine model`: the built-in torus/sphere scene through
//!    that design's clock-exact model and bit-exact narrow phase, the
//!    uncertain verdicts decided again on the f64 coordinates, compared
//!    with the exact software models and timed against the software;
//! 3. `tritri sim --engine verilator`: the same scene through the emitted
//!    top in Verilator against the AXI4 memory model, which must give the
//!    same pairs (and the model's walk, clock for clock).

use std::path::PathBuf;
use std::process::ExitCode;
use tritri_cosim::dram_query::TABLE_WORDS;

#[derive(clap::Args)]
pub struct Args {
    /// Where the RTL and the pair files go.
    #[arg(long, default_value = "build/demo")]
    out: PathBuf,
    /// Skip the Verilator run (it builds the top's model first, a few minutes).
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
        format!("gen --dram-broad-phase --width 16 --pipelines 1 --rare-cases shared --triangles {TABLE_WORDS} --slots {TABLE_WORDS} --data-bits 256 --out {out}/rtl"),
        format!("sim --engine model --out {out}/pairs_model.txt"),
    ];
    if !args.no_verilator {
        steps.push(format!(
            "sim --engine verilator --out {out}/pairs_verilator.txt"
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
