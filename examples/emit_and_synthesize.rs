//! Emit a pipeline configuration as Verilog, synthesize it with Yosys for
//! Xilinx 7-series, and read back its resource report.
//!
//! ```sh
//! cargo run --release --example emit_and_synthesize [-- WIDTH [DIR]]
//! ```
//!
//! WIDTH is the coordinate width (default 8, which synthesizes in seconds;
//! 24 takes minutes), DIR where the files go (default: a temporary
//! directory). Needs `yosys` on PATH. The program fails if the report has
//! no LUTs or no multipliers, or the README lacks the port table.

use tritri_rtl::emit::emit_pipeline;
use tritri_rtl::synth::{synthesize, Target};

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let width: usize = args.next().map(|w| w.parse()).transpose()?.unwrap_or(8);
    let dir = args
        .next()
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join(format!("tritri-example-w{width}")));

    // One module per file, filelist.f, a FuseSoC core, Yosys scripts, README.
    let design = emit_pipeline(width)?;
    design.write_to(&dir)?;
    println!(
        "wrote {} ({} modules) to {}",
        design.top,
        design.modules.len(),
        dir.display()
    );
    let readme = std::fs::read_to_string(dir.join("README.md"))?;
    anyhow::ensure!(
        readme.contains("| `in_x0` |"),
        "the README has no port table"
    );

    // Yosys synth_xilinx on the emitted files (the script is in the directory).
    let report = synthesize(&dir, Target::Xilinx)?;
    println!(
        "Yosys synth_xilinx: {} LUT, {} FF, {} DSP48E1",
        report.luts(),
        report.flip_flops(),
        report.dsps()
    );
    anyhow::ensure!(
        report.luts() > 0 && report.dsps() > 0,
        "an implausible report: {report:?}"
    );
    Ok(())
}
