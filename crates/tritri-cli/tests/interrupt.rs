//! Ctrl-C (SIGINT), SIGTERM and SIGHUP during a Verilator run: `tritri` stops the
//! simulator (or the build) and everything it started, removes its work
//! directories, and exits with 128 + the signal. Checked by process groups
//! in /proc and by an empty private TMPDIR.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// `(pid, parent, process group)` of every process (Linux /proc).
fn processes() -> Vec<(i32, i32, i32)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(stat) = std::fs::read_to_string(entry.path().join("stat")) else {
            continue;
        };
        // pid (comm) state ppid pgrp ...; comm may hold spaces.
        let Some(close) = stat.rfind(')') else {
            continue;
        };
        let fields: Vec<&str> = stat[close + 2..].split_whitespace().collect();
        let (Ok(pid), Some(Ok(ppid)), Some(Ok(pgrp))) = (
            stat.split_whitespace().next().unwrap_or("").parse(),
            fields.get(1).map(|f| f.parse()),
            fields.get(2).map(|f| f.parse()),
        ) else {
            continue;
        };
        if fields.first() != Some(&"Z") {
            out.push((pid, ppid, pgrp));
        }
    }
    out
}

/// Process groups of the running children of `parent`, each in a group of
/// its own. A child caught between its fork and its `setpgid` is still in
/// the parent's group, which is the test's own (cargo's, the shell's) and
/// never empties: it is left out until it has moved. (Once counted, on a
/// loaded machine, the test waited for the test run itself to end.)
fn child_groups(parent: i32) -> Vec<i32> {
    let all = processes();
    let parent_group = all.iter().find(|p| p.0 == parent).map(|p| p.2);
    all.into_iter()
        .filter(|p| p.1 == parent && Some(p.2) != parent_group)
        .map(|p| p.2)
        .collect()
}

fn start(tmp: &Path, cache: Option<&Path>) -> Child {
    let mut command = Command::new(env!("CARGO_BIN_EXE_tritri"));
    if let Some(cache) = cache {
        command.env("TRITRI_CACHE_DIR", cache);
    }
    command
        // Long enough in Verilator to be caught running (about 780,000
        // pairs), or caught building if the model is not cached yet.
        .args([
            "sim",
            "--engine",
            "verilator",
            "--broad-phase",
            "flat",
            "--subdivide",
            "1",
            "--no-compare",
        ])
        .env("TMPDIR", tmp)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run tritri")
}

/// Interrupts `tritri` once it runs a tool; with `empty_cache` that tool
/// is the Verilator build (verilator, make, g++), else the simulation if
/// an earlier test built the model (the demo's configuration).
fn interrupt_and_check(signal: i32, name: &str, empty_cache: bool) {
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("interrupt-{name}"));
    let (tmp, cache) = (root.join("tmp"), root.join("cache"));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&tmp).unwrap();
    let mut child = start(&tmp, empty_cache.then_some(cache.as_path()));
    let pid = child.id() as i32;
    let deadline = Instant::now() + Duration::from_secs(600);
    let groups = loop {
        let groups = child_groups(pid);
        if !groups.is_empty() {
            break groups;
        }
        assert!(
            child.try_wait().unwrap().is_none(),
            "{name}: tritri ended before starting a tool"
        );
        assert!(
            Instant::now() < deadline,
            "{name}: no tool started within 10 minutes"
        );
        std::thread::sleep(Duration::from_millis(20));
    };
    // SAFETY: sends a signal to our own child.
    unsafe {
        libc::kill(pid, signal);
    }
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(128 + signal), "{name}: {err}");
    // (A short tool such as `verilator --version` may end between seeing it
    // and the signal, so the count is not asserted; what is left is.)
    assert!(
        err.contains(&format!("tritri: {name}: stopped ")),
        "{name}: {err}"
    );
    // Killed groups vanish once reaped (by init, their parent is gone).
    let deadline = Instant::now() + Duration::from_secs(10);
    while processes().iter().any(|p| groups.contains(&p.2)) {
        assert!(
            Instant::now() < deadline,
            "{name}: processes of groups {groups:?} still run"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let left: Vec<_> = std::fs::read_dir(&tmp)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert!(left.is_empty(), "{name}: left behind: {left:?}");
    if empty_cache {
        // An interrupted build publishes nothing.
        let cached = std::fs::read_dir(cache.join("verilator"))
            .map(|d| d.count())
            .unwrap_or(0);
        assert_eq!(cached, 0, "{name}: an interrupted build was cached");
    }
}

#[test]
fn sigint_sigterm_and_sighup_leave_no_process_and_no_file() {
    interrupt_and_check(libc::SIGTERM, "SIGTERM", true);
    interrupt_and_check(libc::SIGINT, "SIGINT", false);
    interrupt_and_check(libc::SIGHUP, "SIGHUP", false);
}

/// Ctrl-C while yowasp runs (`gen --synth ecp5`), caught as early as can
/// be (its WebAssembly may still be compiling, when it cannot clean up):
/// its `yowasp_*` directory sits in a TMPDIR of its own under the output
/// directory, which `tritri` removes; nothing is left there or in TMPDIR.
#[test]
fn ctrl_c_during_yowasp_leaves_no_yowasp_directory() {
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("interrupt-yowasp");
    let (tmp, out) = (root.join("tmp"), root.join("out"));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&tmp).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args(["gen", "--width", "8", "--synth", "ecp5", "--out"])
        .arg(&out)
        .env("TMPDIR", &tmp)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run tritri");
    let yowasp_tmp = out.join(".yowasp-tmp");
    let yowasp_dir = || {
        std::fs::read_dir(&yowasp_tmp).is_ok_and(|d| {
            d.flatten()
                .any(|e| e.file_name().to_string_lossy().starts_with("yowasp_"))
        })
    };
    let deadline = Instant::now() + Duration::from_secs(600);
    while !yowasp_dir() {
        assert!(
            child.try_wait().unwrap().is_none(),
            "tritri ended before yowasp made its directory"
        );
        assert!(
            Instant::now() < deadline,
            "no yowasp_* directory in 10 minutes"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let groups = child_groups(child.id() as i32);
    // SAFETY: sends a signal to our own child.
    unsafe {
        libc::kill(child.id() as i32, libc::SIGINT);
    }
    let status = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&status.stderr);
    assert_eq!(status.status.code(), Some(130), "{err}");
    let deadline = Instant::now() + Duration::from_secs(10);
    while processes().iter().any(|p| groups.contains(&p.2)) {
        assert!(Instant::now() < deadline, "groups {groups:?} still run");
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(!yowasp_tmp.exists(), "{} left behind", yowasp_tmp.display());
    let left: Vec<_> = std::fs::read_dir(&tmp)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}
