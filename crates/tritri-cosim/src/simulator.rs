//! The one place that compiles a testbench with emitted Verilog and runs
//! it, in Icarus Verilog or Verilator. The pipeline, the system and the
//! octree classifier each describe their testbench ([`Testbench`]) and
//! read its output file; how the simulators are invoked, cached and
//! cleaned up is written here once.
//!
//! * **Icarus** (`iverilog -g2012`, `vvp`) compiles in about a second, so
//!   every run compiles into a fresh work directory.
//! * **Verilator** (`verilator --binary`) builds C++ for tens of seconds
//!   to minutes, so the executable is cached under
//!   `$TRITRI_CACHE_DIR/verilator/<key>` (default `$XDG_CACHE_HOME/tritri`,
//!   else `~/.cache/tritri`), the key a hash of every source file, define,
//!   parameter, flag and the Verilator version. Builds go to a private
//!   staging directory and are renamed into place, so parallel runs never
//!   see half a build.
//!
//! A traced build (`trace`) defines `TRITRI_VCD`, which every testbench
//! uses to dump a VCD waveform to the file named by `+vcd=PATH`; Verilator
//! also needs `--trace`, and caches that build under a key of its own
//! (tracing slows every cycle, so the plain build stays the fast one).
//!
//! Work directories and the simulator processes are registered with
//! `tritri_rtl::tools::interrupt`, so an interrupted run leaves nothing.

use anyhow::Context as _;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;
use tritri_rtl::tools::{
    block_sigpipe_in_this_thread, make_fifo, release_fifo_writer, run, run_with_lines, IVERILOG,
    VERILATOR, VVP,
};

/// Which simulator runs emitted Verilog.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Simulator {
    Icarus,
    Verilator,
}

/// A testbench and the design under test, ready to compile.
#[derive(Clone, Debug)]
pub struct Testbench {
    /// The testbench's top module.
    pub top: String,
    /// Source files `(name, contents)`, the testbench first.
    pub files: Vec<(String, String)>,
    /// Preprocessor defines, `NAME=VALUE` or `NAME`.
    pub defines: Vec<String>,
    /// Parameters of the top module, `(name, value)`.
    pub parameters: Vec<(String, String)>,
    /// Verilator's C++ optimization level (`-O1` builds large designs
    /// faster; `-O2` runs small ones faster).
    pub c_optimization: u8,
    /// Build with waveform dumping (module docs).
    pub trace: bool,
}

/// A compiled testbench, ready to run.
pub struct Compiled {
    simulator: Simulator,
    /// The `vvp` image (Icarus) or the executable (Verilator).
    image: PathBuf,
    /// Seconds spent compiling (0 for a cached Verilator build).
    pub build_seconds: f64,
    /// Icarus's image lives in a work directory that goes with it.
    _work: Option<WorkDir>,
}

/// Compiles `testbench` in `simulator` (Verilator: or reuses the cache).
pub fn compile(simulator: Simulator, testbench: &Testbench) -> anyhow::Result<Compiled> {
    match simulator {
        Simulator::Icarus => compile_icarus(testbench),
        Simulator::Verilator => compile_verilator(testbench),
    }
}

impl Compiled {
    /// Runs the compiled testbench with `+plusargs`; a non-zero exit is an
    /// error carrying the simulator's output.
    pub fn run(&self, plusargs: &[String]) -> anyhow::Result<Output> {
        self.run_with_lines(plusargs, &mut |_| {})
    }

    /// [`Compiled::run`], and `on_line` sees each line the testbench
    /// prints as it prints it.
    pub fn run_with_lines(
        &self,
        plusargs: &[String],
        on_line: &mut dyn FnMut(&str),
    ) -> anyhow::Result<Output> {
        let mut command = match self.simulator {
            Simulator::Icarus => {
                let mut c = Command::new(VVP.locate()?);
                c.arg("-n").arg(&self.image);
                c
            }
            Simulator::Verilator => Command::new(&self.image),
        };
        command.args(plusargs);
        Ok(run_with_lines(&mut command, on_line)?)
    }
}

