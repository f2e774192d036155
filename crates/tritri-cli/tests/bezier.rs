//! `tritri bezier render` on a small file: a picture is written and the
//! report counts what the cone of normals culled and refined; bad input is
//! refused with status 2, naming it.

use std::process::{Command, Output};

fn tritri(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args(args)
        .output()
        .expect("run tritri")
}

/// Two patches of a flat square, one facing up, one (the same square with
/// its rows reversed) facing down, side by side.
fn two_squares() -> String {
    let mut text = String::from("2\n");
    for (dx, reversed) in [(0.0, false), (4.0, true)] {
        text += "3 3\n";
        for i in 0..4 {
            let i = if reversed { 3 - i } else { i };
            for j in 0..4 {
                text += &format!("{} {} 0\n", dx + i as f64, j);
            }
        }
    }
    text
}

#[test]
fn render_culls_what_faces_away_and_refuses_bad_input() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bezier-cli");
    std::fs::create_dir_all(&dir).unwrap();
    let bpt = dir.join("squares.bpt");
    std::fs::write(&bpt, two_squares()).unwrap();
    let png = dir.join("squares.png");
    let (bpt, png) = (bpt.to_str().unwrap(), png.to_str().unwrap());
    let out = tritri(&[
        "bezier", "render", bpt, "--eye", "3,1.5,10", "--target", "3,1.5,0", "--png", png,
        "--size", "64",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // Seen from above, the square whose d_u x d_v points down is culled.
    assert!(
        text.contains("2 patches") && text.contains("1 culled"),
        "{text}"
    );
    assert!(std::fs::metadata(png).unwrap().len() > 100);
    for (args, needle) in [
        (
            vec!["bezier", "render", "missing.bpt", "--png", png],
            "missing.bpt",
        ),
        (vec!["bezier", "render", bpt, "--png", "out.jpg"], "--png"),
        (
            vec![
                "bezier", "render", bpt, "--png", png, "--eye", "1,1,1", "--target", "1,1,1",
            ],
            "same point",
        ),
        (
            vec!["bezier", "render", bpt, "--png", png, "--subdivide", "9"],
            "--subdivide",
        ),
    ] {
        let out = tritri(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

/// `tritri bezier tessellate`: two squares through the tessellation unit
/// in Verilator equal its fixed-point model, in the formula's clocks, with
/// the error within a grid step; a width the unit is not built for is
/// refused (status 2).
#[test]
fn tessellate_runs_the_unit_and_reports_the_error() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bezier-cli");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("squares-tessellate.bpt");
    std::fs::write(&file, two_squares()).unwrap();
    let out = tritri(&[
        "bezier",
        "tessellate",
        file.to_str().unwrap(),
        "--engine",
        "verilator",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    // Its time at the unit's post-route clock, named (rtl-out/measurements.json).
    for needle in ["engine: verilator: 0 of 2 patches differ from the fixed-point model; 166 clocks (formula: 166)", "2 patches at 8 steps a side", "162 vertices, 256 triangles", "MHz (post-route, ECP5-85): ", "triangles/s"] {
        assert!(text.contains(needle), "no `{needle}` in:\n{text}");
    }
    let steps: f64 = text
        .split("at most ")
        .nth(1)
        .and_then(|t| t.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap();
    assert!(steps <= 1.0, "{text}");
    let out = tritri(&[
        "bezier",
        "tessellate",
        file.to_str().unwrap(),
        "--width",
        "20",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--width 20"));
}

/// `tritri bezier cones`: two squares, one facing the eye and one turned
/// away, through the cone unit in Verilator: one culled, one front-facing,
/// as the f64 guarantee says; a width the unit is not built for is refused.
#[test]
fn cones_runs_the_unit_and_compares_with_f64() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bezier-cli");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("squares-cones.bpt");
    std::fs::write(&file, two_squares()).unwrap();
    let out = tritri(&[
        "bezier",
        "cones",
        file.to_str().unwrap(),
        "--eye",
        "3,1.5,10",
        "--engine",
        "verilator",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    for needle in ["2 patches from (3, 1.5, 10) on a 24-bit grid: 1 culled, 1 front-facing, 0 possible silhouettes; the f64 guarantee culls 1, 0 answers differ", "clocks: 6, one patch a clock after 4 (the model's classes in verilator", "tritri_cone_unit_w24 is not routed (no time without a clock"] {
        assert!(text.contains(needle), "no `{needle}` in:\n{text}");
    }
    let out = tritri(&["bezier", "cones", file.to_str().unwrap(), "--width", "20"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--width 20"));
}
