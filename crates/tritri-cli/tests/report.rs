//! `tritri report`: every number it shows is what `tritri eval`, `tritri
//! sim` and the measurements of `tritri gen --synth` give for the same
//! inputs, and its files are all there.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};
use tritri_rtl::pipeline::pipeline_unit::pipeline_unit_name_for;
use tritri_rtl::pipeline::RareCasePath;
use tritri_rtl::system::system_for_width::PipelineKind;
use tritri_rtl::system::system_unit::system_unit_name;
use tritri_rtl::system::SystemConfig;

fn tritri(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args(args)
        .output()
        .expect("run tritri")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("report-tests")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The number after `label` in `line` (digits, no separators).
fn number_after(output: &str, label: &str) -> u64 {
    let start = output
        .find(label)
        .unwrap_or_else(|| panic!("no `{label}` in:\n{output}"))
        + label.len();
    let digits: String = output[start..]
        .trim_start()
        .chars()
        .take_while(|c| c.is_ascii_digit())
        .collect();
    digits
        .parse()
        .unwrap_or_else(|_| panic!("no number after `{label}` in:\n{output}"))
}

#[test]
fn report_agrees_with_eval_sim_and_the_measurements() {
    let out_dir = scratch("hard-and-scene");
    let out = tritri(&[
        "report",
        "--min-time-ms",
        "1",
        "--widths",
        "8,16",
        "@hard/coplanar_integer_plane",
        "@hard/near_miss",
        "--scene",
        "@torus",
        "@sphere",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    for file in [
        "report.html",
        "report.json",
        "widths.csv",
        "errors.csv",
        "scene.csv",
    ] {
        assert!(out_dir.join(file).is_file(), "{file} missing");
    }
    let html = std::fs::read_to_string(out_dir.join("report.html")).unwrap();
    assert_eq!(
        html.matches("<svg").count(),
        6,
        "errors, cost, speed, Pareto, the scene's time and its errors"
    );
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("report.json")).unwrap())
            .unwrap();

    // Errors: eval's JSON on the same batches, count for count.
    let eval = tritri(&[
        "eval",
        "--json",
        "--min-time-ms",
        "1",
        "--widths",
        "8,16",
        "@hard/coplanar_integer_plane",
        "@hard/near_miss",
    ]);
    assert_eq!(eval.status.code(), Some(0), "{}", text(&eval.stderr));
    let eval: Value = serde_json::from_slice(&eval.stdout).unwrap();
    let counts = [
        "wrong",
        "false_positives",
        "false_negatives",
        "grid_exact_disagreements",
        "uncertain",
        "certified_wrong",
    ];
    let batches = |v: &Value| -> Vec<Value> {
        let mut all = v["batches"].as_array().unwrap().clone();
        all.push(v["total"].clone());
        all
    };
    let (ours, theirs) = (batches(&report["errors"]), batches(&eval));
    assert_eq!(ours.len(), theirs.len());
    for (a, b) in ours.iter().zip(&theirs) {
        assert_eq!(
            (&a["name"], &a["pairs"], &a["exact_intersecting"]),
            (&b["name"], &b["pairs"], &b["exact_intersecting"])
        );
        for (ra, rb) in a["rows"]
            .as_array()
            .unwrap()
            .iter()
            .zip(b["rows"].as_array().unwrap())
        {
            assert_eq!(ra["arithmetic"], rb["arithmetic"]);
            for c in counts {
                assert_eq!(ra[c], rb[c], "{} {} {c}", a["name"], ra["arithmetic"]);
            }
        }
    }
    let fixed8 = report["widths"][0]["error"].clone();
    assert_eq!(fixed8["arithmetic"], "fixed8");
    assert!(
        fixed8["wrong"].as_u64().unwrap() > 0 && fixed8["uncertain"].as_u64().unwrap() > 0,
        "hard cases at W = 8: {fixed8}"
    );

    // Hardware: the measurements `gen --synth` printed (rtl-out/measurements.json,
    // itself held to rtl-out/README.md and to a synthesis run by tritri-rtl's tests).
    // A width's pipeline is the one routed on ECP5 (W = 16: its rare cases
    // shared), its Xilinx row that same pipeline's.
    let kept = tritri_rtl::measured::Measurements::committed();
    for row in report["widths"].as_array().unwrap() {
        let width = row["width"].as_u64().unwrap() as u32;
        let routed = kept.ecp5_pipeline(width);
        let path = routed.map_or(RareCasePath::Parallel, |(path, _)| path);
        assert_eq!(row["rare_cases"], path.name(), "W = {width}");
        let unit = pipeline_unit_name_for(width as usize, path);
        let x = kept.xilinx(&unit).unwrap();
        assert_eq!(
            (
                row["xilinx"]["lut"].as_u64(),
                row["xilinx"]["dsp48e1"].as_u64()
            ),
            (Some(x.lut), Some(x.dsp48e1)),
            "{unit}"
        );
        match routed.map(|(_, e)| e) {
            Some(e) => {
                assert_eq!(row["ecp5"]["fmax_mhz"].as_f64(), Some(e.fmax_mhz), "{unit}");
                let p = row["ecp5_pipelines"].as_u64().unwrap();
                assert!(
                    p >= 1 && p * e.mult18x18d <= 156,
                    "{unit}: {p} pipelines on the ECP5-85"
                );
                // At the clock of the system of those p pipelines where it
                // was routed (W = 16, P = 2: slower than one pipeline alone).
                let config = SystemConfig::new(width as usize, p as usize);
                let system = kept
                    .ecp5(&system_unit_name(config, PipelineKind::from(path)))
                    .map(|s| s.fmax_mhz);
                assert_eq!(row["system_fmax_mhz"].as_f64(), system, "{unit}");
                let clock = system.unwrap_or(e.fmax_mhz);
                assert_eq!(
                    row["pairs_per_second"].as_f64(),
                    Some(clock * 1e6 * p as f64)
                );
            }
            None => assert!(
                row["ecp5"].is_null() && row["pairs_per_second"].is_null(),
                "{unit}"
            ),
        }
    }

    // The scene: `tritri sim` with the same width, pipelines, clock and
    // rare-case path; with the rare cases shared, the report's time adds
    // the stall model's bound that `sim` prints.
    assert!(
        report["scene"]["rows"]
            .as_array()
            .unwrap()
            .iter()
            .any(|r| r["rare_cases"] == "shared"),
        "W = 16's routed pipeline shares its rare cases"
    );
    // Its plot draws the rows at a routed clock as a line of their own
    // (a series with no point has no legend entry).
    assert!(
        report["scene"]["rows"]
            .as_array()
            .unwrap()
            .iter()
            .any(|r| r["clock"].as_str().unwrap().starts_with("post-route")),
        "W = 8 and 16 were routed"
    );
    assert!(
        html.contains("hardware at the post-route Fmax"),
        "the scene plot's line at the routed clocks"
    );
    for row in report["scene"]["rows"].as_array().unwrap() {
        let (w, p, clock) = (
            row["width"].to_string(),
            row["pipelines"].to_string(),
            row["clock_mhz"].as_f64().unwrap().to_string(),
        );
        let rare_cases = row["rare_cases"].as_str().unwrap();
        let sim = tritri(&[
            "sim",
            "--broad-phase",
            "octree",
            "--verbose",
            "--width",
            &w,
            "--pipelines",
            &p,
            "--clock-mhz",
            &clock,
            "--rare-cases",
            rare_cases,
        ]);
        assert_eq!(sim.status.code(), Some(0), "{}", text(&sim.stderr));
        let sim = text(&sim.stdout);
        let field = |name: &str| row[name].as_u64().unwrap();
        assert_eq!(
            field("pairs_tested"),
            number_after(&sim, "pairs tested:"),
            "W = {w}"
        );
        assert_eq!(
            field("leaves"),
            number_after(&sim, "classified,"),
            "W = {w}: leaves"
        );
        assert_eq!(
            field("intersecting"),
            number_after(&sim, "intersecting pairs on the grid:"),
            "W = {w}"
        );
        assert_eq!(
            field("uncertain"),
            number_after(&sim, "certificates:"),
            "W = {w}"
        );
        assert_eq!(field("cycles"), number_after(&sim, "\ncycles:"), "W = {w}");
        let stalls = match rare_cases {
            "shared" => number_after(&sim, "stall model) at most"),
            _ => 0,
        };
        assert_eq!(field("stall_cycles"), stalls, "W = {w}");
        assert_eq!(
            field("whole_cycles"),
            number_after(&sim, "first triangle in to last pair out:"),
            "W = {w}"
        );
        assert_eq!(
            field("missing"),
            number_after(&sim, "bits):"),
            "W = {w}: missing"
        );
        assert_eq!(
            field("extra"),
            number_after(&sim, "pairs missing,"),
            "W = {w}: extra"
        );
    }
}

/// Nothing to report on, an unreadable pair file, a file in the way of the
/// directory and bad measurements: status 2, the value named.
#[test]
fn report_refuses_bad_input() {
    let dir = scratch("bad");
    let out = tritri(&["report", "--out", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("nothing to report on"),
        "{}",
        text(&out.stderr)
    );

    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.txt");
    std::fs::write(&bad, "0 0 0 1 0 0 0 1 0  5 5 5 6 5 5 5 6 nan\n").unwrap();
    let out = tritri(&[
        "report",
        bad.to_str().unwrap(),
        "--out",
        dir.join("r").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("bad.txt:1:"),
        "{}",
        text(&out.stderr)
    );
    assert!(
        !dir.join("r").join("report.html").exists(),
        "nothing written"
    );

    let out = tritri(&["report", "@hard/near_miss", "--out", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("--out") && text(&out.stderr).contains("not a directory"),
        "{}",
        text(&out.stderr)
    );

    let out = tritri(&[
        "report",
        "@hard/near_miss",
        "--measurements",
        bad.to_str().unwrap(),
        "--out",
        dir.join("r").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("--measurements") && text(&out.stderr).contains("bad.txt"),
        "{}",
        text(&out.stderr)
    );

    let out = tritri(&["report", "@nope", "--out", dir.join("r").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
}
