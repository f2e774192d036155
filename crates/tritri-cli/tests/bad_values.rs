//! Values users get wrong, each refused with exit status 2 and a message
//! naming the option, never a panic (exit 101); and a reader that closes the
//! pipe early ends the program quietly.

use std::io::Read;
use std::process::{Command, Output, Stdio};

fn tritri(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tritri")).args(args).output().expect("run tritri")
}

#[test]
fn out_of_range_options_are_usage_errors_naming_the_option() {
    let out_dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad-values-gen");
    let out_dir = out_dir.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["sim", "--clock-mhz", "0"], "--clock-mhz"),
        (&["sim", "--clock-mhz", "nan"], "--clock-mhz"),
        (&["sim", "--clock-mhz", "-5"], "--clock-mhz"),
        (&["sim", "--clock-mhz", "1e-300"], "--clock-mhz"),
        (&["sim", "--clock-mhz", "inf"], "--clock-mhz"),
        (&["chapter5", "--clock-mhz", "0"], "--clock-mhz"),
        (&["sim", "--depth", "32768"], "--depth"),
        (&["gen", "--system", "--depth", "32768", "--out", out_dir], "--depth"),
        (&["sim", "--scale-b", "0"], "--scale-b"),
        (&["sim", "--subdivide", "9"], "--subdivide"),
        (&["sim", "--grid-bits", "40"], "--grid-bits"),
    ];
    for (args, option) in cases {
        let out = tritri(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(option), "{args:?}: {err}");
    }
}

/// The largest documented depth is accepted by the generator (it used to
/// fail an assertion in the address generator).
#[test]
fn largest_depth_generates() {
    let out_dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("largest-depth-gen");
    let out = tritri(&["gen", "--system", "--depth", "32767", "--out", out_dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// `tritri eval @hard | head -c 1` and `tritri chapter5 | head -c 1`: no
/// panic, nothing on stderr.
#[test]
fn closed_pipe_ends_quietly() {
    for args in [&["eval", "@hard"][..], &["chapter5", "--fractions", "5,25"]] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_tritri"))
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("run tritri");
        let mut first = [0u8; 1];
        child.stdout.take().unwrap().read_exact(&mut first).unwrap();
        // The read end is dropped here: the next write gets SIGPIPE.
        let out = child.wait_with_output().unwrap();
        assert_ne!(out.status.code(), Some(101), "{args:?}");
        assert!(out.stderr.is_empty(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
}