impl Testbench {
    fn trace_define(&self) -> Option<&'static str> {
        self.trace.then_some("-DTRITRI_VCD")
    }

    /// Writes the sources into `dir`; returns their paths, testbench first.
    fn write_into(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        self.files
            .iter()
            .map(|(name, contents)| {
                let path = dir.join(name);
                std::fs::write(&path, contents)?;
                Ok(path)
            })
            .collect()
    }
}

fn compile_icarus(testbench: &Testbench) -> anyhow::Result<Compiled> {
    let iverilog = IVERILOG.locate()?;
    VVP.locate()?;
    let work = WorkDir::new("icarus").context("creating the Icarus work directory")?;
    let sources = testbench
        .write_into(&work.path)
        .context("writing the Verilog sources")?;
    let started = Instant::now();
    let image = work.join("tb.vvp");
    let mut command = Command::new(iverilog);
    command
        .arg("-g2012")
        .arg("-o")
        .arg(&image)
        .arg("-s")
        .arg(&testbench.top);
    command.args(testbench.defines.iter().map(|d| format!("-D{d}")));
    command.args(
        testbench
            .parameters
            .iter()
            .map(|(k, v)| format!("-P{}.{k}={v}", testbench.top)),
    );
    command.args(testbench.trace_define()).args(&sources);
    run(&mut command).context("compiling in Icarus")?;
    Ok(Compiled {
        simulator: Simulator::Icarus,
        image,
        build_seconds: started.elapsed().as_secs_f64(),
        _work: Some(work),
    })
}

