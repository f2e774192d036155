//! `tritri bench`: every engine agrees with the model on the benchmark's
//! pairs, the cycle counts follow the formula, and the table reports a
//! throughput for each engine; bad parameters are refused by name.

use std::process::Command;

fn tritri() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tritri"))
}

/// A small run through all engines: exit 0, one row per engine with
/// 0 mismatches and the formula's cycle count.
#[test]
fn small_bench_agrees_everywhere() {
    let out = tritri()
        .args(["bench", "--width", "16", "--pairs", "300", "--bases", "7"])
        .output()
        .unwrap();
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{table}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for engine in ["model", "rusthdl", "verilator", "icarus"] {
        let row = table
            .lines()
            .find(|l| l.starts_with(&format!("| 16 | {engine} |")))
            .unwrap_or_else(|| panic!("no {engine} row in\n{table}"));
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        // 7 bases x ceil(300 / 7) = 43 streamed triangles.
        assert_eq!(cells[3], "301", "{row}");
        assert_eq!(cells[4], "0", "{row}");
        if engine != "model" {
            assert_eq!(
                cells[5],
                format!(
                    "{} (= formula)",
                    7 + 301 + tritri_rtl::pipeline::triangle_pipeline::latency()
                ),
                "{row}"
            );
        }
        assert!(cells[8].parse::<f64>().unwrap() > 0.0, "{row}");
    }
}

#[test]
fn bad_parameters_are_named() {
    let out = tritri().args(["bench", "--width", "23"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--width 23"));
    let out = tritri().args(["bench", "--pairs", "0"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    // Refused by the option's parser, which names it and its range.
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("'0' for '--pairs") && stderr.contains("from 1 to"),
        "{stderr}"
    );
}
