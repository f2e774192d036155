//! `tritri`: the command line of the tritri toolkit.
//!
//! One module per subcommand; each has an `Args` struct (clap derive) and a
//! `run(args) -> anyhow::Result<ExitCode>`. To add a subcommand, add its
//! module, a variant to [`Command`] and an arm to the `match` in `main`.
//!
//! Exit codes: 0 success; 1 a failed check, a runtime or I/O failure; 2
//! bad input or bad usage (nothing is computed); 129 / 130 / 143 interrupted by
//! SIGHUP / SIGINT / SIGTERM (running tools stopped, work directories removed).

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::process::ExitCode;

mod bench;
mod bezier;
mod chapter5;
mod classify;
mod demo;
mod eval;
mod gen;
mod input;
mod model_files;
mod octree;
mod output_file;
mod progress;
mod report;
mod scene_input;
mod sim;
mod stdout;
mod voxelize;

#[derive(Parser)]
#[command(
    name = "tritri",
    version,
    about = "Devillers-Guigue triangle-triangle tests in exact, float and fixed-point arithmetic",
    after_help = "Exit status: 0 done; 1 a failed check or a runtime / I/O failure; 2 bad input or usage (nothing computed); \
                  129 / 130 / 143 interrupted by SIGHUP / SIGINT / SIGTERM (tools stopped, temporary files removed)."
)]
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
    /// Speed against error: one HTML page (plots and tables), JSON and CSV, per coordinate width, on pair files and a scene.
    Report(report::Args),
    /// Co-simulation throughput: the same pairs through the model, rust-hdl, Verilator and Icarus, with mismatches.
    Bench(bench::Args),
    /// Voxelize a mesh, surface or solid, exactly: write an octree (.oct), .binvox, .vox, its boundary (.obj) or a render (.png).
    Voxelize(voxelize::Args),
    /// The octree engine on model files: plane classification, clipping, union / intersection / difference, conversion, renders.
    Octree(octree::Args),
    /// Bezier patches with the level of detail of bezier_lod_gpu.txt: render with cone-of-normals culling, silhouettes and distance levels.
    Bezier(bezier::Args),
    /// The main job on a built-in default: emit the RTL, run the built-in scene in the model and in Verilator.
    Demo(demo::Args),
}

fn main() -> ExitCode {
    end_quietly_on_closed_pipe();
    clean_up_on_interrupt();
    let matches = command_line().get_matches();
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let result = dispatch(cli, &matches);
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(1)
        }
    }
}

/// The command line, where every option that takes a value takes a
/// negative number too: `--depth -1` is then refused by the option's own
/// parser, which names the valid range, instead of by clap as "unexpected
/// argument '-1'".
fn command_line() -> clap::Command {
    fn negative_numbers_are_values(command: clap::Command) -> clap::Command {
        command
            .mut_args(|arg| {
                if arg.get_action().takes_values() {
                    arg.allow_negative_numbers(true)
                } else {
                    arg
                }
            })
            .mut_subcommands(negative_numbers_are_values)
    }
    negative_numbers_are_values(Cli::command())
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

/// Ctrl-C (SIGINT), SIGTERM and SIGHUP (the terminal closed) stop the
/// simulators and tools `tritri`
/// started and remove its work directories (`tools::interrupt`), then end
/// with the conventional status 128 + signal. The signals are blocked
/// in every thread (the mask is inherited; children get a clean one) and
/// taken by one thread with `sigwait`, where cleaning up may lock and
/// allocate, which a signal handler may not.
fn clean_up_on_interrupt() {
    #[cfg(unix)]
    // SAFETY: called in `main` before any other thread starts; the set is
    // initialized by sigemptyset before use.
    unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        libc::sigaddset(&mut set, libc::SIGINT);
        libc::sigaddset(&mut set, libc::SIGTERM);
        libc::sigaddset(&mut set, libc::SIGHUP);
        libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut());
        std::thread::spawn(move || {
            let mut signal: libc::c_int = 0;
            if libc::sigwait(&set, &mut signal) != 0 {
                return;
            }
            let (groups, temporaries) = tritri_rtl::tools::interrupt::clean_up();
            let name = match signal {
                libc::SIGINT => "SIGINT",
                libc::SIGHUP => "SIGHUP",
                _ => "SIGTERM",
            };
            eprintln!("\ntritri: {name}: stopped {groups} running tool(s), removed {temporaries} temporary file(s) and directory(ies)");
            std::process::exit(128 + signal);
        });
    }
}

/// The options of subcommand `name` given on the command line (not left at
/// their defaults), by their ids (`grid_bits`): a design refuses those that
/// do not apply to it by name.
fn given_options(matches: &clap::ArgMatches, name: &str) -> Vec<String> {
    let Some(sub) = matches.subcommand_matches(name) else {
        return Vec::new();
    };
    sub.ids()
        .filter(|id| sub.value_source(id.as_str()) == Some(clap::parser::ValueSource::CommandLine))
        .map(|id| id.to_string())
        .collect()
}

/// Runs one parsed command line (`matches`, its raw form).
fn dispatch(cli: Cli, matches: &clap::ArgMatches) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Classify(args) => classify::run(args),
        Command::Eval(args) => eval::run(args),
        Command::Sim(args) => sim::run(args, &given_options(matches, "sim")),
        Command::Chapter5(args) => chapter5::run(args),
        Command::Gen(args) => gen::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Report(args) => report::run(args),
        Command::Voxelize(args) => voxelize::run(args),
        Command::Bezier(args) => bezier::run(args),
        Command::Octree(args) => octree::run(args),
        Command::Demo(args) => demo::run(args, |words| {
            let argv = std::iter::once("tritri".to_string()).chain(words);
            let matches = command_line().try_get_matches_from(argv)?;
            dispatch(Cli::from_arg_matches(&matches)?, &matches)
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every option that takes a value, with the subcommands that lead to
    /// it: `(["octree", "clip"], "--plane")`.
    fn options(command: &clap::Command, path: &[String], out: &mut Vec<(Vec<String>, String)>) {
        for arg in command.get_arguments() {
            if let (Some(long), true) = (arg.get_long(), arg.get_action().takes_values()) {
                out.push((path.to_vec(), format!("--{long}")));
            }
        }
        for sub in command.get_subcommands() {
            let mut path = path.to_vec();
            path.push(sub.get_name().to_string());
            options(sub, &path, out);
        }
    }

    /// A value an option refuses is refused with what it takes: Rust's
    /// bare parse messages ("invalid digit found in string") name no
    /// range, and a negative number is the option's value, not a flag.
    #[test]
    fn every_option_refuses_a_bad_number_by_naming_what_it_takes() {
        let mut all = Vec::new();
        options(&command_line(), &[], &mut all);
        assert!(all.len() > 50, "{} options", all.len());
        let mut unclear = Vec::new();
        for (path, option) in &all {
            for value in ["-1", "1e3", "x"] {
                let argv = std::iter::once("tritri".to_string())
                    .chain(path.iter().cloned())
                    .chain([option.clone(), value.to_string()]);
                let Err(e) = command_line().try_get_matches_from(argv) else {
                    continue;
                };
                let message = e.to_string();
                let bare = [
                    "invalid digit",
                    "invalid float literal",
                    "unexpected argument '-1'",
                    "too large",
                    "too small",
                ];
                if bare.iter().any(|b| message.contains(b)) {
                    unclear.push(format!(
                        "{} {option} {value}: {}",
                        path.join(" "),
                        message.lines().next().unwrap_or("")
                    ));
                }
            }
        }
        assert!(unclear.is_empty(), "{}", unclear.join("\n"));
    }
}
