//! `tritri classify` and `tritri eval`: output rules and exit codes.

use std::path::PathBuf;
use std::process::{Command, Output};

fn tritri(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args(args)
        .output()
        .expect("run tritri")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A file in a fresh temporary directory.
fn write(name: &str, contents: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tritri-cli-test-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, contents).unwrap();
    path
}

const GOOD: &str = "0 0 0 1 0 0 0 1 0  0 0 0 0 0 1 1 1 1\n0 0 0 1 0 0 0 1 0  5 5 5 6 5 5 5 6 5\n";

/// One line per pair, 1 = intersect, for every arithmetic; fixed notes its step on stderr.
#[test]
fn classify_prints_one_verdict_per_pair() {
    let file = write("good.txt", &format!("# two pairs\n\n{GOOD}"));
    for arith in ["exact", "f64", "f32", "moller", "fixed"] {
        let out = tritri(&["classify", "--arith", arith, file.to_str().unwrap()]);
        assert!(out.status.success(), "{arith}: {}", text(&out.stderr));
        assert_eq!(text(&out.stdout), "1\n0\n", "{arith}");
    }
    let out = tritri(&[
        "classify",
        "--arith",
        "fixed",
        "--width",
        "12",
        file.to_str().unwrap(),
    ]);
    assert!(
        text(&out.stderr).contains("fixed12") && text(&out.stderr).contains("step h ="),
        "{}",
        text(&out.stderr)
    );
}

/// Bad records: every one named (file:line) on stderr, exit 2, and no
/// verdict at all on stdout, in every arithmetic (a partial answer would
/// read as the file's).
#[test]
fn classify_reports_bad_records_and_gives_no_verdicts() {
    let file = write(
        "bad.txt",
        &format!("{GOOD}1 2 3\n0 0 0 1 0 0 0 1 0  5 5 5 6 5 5 5 6 inf\n{GOOD}"),
    );
    for arith in ["exact", "fixed"] {
        let out = tritri(&["classify", "--arith", arith, file.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{arith}");
        assert_eq!(text(&out.stdout), "", "{arith}");
        let err = text(&out.stderr);
        assert!(err.contains("bad.txt:3: expected 18 numbers"), "{err}");
        assert!(
            err.contains("bad.txt:4: number 18 `inf` is not finite"),
            "{err}"
        );
        assert!(
            !err.contains("note:"),
            "{arith}: no frame note after an error: {err}"
        );
    }
}

/// `eval bad.txt good.txt`: no table and no total that would silently
/// leave the bad file out.
#[test]
fn eval_with_a_bad_file_evaluates_nothing() {
    let bad = write("eval-bad.txt", "0 0 0 1 0 0 0 1 0  5 5 5 6 5 5 5 6 nan\n");
    let good = write("eval-good.txt", GOOD);
    let out = tritri(&[
        "eval",
        "--min-time-ms",
        "1",
        bad.to_str().unwrap(),
        good.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(text(&out.stdout), "");
    assert!(
        text(&out.stderr).contains("eval-bad.txt:1:"),
        "{}",
        text(&out.stderr)
    );
}

/// Widths outside 8..=32 are refused, naming the value; --width needs --arith fixed.
#[test]
fn classify_refuses_bad_widths() {
    let file = write("w.txt", GOOD);
    let out = tritri(&[
        "classify",
        "--arith",
        "fixed",
        "--width",
        "40",
        file.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("width 40 is out of range"),
        "{}",
        text(&out.stderr)
    );
    let out = tritri(&[
        "classify",
        "--arith",
        "f64",
        "--width",
        "16",
        file.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("--width 16 applies only to --arith fixed"));
}

/// JSON input; malformed JSON names the line and column.
#[test]
fn classify_reads_json() {
    let file = write(
        "p.json",
        r#"[{"name": "x", "t1": [[0,0,0],[1,0,0],[0,1,0]], "t2": [[0,0,0],[0,0,1],[1,1,1]]}]"#,
    );
    let out = tritri(&["classify", file.to_str().unwrap()]);
    assert!(out.status.success());
    assert_eq!(text(&out.stdout), "1\n");
    let file = write("m.json", "[\n{\"t1\": [[NaN, 0, 0]]}]");
    let out = tritri(&["classify", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("m.json:2:"),
        "{}",
        text(&out.stderr)
    );
}

/// The eval JSON has a row per arithmetic and width; fixed agrees with
/// exact on the grid.
#[test]
fn eval_json_rows() {
    let file = write("e.txt", GOOD);
    let out = tritri(&[
        "eval",
        "--json",
        "--min-time-ms",
        "1",
        "--widths",
        "8,24",
        file.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let report: serde_json::Value = serde_json::from_str(&text(&out.stdout)).unwrap();
    let rows = report["total"]["rows"].as_array().unwrap();
    let names: Vec<_> = rows
        .iter()
        .map(|r| r["arithmetic"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["exact", "f64", "f32", "moller", "fixed8", "fixed24"]
    );
    for r in rows {
        assert_eq!(r["wrong"], 0, "{r}");
    }
    assert_eq!(rows[5]["grid_exact_disagreements"], 0);
    assert!(report["batches"][0]["rows"][5]["step"].as_f64().unwrap() > 0.0);
}

/// Unknown suites and categories are usage errors.
#[test]
fn eval_refuses_unknown_suite() {
    let out = tritri(&["eval", "@nope"]);
    assert_eq!(out.status.code(), Some(2));
    let out = tritri(&["eval", "@hard/nope"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("known are"),
        "{}",
        text(&out.stderr)
    );
}

/// `-` reads the pairs from standard input.
#[test]
fn classify_reads_standard_input() {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args(["classify", "-"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(GOOD.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    assert_eq!(text(&out.stdout), "1\n0\n");
}
