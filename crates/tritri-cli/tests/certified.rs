//! The exact answer by default: `tritri classify --arith fixed` and
//! `tritri sim` decide every verdict without a certificate again on the
//! original coordinates, so their answer is the exact answer where the
//! grid's is not.

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

/// 4,000 pairs of small triangles in the unit cube (a fixed pseudo-random
/// sequence), one per line.
fn random_pair_file() -> std::path::PathBuf {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut text = String::new();
    for _ in 0..4000 {
        let centre = [next(), next(), next()];
        for _ in 0..6 {
            for c in centre {
                text.push_str(&format!("{} ", c + 0.2 * (next() - 0.5)));
            }
        }
        text.push('\n');
    }
    let dir = std::env::temp_dir().join(format!("tritri-certified-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("pairs.txt");
    std::fs::write(&path, text).unwrap();
    path
}

/// At W = 8 the grid gets some verdicts wrong; `--arith fixed` prints the
/// exact answer by default (the uncertain verdicts decided again), with a
/// note counting the pairs that went back to the host; `--grid-verdicts`
/// prints the grid's own; `--certified` is kept for scripts.
#[test]
fn classify_fixed_is_exact_by_default_where_the_grid_is_not() {
    let path = random_pair_file();
    let file = path.to_str().unwrap();
    let exact = tritri(&["classify", file]);
    assert!(exact.status.success(), "{}", text(&exact.stderr));
    let fixed = ["classify", "--arith", "fixed", "--width", "8"];
    let grid = tritri(&[&fixed[..], &["--grid-verdicts", file]].concat());
    assert!(grid.status.success(), "{}", text(&grid.stderr));
    assert_ne!(
        text(&grid.stdout),
        text(&exact.stdout),
        "W = 8 should get some verdicts wrong"
    );
    for extra in [&[][..], &["--certified"][..]] {
        let answer = tritri(&[&fixed[..], extra, &[file]].concat());
        assert!(answer.status.success(), "{}", text(&answer.stderr));
        assert_eq!(text(&answer.stdout), text(&exact.stdout), "{extra:?}");
        let note = text(&answer.stderr);
        assert!(
            note.contains("exact answer:") && note.contains("without a certificate"),
            "{note}"
        );
    }
    // Only with --arith fixed, and not both.
    for flag in ["--certified", "--grid-verdicts"] {
        let refused = tritri(&["classify", flag, file]);
        assert_eq!(refused.status.code(), Some(2), "{flag}");
        assert!(
            text(&refused.stderr).contains(flag),
            "{}",
            text(&refused.stderr)
        );
    }
    let both = tritri(&[&fixed[..], &["--certified", "--grid-verdicts", file]].concat());
    assert_eq!(both.status.code(), Some(2));
}

/// The built-in scene: the grid reports one pair too many against exact
/// f64; the default answer, the uncertain verdicts decided again, none.
/// `--grid-verdicts` writes the grid's own answer, and `--json` both.
#[test]
fn sim_answer_is_exact_by_default_on_the_built_in_scene() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("certified-sim");
    std::fs::create_dir_all(&dir).unwrap();
    let (exact, grid, json) = (
        dir.join("exact.txt"),
        dir.join("grid.txt"),
        dir.join("run.json"),
    );
    let out = tritri(&[
        "sim",
        "--out",
        exact.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let report = text(&out.stdout);
    assert!(
        report.contains("exact pairs: 113 (the grid's 114 hits; 37 verdicts without a certificate"),
        "{report}"
    );
    assert!(report.contains("(0 missing, 0 extra)"), "{report}");
    assert_eq!(report.lines().count(), 5, "the short summary: {report}");
    let verbose = tritri(&["sim", "--verbose"]);
    let verbose = text(&verbose.stdout);
    assert!(
        verbose.contains("114 hits on the grid and 37 without a certificate"),
        "{verbose}"
    );
    assert!(
        verbose.contains("quantization error on the 16-bit grid: 0 missing, 1 extra"),
        "{verbose}"
    );
    assert!(
        verbose.contains("exact pairs: 0 missing, 0 extra"),
        "{verbose}"
    );
    let out = tritri(&["sim", "--grid-verdicts", "--out", grid.to_str().unwrap()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let lines = |p: &std::path::Path| std::fs::read_to_string(p).unwrap().lines().count();
    assert_eq!((lines(&exact), lines(&grid)), (113, 114));
    let figures: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(figures["pairs"].as_array().unwrap().len(), 113);
    assert_eq!(figures["grid_pairs"].as_array().unwrap().len(), 114);
    assert_eq!(figures["check"]["pairs_vs_exact_f64"]["extra"], 0);
    assert_eq!(figures["check"]["grid_vs_exact_f64"]["extra"], 1);
    assert!(figures["faults"].as_array().unwrap().is_empty());
}
