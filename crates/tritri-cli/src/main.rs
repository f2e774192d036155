//! `tritri`: the command line of the tritri toolkit.
//!
//! One module per subcommand; each has an `Args` struct (clap derive) and a
//! `run(args) -> anyhow::Result<ExitCode>`. To add a subcommand, add its
//! module, a variant to [`Command`] and an arm to the `match` in `main`.
//!
//! Exit codes: 0 success; 1 a failed check or an internal error; 2 bad
//! input (unreadable or malformed records: the good ones are still
//! processed) or bad usage.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod bench;
mod classify;
mod demo;
mod eval;
mod gen;
mod input;
mod chapter5;
mod scene_input;
mod sim;

#[derive(Parser)]
#[command(name = "tritri", version, about = "Devillers-Guigue triangle-triangle tests in exact, float and fixed-point arithmetic")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Decide every triangle pair of a file: prints 1 (intersect) or 0 per pair.
    Classify(classify::Args),
    /// Compare every arithmetic with the exact answer: errors and speed.
    Eval(eval::Args),
    /// Run the bounding-volume-aware system on two objects (default: the built-in scene).
    Sim(sim::Args),
    /// The thesis's chapter-5 comparison: 5/25/50/75 % of the polygons in the common BV, hardware vs software time.
    Chapter5(chapter5::Args),
    /// Write the pipeline's (or with --system the whole system's) Verilog: one module per file, filelist, FuseSoC core, README; --synth runs Yosys.
    Gen(gen::Args),
    /// Co-simulation throughput: the same pairs through the model, rust-hdl, Verilator and Icarus, with mismatches.
    Bench(bench::Args),
    /// The main job on a built-in default: emit the RTL, run the built-in scene in the model and in Verilator.
    Demo(demo::Args),
}

fn main() -> ExitCode {
    end_quietly_on_closed_pipe();
    let result = dispatch(Cli::parse());
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(1)
        }
    }
}

/// `tritri eval @hard | head -1`: when the reader closes the pipe, end as
/// Unix tools do (killed by SIGPIPE, no message) instead of Rust's default
/// of ignoring the signal and panicking in the next `println!`.
fn end_quietly_on_closed_pipe() {
    #[cfg(unix)]
    // SAFETY: called first in `main`, before any thread starts; SIG_DFL is a
    // valid disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// Runs one parsed command line.
fn dispatch(cli: Cli) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Classify(args) => classify::run(args),
        Command::Eval(args) => eval::run(args),
        Command::Sim(args) => sim::run(args),
        Command::Chapter5(args) => chapter5::run(args),
        Command::Gen(args) => gen::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Demo(args) => demo::run(args, |words| {
            let argv = std::iter::once("tritri".to_string()).chain(words);
            dispatch(Cli::try_parse_from(argv)?)
        }),
    }
}
