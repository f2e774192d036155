//! `tritri sim` and `tritri chapter5` run as a user runs them: the built
//! binary, its exit status, its output and the pairs file.

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

/// A file in this test binary's scratch directory.
fn scratch(name: &str, contents: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("sim-tests");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, contents).unwrap();
    path
}

fn scratch_path(name: &str) -> PathBuf {
    scratch(name, "")
}

/// A scene file that cannot be parsed: exit status 2 and an error naming the
/// file and the line.
#[test]
fn unparsable_scene_file_names_file_and_line() {
    let bad = scratch("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n");
    let out = tritri(&["sim", "--scene", bad.to_str().unwrap(), "@sphere"]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(
        err.contains("bad.obj:3:") && err.contains("`x` is not a number"),
        "{err}"
    );

    let bad_off = scratch("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    let out = tritri(&["sim", "--scene", "@torus", bad_off.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("bad.off:6:"),
        "{}",
        text(&out.stderr)
    );

    let missing = tritri(&["sim", "--scene", "/nonexistent/a.ply", "@sphere"]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(text(&missing.stderr).contains("/nonexistent/a.ply"));
}

/// Objects whose boxes do not meet: a clear message, zero pairs, an empty
/// pairs file, success.
#[test]
fn no_overlap_says_so_and_writes_no_pairs() {
    let pairs = scratch_path("none.txt");
    let out = tritri(&[
        "sim",
        "--verbose",
        "--pose-b",
        "10,0,0",
        "--out",
        pairs.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let report = text(&out.stdout);
    assert!(
        report.contains("no overlap") && report.contains("zero pairs"),
        "{report}"
    );
    assert_eq!(std::fs::read_to_string(&pairs).unwrap(), "");
}

/// `tritri sim` alone runs the built-in scene on the accelerator that fits
/// the ECP5-85 (its scene in DRAM), at that top's post-route clock with the
/// Versa's memory, and its exact pairs are exact f64's.
#[test]
fn sim_alone_runs_the_default_scene() {
    let out = tritri(&["sim", "--verbose"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let report = text(&out.stdout);
    for needle in [
        "@torus (2304 triangles)",
        "@sphere (960 triangles)",
        "exact pairs: 113",
        "at 52.9 MHz (post-route on the ECP5-85), 256-bit AXI4 port, 1.6 GB/s of DRAM",
        "design: tritri_dram_broad_phase_g16_w16_d256_p1_t256_i8192_s8192_shared",
        "KiB read",
        "that traffic takes at least",
        "over memory bandwidth",
        "25.6 GB/s: ",
        "(114 pairs): equal",
        "exact pairs: 0 missing, 0 extra",
    ] {
        assert!(report.contains(needle), "missing `{needle}` in:\n{report}");
    }
    assert!(!report.contains("assumed"), "{report}");
    // Without --verbose: the scene, the exact pairs, the time against the
    // software baseline, the check, where the details are.
    let out = tritri(&["sim"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let short = text(&out.stdout);
    let starts: Vec<&str> = short
        .lines()
        .map(|l| l.split(':').next().unwrap_or(""))
        .collect();
    assert_eq!(
        starts,
        ["scene", "exact pairs", "time", "check", "details"],
        "{short}"
    );
    // The same exact pairs as the on-chip octree design, and every figure
    // in --json: the DRAM traffic, the memory's bound, the times.
    let (dram, octree, json) = (
        scratch_path("dram_default.txt"),
        scratch_path("octree_for_dram.txt"),
        scratch_path("dram_default.json"),
    );
    let o = tritri(&[
        "sim",
        "--out",
        dram.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let o = tritri(&[
        "sim",
        "--broad-phase",
        "octree",
        "--out",
        octree.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert_eq!(
        std::fs::read_to_string(&dram).unwrap(),
        std::fs::read_to_string(&octree).unwrap()
    );
    let value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(value["accelerator"]["broad_phase"], "dram");
    assert_eq!(value["pairs"].as_array().unwrap().len(), 113);
    let clocks = value["clocks"].as_u64().unwrap();
    let bound = value["dram"]["memory_bound_clocks"].as_u64().unwrap();
    assert!(bound > 0 && clocks >= bound, "{value}");
    assert!(value["dram"]["bytes_read"].as_u64().unwrap() > 0, "{value}");
    let seconds = &value["seconds"];
    let whole = seconds["end_to_end"].as_f64().unwrap();
    let parts: f64 = ["host", "link_in", "accelerator", "link_back", "redecide"]
        .iter()
        .map(|k| seconds[k].as_f64().unwrap())
        .sum();
    assert!((whole - parts).abs() < 1e-9, "{value}");
    assert_eq!(value["over_bandwidth"].as_array().unwrap().len(), 7);
}

/// A faster memory never makes the top slower, and the link's bandwidth
/// moves only the transfer's share of the end-to-end time.
#[test]
fn the_memory_and_the_link_are_options() {
    let json = |args: &[&str]| -> serde_json::Value {
        let path = scratch_path(&format!("dram-{}.json", args.join("_")));
        let mut all = vec!["sim", "--no-compare", "--json", path.to_str().unwrap()];
        all.extend(args);
        let o = tritri(&all);
        assert!(o.status.success(), "{}", text(&o.stderr));
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap()
    };
    let (slow, fast) = (
        json(&["--memory-gbytes", "0.4"]),
        json(&["--memory-gbytes", "12.8"]),
    );
    assert!(
        slow["clocks"].as_u64() > fast["clocks"].as_u64(),
        "{slow} {fast}"
    );
    let (narrow, wide) = (
        json(&["--link-gbytes", "0.1"]),
        json(&["--link-gbytes", "10"]),
    );
    assert_eq!(narrow["clocks"], wide["clocks"]);
    let link = |v: &serde_json::Value| v["seconds"]["link_in"].as_f64().unwrap();
    // (Durations are whole nanoseconds.)
    assert!((link(&narrow) / link(&wide) - 100.0).abs() < 0.1);
    // An assumed clock is named as such.
    let out = tritri(&["sim", "--no-compare", "--clock-mhz", "50"]);
    assert!(
        text(&out.stdout).contains("at 50.0 MHz (assumed)"),
        "{}",
        text(&out.stdout)
    );
    // A port without a post-route clock is at the assumed 100 MHz.
    let out = tritri(&["sim", "--no-compare", "--data-bits", "64"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("at 100.0 MHz (assumed), 64-bit AXI4 port"),
        "{}",
        text(&out.stdout)
    );
}

/// The octree broad phase reports the flat system's pairs
/// while testing far fewer pairs in far fewer cycles.
#[test]
fn octree_gives_the_flat_pairs_with_less_work() {
    let run = |broad_phase: &str, out: &PathBuf| {
        let o = tritri(&[
            "sim",
            "--verbose",
            "--broad-phase",
            broad_phase,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", text(&o.stderr));
        text(&o.stdout)
    };
    let (flat_pairs, octree_pairs) = (
        scratch_path("flat_default.txt"),
        scratch_path("octree_default.txt"),
    );
    let (flat, octree) = (run("flat", &flat_pairs), run("octree", &octree_pairs));
    assert_eq!(
        std::fs::read_to_string(&flat_pairs).unwrap(),
        std::fs::read_to_string(&octree_pairs).unwrap()
    );
    let number_after = |report: &str, key: &str| -> u64 {
        let rest = &report[report
            .find(key)
            .unwrap_or_else(|| panic!("no `{key}` in {report}"))
            + key.len()..];
        rest.split(|c: char| !c.is_ascii_digit())
            .find(|s| !s.is_empty())
            .unwrap()
            .parse()
            .unwrap()
    };
    let (flat_tested, octree_tested) = (
        number_after(&flat, "pairs tested: "),
        number_after(&octree, "pairs tested: "),
    );
    let (flat_cycles, octree_cycles) = (
        number_after(&flat, "cycles: "),
        number_after(&octree, "cycles: "),
    );
    assert!(
        octree_tested * 20 < flat_tested,
        "{octree_tested} vs {flat_tested}"
    );
    assert!(
        octree_cycles * 10 < flat_cycles,
        "{octree_cycles} vs {flat_cycles}"
    );
    // Work within 4 x the pairs whose triangle boxes overlap (3.4 x here:
    // the split rule also counts the binning unit's classifications).
    assert!(
        octree_tested <= 4 * number_after(&octree, "box-overlap pairs ("),
        "{octree}"
    );
    // The whole run is the broad-phase top's cycles (binning, then the
    // leaves through the system's banks) and, at most, its owner filter's;
    // the filter drops the duplicates the leaves found, leaving each pair
    // once.
    let binning = number_after(&octree, "frames deep: ");
    let top = number_after(&octree, "the broad-phase top: binning and narrow phase ");
    let top_filter = number_after(&octree, "+ its owner filter at most ");
    assert!(
        binning > 0 && top > binning && top > octree_cycles && top_filter > 0,
        "{octree}"
    );
    let filter = number_after(&octree, "pairs through; ");
    let (hits, pairs) = (
        number_after(&octree, "owner filter (hardware rule"),
        number_after(&octree, "intersecting pairs on the grid: "),
    );
    assert!(
        hits > pairs
            && octree.contains(&format!(
                "{} duplicates dropped, {pairs} pairs through",
                hits - pairs
            )),
        "{octree}"
    );
    assert!(filter >= 2 * hits, "{octree}");
}

/// Pairs are `i j` lines; splitting into tiles (small D) gives the same
/// pairs as one batch, and says that it split; degenerate triangles (a
/// point, a segment, a zero-area triangle) go through.
#[test]
fn tiled_run_writes_the_same_pairs_as_untiled_with_degenerate_triangles() {
    let a = scratch(
        "a.off",
        "OFF\n7 5 0\n0 0 0\n1 0 0\n0 1 0\n0.5 0.5 0\n1 1 0\n-1 -1 0.5\n2 2 0.5\n3 0 1 2\n3 3 3 3\n3 0 4 4\n3 5 6 6\n4 0 1 4 2\n",
    );
    let b = scratch(
        "b.obj",
        "v 0.2 0.2 -1\nv 0.2 0.2 1\nv 0.9 0.9 0.5\nv 0.5 0.5 0\nf 1 2 3\nf 4 4 4\nf 1 2 2\n",
    );
    let (one, tiles) = (scratch_path("one.txt"), scratch_path("tiles.txt"));
    let run = |depth: &str, out: &PathBuf| {
        tritri(&[
            "sim",
            "--verbose",
            "--broad-phase",
            "flat",
            "--scene",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "--depth",
            depth,
            "--out",
            out.to_str().unwrap(),
        ])
    };
    let r1 = run("100", &one);
    assert!(r1.status.success(), "{}", text(&r1.stderr));
    let r2 = run("2", &tiles);
    assert!(r2.status.success(), "{}", text(&r2.stderr));
    assert!(
        text(&r2.stdout).contains("split into"),
        "{}",
        text(&r2.stdout)
    );
    let pairs = std::fs::read_to_string(&one).unwrap();
    assert_eq!(pairs, std::fs::read_to_string(&tiles).unwrap());
    assert!(
        pairs
            .lines()
            .all(|l| l.split(' ').count() == 2 && l.split(' ').all(|n| n.parse::<u32>().is_ok())),
        "{pairs}"
    );
    // The point (0.5,0.5,0) is A's triangle 1 and B's triangle 1, and lies on B's vertical triangle 0.
    assert!(
        pairs.lines().any(|l| l == "1 1") && pairs.lines().any(|l| l == "1 0"),
        "{pairs}"
    );
    assert!(pairs.lines().count() >= 4, "{pairs}");
    assert!(
        text(&r1.stdout).contains("0 pairs missing, 0 extra"),
        "{}",
        text(&r1.stdout)
    );
    // The octree broad phase, with memories of 2 and of 100, reports the same pairs.
    for depth in ["2", "100"] {
        let octree = scratch_path(&format!("octree{depth}.txt"));
        let r = tritri(&[
            "sim",
            "--broad-phase",
            "octree",
            "--verbose",
            "--scene",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "--depth",
            depth,
            "--out",
            octree.to_str().unwrap(),
        ]);
        assert!(r.status.success(), "{}", text(&r.stderr));
        assert!(
            text(&r.stdout).contains("broad phase: octree"),
            "{}",
            text(&r.stdout)
        );
        assert_eq!(
            pairs,
            std::fs::read_to_string(&octree).unwrap(),
            "octree, depth {depth}"
        );
    }

    // Face indices: the quad (face 4) is triangles 4 and 5.
    let faces = scratch_path("faces.txt");
    let r3 = tritri(&[
        "sim",
        "--verbose",
        "--scene",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--indices",
        "faces",
        "--out",
        faces.to_str().unwrap(),
    ]);
    assert!(r3.status.success());
    assert!(std::fs::read_to_string(&faces).unwrap().lines().all(|l| l
        .split(' ')
        .next()
        .unwrap()
        .parse::<u32>()
        .unwrap()
        <= 4));
}

/// With --no-split, arrays deeper than the memory depth are an error naming
/// the sizes and the depth.
#[test]
fn no_split_error_names_the_sizes() {
    let out = tritri(&[
        "sim",
        "--verbose",
        "--broad-phase",
        "flat",
        "--depth",
        "100",
        "--no-split",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(
        err.contains("(A)") && err.contains("(B)") && err.contains("memory depth 100"),
        "{err}"
    );
}

/// A pose that is not six (or three) numbers is refused by the parser.
#[test]
fn bad_pose_is_refused() {
    let out = tritri(&["sim", "--pose-b", "1,2"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("bad pose"),
        "{}",
        text(&out.stderr)
    );
    // Negative numbers are values, not flags.
    assert!(tritri(&["sim", "--pose-b", "-0.1,0,0,0,0,-45"])
        .status
        .success());
}

/// Pairs to stdout with `--out -`, the report then goes to stderr.
#[test]
fn pairs_to_stdout_send_the_report_to_stderr() {
    let out = tritri(&["sim", "--out", "-"]);
    assert!(out.status.success());
    let stdout = text(&out.stdout);
    assert!(
        stdout.lines().count() > 10 && stdout.lines().all(|l| l.split(' ').count() == 2),
        "{stdout}"
    );
    assert!(text(&out.stderr).contains("exact pairs: 113"));
}

/// The chapter-5 table: one row per target share, the share reached at or
/// above the target.
#[test]
fn chapter5_prints_one_row_per_share() {
    let out = tritri(&[
        "chapter5",
        "--scene",
        "@sphere",
        "@sphere",
        "--fractions",
        "25,50",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let report = text(&out.stdout);
    let rows: Vec<&str> = report
        .lines()
        .filter(|l| l.starts_with("| 25 %") || l.starts_with("| 50 %"))
        .collect();
    assert_eq!(rows.len(), 2, "{report}");
    for (row, target) in rows.iter().zip([25.0, 50.0]) {
        let share: f64 = row
            .split('=')
            .nth(1)
            .unwrap()
            .trim()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(share >= target && share < target + 10.0, "{row}");
    }
}

/// The rust-hdl simulation of the system gives the same pairs and the same
/// cycle count as the model engine, on a tiled scene with degenerate
/// triangles (several batches through the two banks).
#[test]
fn rusthdl_engine_agrees_with_the_model() {
    let a = scratch(
        "ra.off",
        "OFF\n5 4 0\n0 0 0\n1 0 0\n0 1 0\n0.5 0.5 0\n1 1 0\n3 0 1 2\n3 3 3 3\n3 0 4 4\n4 0 1 4 2\n",
    );
    let b = scratch(
        "rb.obj",
        "v 0.2 0.2 -1\nv 0.2 0.2 1\nv 0.9 0.9 0.5\nv 0.5 0.5 0\nf 1 2 3\nf 4 4 4\nf 1 2 2\n",
    );
    let (model, hdl) = (scratch_path("model.txt"), scratch_path("hdl.txt"));
    let run = |engine: &str, out: &PathBuf| {
        let o = tritri(&[
            "sim",
            "--broad-phase",
            "octree",
            "--verbose",
            "--scene",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "--depth",
            "2",
            "--engine",
            engine,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{engine}: {}", text(&o.stderr));
        let report = text(&o.stdout);
        assert!(report.contains(": equal"), "{report}");
        report
            .lines()
            .find(|l| l.starts_with("cycles:"))
            .unwrap()
            .to_string()
    };
    let (cycles_model, cycles_hdl) = (run("model", &model), run("rusthdl", &hdl));
    assert_eq!(cycles_model, cycles_hdl);
    let pairs = std::fs::read_to_string(&model).unwrap();
    assert!(!pairs.is_empty());
    assert_eq!(pairs, std::fs::read_to_string(&hdl).unwrap());
}

/// `--grid-bits G` above W: leaves go to W-bit hardware in frames of their
/// own and the answer is the flat system's on the same G-bit grid; a grid
/// below W, or above W with the flat system, is refused naming the option.
#[test]
fn local_frames_give_the_answer_of_the_finer_grid() {
    let (local, flat) = (scratch_path("local.txt"), scratch_path("flat20.txt"));
    let o = tritri(&[
        "sim",
        "--broad-phase",
        "octree",
        "--verbose",
        "--width",
        "16",
        "--grid-bits",
        "20",
        "--out",
        local.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(
        text(&o.stdout).contains("local frames: leaves go to the 16-bit hardware"),
        "{}",
        text(&o.stdout)
    );
    let o = tritri(&[
        "sim",
        "--verbose",
        "--broad-phase",
        "flat",
        "--width",
        "20",
        "--out",
        flat.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert_eq!(
        std::fs::read_to_string(&local).unwrap(),
        std::fs::read_to_string(&flat).unwrap()
    );
    for bad in [
        &[
            "sim",
            "--broad-phase",
            "octree",
            "--width",
            "24",
            "--grid-bits",
            "16",
        ][..],
        &[
            "sim",
            "--verbose",
            "--broad-phase",
            "flat",
            "--width",
            "16",
            "--grid-bits",
            "20",
        ],
    ] {
        let o = tritri(bad);
        assert_eq!(o.status.code(), Some(2), "{bad:?}");
        assert!(
            text(&o.stderr).contains("--grid-bits"),
            "{}",
            text(&o.stderr)
        );
    }
}

/// `--png`: the render is a PNG of the asked size with the contact in the
/// hit colours; a name that is not .png, or `-`, is refused before any
/// work (status 2, the option named).
#[test]
fn png_renders_the_contact() {
    let png = scratch_path("scene.png");
    let out = tritri(&[
        "sim",
        "--verbose",
        "--png",
        png.to_str().unwrap(),
        "--size",
        "128",
        "--up",
        "z",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("render:")
            && text(&out.stdout).contains("113 pairs highlighted"),
        "{}",
        text(&out.stdout)
    );
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(
        (
            u32::from_be_bytes(bytes[16..20].try_into().unwrap()),
            u32::from_be_bytes(bytes[20..24].try_into().unwrap())
        ),
        (128, 128)
    );
    for bad in ["scene.jpg", "-"] {
        let out = tritri(&["sim", "--png", bad]);
        assert_eq!(out.status.code(), Some(2), "{bad}");
        assert!(
            text(&out.stderr).contains("--png") && text(&out.stderr).contains(".png"),
            "{}",
            text(&out.stderr)
        );
        assert!(
            !text(&out.stdout).contains("pairs tested"),
            "{bad}: refused before any work"
        );
    }
}

/// `--tolerance`: a wavy patch 3 units wide cut by the built-in sphere
/// (0.8 across): only pieces near the sphere become triangles, fewer than
/// the whole patch at the same tolerance, and the contact is found; a
/// tolerance that is not a positive number is refused (status 2).
#[test]
fn tolerance_tessellates_only_what_the_query_needs() {
    let mut bpt = String::from("1\n3 3\n");
    for i in 0..4 {
        for j in 0..4 {
            bpt.push_str(&format!(
                "{} {} {}\n",
                i as f64,
                j as f64 - 1.5,
                0.5 + 0.05 * ((i + j) % 2) as f64
            ));
        }
    }
    let patch = scratch("wavy.bpt", &bpt);
    let out = tritri(&[
        "sim",
        "--broad-phase",
        "octree",
        "--verbose",
        "--scene",
        patch.to_str().unwrap(),
        "@sphere",
        "--tolerance",
        "0.001",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let report = text(&out.stdout);
    let note = report
        .lines()
        .find(|l| l.starts_with("tessellation for the query:"))
        .unwrap_or_else(|| panic!("{report}"));
    // The numbers after the file's path (a target directory's name may
    // hold digits).
    let numbers: Vec<u64> = note
        .split_once(".bpt: ")
        .map_or(note, |(_, rest)| rest)
        .split(|c: char| !c.is_ascii_digit())
        .filter_map(|w| w.parse().ok())
        .collect();
    // "... 1 of 1 patches ..., cut into P pieces: T triangles within 0.001 ..., against U for every patch at N samples a side"
    let (pieces, triangles, uniform) = (numbers[2], numbers[3], numbers[numbers.len() - 2]);
    assert!(
        pieces > 1 && triangles > 0 && triangles * 4 < uniform,
        "{note}"
    );
    let hits: u64 = report
        .lines()
        .find_map(|l| l.strip_prefix("intersecting pairs on the grid: "))
        .and_then(|n| n.trim().parse().ok())
        .unwrap();
    assert!(hits > 0, "{report}");
    // With a hardware engine the pieces go through the tessellation unit
    // (its triangles assembled) in it, and the contact is still found.
    let out = tritri(&[
        "sim",
        "--broad-phase",
        "octree",
        "--verbose",
        "--scene",
        patch.to_str().unwrap(),
        "@sphere",
        "--tolerance",
        "0.001",
        "--engine",
        "rusthdl",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let report = text(&out.stdout);
    assert!(
        report.contains("for the tessellation unit in rusthdl (24-bit grid"),
        "{report}"
    );
    let unit_hits: u64 = report
        .lines()
        .find_map(|l| l.strip_prefix("intersecting pairs on the grid: "))
        .and_then(|n| n.trim().parse().ok())
        .unwrap();
    assert!(unit_hits > 0, "{report}");
    for bad in ["0", "-1", "x"] {
        let out = tritri(&[
            "sim",
            "--verbose",
            "--scene",
            patch.to_str().unwrap(),
            "@sphere",
            "--tolerance",
            bad,
        ]);
        assert_eq!(out.status.code(), Some(2), "--tolerance {bad}");
        assert!(
            text(&out.stderr).contains("--tolerance"),
            "{}",
            text(&out.stderr)
        );
    }
}

/// `--broad-phase-top`: the emitted broad-phase top (binning unit, system,
/// owner filter) in Verilator on the built-in scene gives its model's
/// pairs, `done` within its models' window, and the exact answer on the
/// original coordinates; without a hardware engine it is refused (status 2).
#[test]
fn broad_phase_top_runs_from_the_command_line() {
    let out = tritri(&[
        "sim",
        "--broad-phase",
        "octree",
        "--verbose",
        "--broad-phase-top",
        "--engine",
        "verilator",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}{}",
        text(&out.stdout),
        text(&out.stderr)
    );
    let report = text(&out.stdout);
    for needle in [
        "broad-phase top tritri_broad_phase_g24_w24_p2_d256",
        "114 pairs out once each, 4 without a certificate",
        "its pairs equal its model's",
        "check: engine = exact model on the quantized coordinates (114 pairs): equal",
        "exact pairs: 0 missing, 0 extra against exact f64",
    ] {
        assert!(report.contains(needle), "no `{needle}` in:\n{report}");
    }
    let out = tritri(&["sim", "--broad-phase", "octree", "--broad-phase-top"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("--broad-phase-top"),
        "{}",
        text(&out.stderr)
    );
}

/// A fault (here the engine's pairs against the exact model on the same
/// grid, one pair lost on purpose through the library's test hook) reaches
/// the user as `fault: ...` on stderr and exit status 1, with the report
/// and the pairs still written; the same run without the hook exits 0.
#[test]
fn a_fault_exits_with_status_1_and_names_what_differed() {
    let pairs = scratch_path("faulty.txt");
    let out = Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args(["sim", "--out", pairs.to_str().unwrap()])
        .env("TRITRI_INJECT_FAULT", "drop-grid-pair")
        .output()
        .expect("run tritri");
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(
        err.contains("fault: the model engine differs from the exact model on the quantized coordinates: 1 pairs missing, 0 extra"),
        "{err}"
    );
    assert!(
        text(&out.stdout).contains("1 missing, 0 extra: a bug"),
        "{}",
        text(&out.stdout)
    );
    assert!(std::fs::read_to_string(&pairs).unwrap().lines().count() > 100);
    assert_eq!(tritri(&["sim"]).status.code(), Some(0));
}

/// Every engine runs the DRAM top on the built-in scene: rust-hdl, Icarus
/// and Verilator simulate the emitted design against the AXI4 memory model
/// and give the model's pairs and clocks (a difference would be a fault,
/// status 1).
#[test]
fn every_engine_runs_the_dram_top() {
    let run = |engine: &str| {
        let pairs = scratch_path(&format!("dram-{engine}.txt"));
        let json = scratch_path(&format!("dram-{engine}.json"));
        let out = tritri(&[
            "sim",
            "--engine",
            engine,
            "--out",
            pairs.to_str().unwrap(),
            "--json",
            json.to_str().unwrap(),
        ]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{engine}: {}",
            text(&out.stderr)
        );
        let value: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        (
            std::fs::read_to_string(&pairs).unwrap(),
            value["clocks"].clone(),
        )
    };
    let model = run("model");
    assert_eq!(model.0.lines().count(), 113);
    for engine in ["rusthdl", "icarus", "verilator"] {
        assert_eq!(run(engine), model, "{engine}");
    }
}