fn compile_verilator(testbench: &Testbench) -> anyhow::Result<Compiled> {
    VERILATOR.locate()?;
    let version = String::from_utf8_lossy(&run(VERILATOR.command()?.arg("--version"))?.stdout)
        .trim()
        .to_string();
    let jobs = std::thread::available_parallelism()
        .map_or(2, |n| n.get())
        .to_string();
    let mut flags: Vec<String> = [
        "--binary",
        "-j",
        &jobs,
        "--top-module",
        &testbench.top,
        "-Mdir",
        "obj",
        "-Wno-fatal",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    // Optimize the model for run time: the build is cached.
    flags.extend(
        [
            "-O3",
            "--x-assign",
            "fast",
            "--x-initial",
            "fast",
            "-CFLAGS",
        ]
        .map(String::from),
    );
    flags.push(format!("-O{}", testbench.c_optimization));
    flags.extend(testbench.defines.iter().map(|d| format!("-D{d}")));
    flags.extend(
        testbench
            .parameters
            .iter()
            .map(|(k, v)| format!("-G{k}={v}")),
    );
    if testbench.trace {
        flags.extend(["--trace", "-DTRITRI_VCD"].map(String::from));
    }

    let mut parts: Vec<&str> = vec![&version];
    parts.extend(flags.iter().filter(|f| *f != &jobs).map(String::as_str));
    for (name, contents) in &testbench.files {
        parts.extend([name.as_str(), contents.as_str()]);
    }
    let key = format!(
        "{}-{:016x}{}",
        testbench.top,
        fingerprint(parts),
        if testbench.trace { "-vcd" } else { "" }
    );
    let dir = cache_root().join("verilator").join(&key);
    let exe_name = format!("V{}", testbench.top);
    let exe = dir.join(&exe_name);
    if exe.is_file() {
        return Ok(Compiled {
            simulator: Simulator::Verilator,
            image: exe,
            build_seconds: 0.0,
            _work: None,
        });
    }

    let started = Instant::now();
    std::fs::create_dir_all(cache_root().join("verilator"))
        .context("creating the Verilator cache directory")?;
    let staging = WorkDir::new(&format!("verilator-build-{key}"))?;
    let sources = testbench
        .write_into(&staging.path)
        .context("writing the Verilog sources")?;
    let mut command = VERILATOR.command()?;
    // The compiler's temporary files go into the staging directory too, so
    // an interrupted build leaves nothing behind.
    command
        .current_dir(&staging.path)
        .env("TMPDIR", &staging.path)
        .args(&flags)
        .args(&sources);
    run(&mut command).context("building the Verilator model")?;
    let built = staging.path.join("obj").join(&exe_name);
    anyhow::ensure!(
        built.is_file(),
        "verilator --binary did not produce {}",
        built.display()
    );
    // Publish: copy the executable into a fresh directory, then rename it
    // into place; if someone else published the same key first, theirs is
    // as good.
    let publish = dir.with_extension(format!("tmp{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&publish);
    std::fs::create_dir_all(&publish)?;
    std::fs::copy(&built, publish.join(&exe_name))?;
    if std::fs::rename(&publish, &dir).is_err() {
        let _ = std::fs::remove_dir_all(&publish);
    }
    anyhow::ensure!(
        exe.is_file(),
        "the Verilator cache entry {} is incomplete",
        dir.display()
    );
    Ok(Compiled {
        simulator: Simulator::Verilator,
        image: exe,
        build_seconds: started.elapsed().as_secs_f64(),
        _work: None,
    })
}

/// The cache root (see the module docs).
pub fn cache_root() -> PathBuf {
    if let Some(dir) = std::env::var_os("TRITRI_CACHE_DIR") {
        return PathBuf::from(dir);
    }
    if let Some(dir) = std::env::var_os("XDG_CACHE_HOME") {
        return PathBuf::from(dir).join("tritri");
    }
    if let Some(home) = std::env::var_os("HOME") {
        return PathBuf::from(home).join(".cache").join("tritri");
    }
    std::env::temp_dir().join("tritri-cache")
}

/// FNV-1a over the strings, each ended by a zero byte: a hash that is the
/// same in every build, as a cache key must be.
pub fn fingerprint<'a>(parts: impl IntoIterator<Item = &'a str>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for part in parts {
        for &b in part.as_bytes().iter().chain(b"\0") {
            h ^= b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

/// A directory removed on drop (unless `TRITRI_KEEP_WORK` is set, for
/// debugging), and on an interrupt. The first one a process makes also
/// removes those a killed run left behind ([`sweep_abandoned`]).
pub struct WorkDir {
    pub path: PathBuf,
}

impl WorkDir {
    pub fn new(label: &str) -> std::io::Result<Self> {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        static SWEEP: std::sync::Once = std::sync::Once::new();
        SWEEP.call_once(|| sweep_abandoned(&std::env::temp_dir()));
        let path = std::env::temp_dir().join(format!(
            "tritri-{label}-{}-{}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        tritri_rtl::tools::interrupt::make_temporary(&path, |path| {
            let _ = std::fs::remove_dir_all(path);
            std::fs::create_dir_all(path)
        })?;
        Ok(WorkDir { path })
    }

    pub fn join(&self, name: &str) -> PathBuf {
        self.path.join(name)
    }
}

impl Drop for WorkDir {
    fn drop(&mut self) {
        tritri_rtl::tools::interrupt::unregister_temporary(&self.path);
        if std::env::var_os("TRITRI_KEEP_WORK").is_none() {
            let _ = std::fs::remove_dir_all(&self.path);
        } else {
            // Kept on purpose: a later run's sweep leaves it.
            let _ = std::fs::write(self.path.join(KEPT_MARKER), "");
            eprintln!("tritri: kept work directory {}", self.path.display());
        }
    }
}

/// The file that marks a work directory kept with `TRITRI_KEEP_WORK`.
const KEPT_MARKER: &str = ".tritri-kept";

/// Removes the work directories under `dir` that a run killed without a
/// chance to clean up left behind: named `tritri-<label>-<pid>-<n>`
/// ([`WorkDir::new`]), their process gone (no `/proc/<pid>`), and not
/// kept on purpose. A directory whose process may still run is left, so a
/// reused process id errs on the side of keeping.
pub fn sweep_abandoned(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = name.strip_prefix("tritri-") else {
            continue;
        };
        let mut fields = rest.rsplit('-');
        let (Some(counter), Some(pid)) = (fields.next(), fields.next()) else {
            continue;
        };
        let numeric = |f: &str| !f.is_empty() && f.bytes().all(|b| b.is_ascii_digit());
        if !numeric(counter) || !numeric(pid) || fields.next().is_none() {
            continue;
        }
        let path = entry.path();
        let alive = Path::new("/proc").join(pid).exists();
        if !alive && path.is_dir() && !path.join(KEPT_MARKER).exists() {
            let _ = std::fs::remove_dir_all(&path);
        }
    }
}

/// Fields `0 .. count` of `width` bits each, two's complement, of a bus a
/// testbench printed with `%h` (most significant digit first; digits the
/// printout drops at the top count as zero).
pub(crate) fn signed_hex_fields(
    hex: &str,
    width: usize,
    count: usize,
) -> anyhow::Result<Vec<i128>> {
    use anyhow::Context as _;
    assert!((1..=127).contains(&width), "a field of {width} bits");
    let digits: Vec<u32> = hex
        .chars()
        .rev()
        .map(|c| {
            c.to_digit(16)
                .with_context(|| format!("`{hex}` is not hexadecimal"))
        })
        .collect::<anyhow::Result<_>>()?;
    let bit = |at: usize| digits.get(at / 4).is_some_and(|d| d >> (at % 4) & 1 == 1);
    Ok((0..count)
        .map(|f| {
            let raw: i128 = (0..width)
                .filter(|&b| bit(f * width + b))
                .map(|b| 1i128 << b)
                .sum();
            if raw >> (width - 1) & 1 == 1 {
                raw - (1i128 << width)
            } else {
                raw
            }
        })
        .collect())
}

#[cfg(test)]
mod sweep_tests {
    use super::*;

    #[test]
    fn only_work_directories_of_gone_processes_are_swept() {
        let root = std::env::temp_dir().join(format!("sweep-test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).unwrap();
        // A process id that is gone: a child that has exited.
        let mut child = Command::new("true").spawn().unwrap();
        let gone = child.id();
        child.wait().unwrap();
        let me = std::process::id();
        let make = |name: String| {
            let p = root.join(name);
            std::fs::create_dir_all(&p).unwrap();
            p
        };
        let abandoned = make(format!("tritri-verilator-build-x-{gone}-3"));
        let running = make(format!("tritri-list-pass-{me}-0"));
        let kept = make(format!("tritri-list-pass-{gone}-1"));
        std::fs::write(kept.join(KEPT_MARKER), "").unwrap();
        let cache = make("tritri-cache".to_string());
        let foreign = make(format!("other-{gone}-0"));
        sweep_abandoned(&root);
        assert!(
            !abandoned.exists(),
            "the abandoned directory is still there"
        );
        for p in [&running, &kept, &cache, &foreign] {
            assert!(p.exists(), "{} was removed", p.display());
        }
        let _ = std::fs::remove_dir_all(&root);
    }
}

/// Runs `compiled` on a vector file and returns the output file's text:
/// both files live in a work directory of their own for the run.
pub fn run_on_vectors(
    compiled: &Compiled,
    label: &str,
    vectors: &str,
    extra: &[String],
) -> anyhow::Result<(String, f64)> {
    run_on_vector_stream(
        compiled,
        label,
        &mut |out| out.write_all(vectors.as_bytes()),
        extra,
        &mut |_| {},
    )
}

/// Runs `compiled` on the vectors `write` produces and returns the output
/// file's text and the run's seconds. The vectors go through a named pipe:
/// a thread writes them as the simulator reads them, so a run of 10^9
/// cycles needs neither the memory nor the disk its vector file would
/// (over a gigabyte). `on_line` sees what the testbench prints, as it
/// prints it.
pub fn run_on_vector_stream(
    compiled: &Compiled,
    label: &str,
    write: &mut (dyn FnMut(&mut dyn Write) -> std::io::Result<()> + Send),
    extra: &[String],
    on_line: &mut dyn FnMut(&str),
) -> anyhow::Result<(String, f64)> {
    let work = WorkDir::new(label)?;
    let (vectors_path, outputs_path) = (work.join("vectors.fifo"), work.join("outputs.txt"));
    make_fifo(&vectors_path)
        .with_context(|| format!("creating the named pipe {}", vectors_path.display()))?;
    let mut plusargs = vec![
        format!("+vectors={}", vectors_path.display()),
        format!("+outputs={}", outputs_path.display()),
    ];
    plusargs.extend_from_slice(extra);
    let started = Instant::now();
    let (output, written) = std::thread::scope(|scope| {
        let writer = scope.spawn(|| -> std::io::Result<()> {
            block_sigpipe_in_this_thread();
            // Opening blocks until the simulator opens the pipe to read.
            let mut out = std::io::BufWriter::with_capacity(
                1 << 16,
                std::fs::OpenOptions::new()
                    .write(true)
                    .open(&vectors_path)?,
            );
            write(&mut out)?;
            out.flush()
        });
        let output = compiled.run_with_lines(&plusargs, on_line);
        if !writer.is_finished() {
            // The simulator has ended without reading to the end (or without
            // opening the pipe at all): a reader opened and closed here
            // releases a writer blocked in `open`, whose writes then fail.
            release_fifo_writer(&vectors_path);
        }
        let written = writer
            .join()
            .unwrap_or_else(|_| Err(std::io::Error::other("the vector writer panicked")));
        (output, written)
    });
    let output = output?;
    let seconds = started.elapsed().as_secs_f64();
    let text = std::fs::read_to_string(&outputs_path).with_context(|| {
        format!(
            "the testbench wrote no outputs; the simulator said:\n{}",
            String::from_utf8_lossy(&output.stdout)
        )
    })?;
    written.with_context(|| format!("writing the vectors into {}", vectors_path.display()))?;
    Ok((text, seconds))
}

/// The parts of a generated testbench that feeds a unit one input per
/// clock from `+vectors=FILE` and logs its outputs to `+outputs=FILE`; the
/// skeleton around them (clock, reset for two cycles, the file handling,
/// the read loop, the drain) is [`vector_testbench`]'s.
pub struct VectorTestbench<'a> {
    /// The testbench module's name.
    pub name: &'a str,
    /// Declarations, the unit's instance, and an `always @(negedge clock)`
    /// block that writes each valid output to `outputs`. `clock`, `reset`,
    /// `advance`, `in_valid`, the file handles and `r`, `i` are declared.
    pub body: String,
    /// Statements that zero the inputs before reset is released.
    pub start: String,
    /// The read loop's condition: reads a line's first fields, true while
    /// there is a line.
    pub read: String,
    /// Statements that read the rest of the line into the inputs.
    pub fill: String,
    /// Idle clocks after the last input (the unit's latency and a margin).
    pub drain: usize,
}

/// The statements that open a generated testbench's files: `+vectors=`
/// for reading into `vectors`, `+outputs=` for writing into `outputs` (the
/// `reg` paths and `integer` handles declared by the testbench).
pub const OPEN_VECTOR_FILES: &str = "        if (!$value$plusargs(\"vectors=%s\", vectors_path) || !$value$plusargs(\"outputs=%s\", outputs_path)) begin
            $display(\"usage: +vectors=FILE +outputs=FILE\");
            $finish;
        end
        vectors = $fopen(vectors_path, \"r\");
        outputs = $fopen(outputs_path, \"w\");";

/// The Verilog of `parts` (see [`VectorTestbench`]).
pub fn vector_testbench(parts: &VectorTestbench) -> String {
    let VectorTestbench {
        name,
        body,
        start,
        read,
        fill,
        drain,
    } = parts;
    let open_files = OPEN_VECTOR_FILES;
    format!(
        "\
// Generated by tritri-cosim: drives a unit from a vector file.
`timescale 1ns/1ps
module {name};
    reg clock = 1'b0;
    reg reset = 1'b1;
    reg advance = 1'b1;
    reg in_valid = 1'b0;
    integer vectors, outputs, r, i;
    reg [8*4096-1:0] vectors_path, outputs_path;
{body}
    always #5 clock = ~clock;

    initial begin
{open_files}
{start}
        repeat (2) @(negedge clock);
        reset = 1'b0;
        while ({read}) begin
{fill}
            in_valid = 1'b1;
            @(negedge clock);
        end
        in_valid = 1'b0;
        repeat ({drain}) @(negedge clock);
        $fclose(outputs);
        $finish;
    end
endmodule
"
    )
}
