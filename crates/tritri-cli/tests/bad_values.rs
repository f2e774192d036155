//! Values users get wrong, each refused with exit status 2 and a message
//! naming the option, never a panic (exit 101); and a reader that closes the
//! pipe early ends the program quietly.

use std::io::Read;
use std::process::{Command, Output, Stdio};

fn tritri(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args(args)
        .output()
        .expect("run tritri")
}

#[test]
fn out_of_range_options_are_usage_errors_naming_the_option() {
    let out_dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad-values-gen");
    let out_dir = out_dir.to_str().unwrap();
    let out_vcd = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad-values.vcd");
    let out_vcd = out_vcd.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["sim", "--clock-mhz", "0"], "--clock-mhz"),
        (&["sim", "--clock-mhz", "nan"], "--clock-mhz"),
        (&["sim", "--clock-mhz", "-5"], "--clock-mhz"),
        (&["sim", "--clock-mhz", "1e-300"], "--clock-mhz"),
        (&["sim", "--clock-mhz", "inf"], "--clock-mhz"),
        (&["chapter5", "--clock-mhz", "0"], "--clock-mhz"),
        (&["sim", "--depth", "32768"], "--depth"),
        (
            &["gen", "--system", "--depth", "32768", "--out", out_dir],
            "--depth",
        ),
        (&["sim", "--scale-b", "0"], "--scale-b"),
        // A negative number is the option's value, refused by its rule
        // (it was "unexpected argument '-1'").
        (&["sim", "--scale-b", "-1"], "--scale-b"),
        // Counts of clocks name their range ("invalid digit" did not).
        (&["sim", "--max-cycles", "1e3"], "a whole number from 0 to"),
        (&["sim", "--max-cycles", "-1"], "a whole number from 0 to"),
        // So does every other whole-number option (issue 68, item 9; the
        // rule for all of them is a unit test of the command line).
        (
            &["sim", "--depth", "-1"],
            "`-1` is not a whole number from 1 to 32767",
        ),
        (
            &["gen", "--pipelines", "x", "--out", out_dir],
            "`x` is not a whole number from 1 to 16",
        ),
        (&["sim", "--vcd-max-cycles", "x"], "--vcd-max-cycles"),
        // A timing time that would run without end (issue 68, item 7).
        (
            &["report", "--min-time-ms", "1099511627776", "--out", out_dir],
            "--min-time-ms",
        ),
        (&["eval", "--min-time-ms", "-1", "@hard"], "--min-time-ms"),
        (&["sim", "--subdivide", "9"], "--subdivide"),
        (&["sim", "--grid-bits", "40"], "--grid-bits"),
        (&["sim", "--tessellation", "0"], "--tessellation"),
        (&["chapter5", "--fractions", "0"], "--fractions"),
        (&["sim", "--tessellation", "100000"], "--tessellation"),
        (
            &[
                "sim",
                "--broad-phase",
                "octree",
                "--width",
                "10",
                "--engine",
                "verilator",
            ],
            "--width 10 --engine verilator",
        ),
        // The DRAM design (the default) is fixed; the design studies take
        // none of its board's options.
        (
            &["sim", "--width", "16"],
            "--width does not apply to --broad-phase dram",
        ),
        (
            &["sim", "--pipelines", "1"],
            "--pipelines does not apply to --broad-phase dram",
        ),
        (
            &["sim", "--grid-bits", "24"],
            "--grid-bits does not apply to --broad-phase dram",
        ),
        (
            &["sim", "--rare-cases", "shared"],
            "--rare-cases does not apply to --broad-phase dram",
        ),
        (
            &["sim", "--no-split"],
            "--no-split does not apply to --broad-phase dram",
        ),
        (
            &["sim", "--broad-phase", "octree", "--data-bits", "256"],
            "--data-bits does not apply to --broad-phase octree",
        ),
        (
            &["sim", "--broad-phase", "flat", "--memory-gbytes", "3.2"],
            "--memory-gbytes does not apply to --broad-phase flat",
        ),
        (&["sim", "--data-bits", "100"], "--data-bits"),
        (&["sim", "--memory-gbytes", "0"], "--memory-gbytes"),
        (&["sim", "--link-gbytes", "-1"], "--link-gbytes"),
        (
            &["sim", "--out", "/nonexistent-directory/pairs.txt"],
            "--out",
        ),
        (
            &[
                "sim",
                "--engine",
                "rusthdl",
                "--broad-phase",
                "flat",
                "--max-cycles",
                "1000",
            ],
            "--max-cycles",
        ),
        (
            &["sim", "--broad-phase", "octree", "--vcd", "wave.vcd"],
            "--vcd needs --engine icarus or verilator",
        ),
        (
            &[
                "sim",
                "--broad-phase",
                "octree",
                "--engine",
                "icarus",
                "--vcd",
                "/nonexistent-directory/wave.vcd",
            ],
            "--vcd: ",
        ),
        (
            &[
                "sim",
                "--broad-phase",
                "octree",
                "--engine",
                "icarus",
                "--vcd",
                "-",
            ],
            "--vcd -",
        ),
        (
            &[
                "sim",
                "--broad-phase",
                "octree",
                "--engine",
                "verilator",
                "--vcd",
                out_vcd,
                "--vcd-max-cycles",
                "100",
            ],
            "--vcd-max-cycles 100",
        ),
        (&["gen", "--owner-filter", "--slots", "0"], "--slots"),
        (&["gen", "--owner-filter", "--slots", "16777217"], "--slots"),
        (&["gen", "--slots", "64"], "--owner-filter"),
        (&["gen", "--broad-phase", "--depth", "3"], "--depth 3"),
        (&["gen", "--broad-phase", "--width", "20"], "--width 20"),
        (&["gen", "--triangles", "64"], "--broad-phase"),
        (&["gen", "--owner-filter", "--width", "16"], "--width"),
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
    let out = tritri(&[
        "gen",
        "--system",
        "--depth",
        "32767",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
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
        assert!(
            out.stderr.is_empty(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// An empty mesh is an error naming the file; nothing is written to `--out`.
#[test]
fn empty_mesh_is_an_error_and_leaves_no_output() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("empty-mesh");
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = dir.join("empty.off");
    std::fs::write(&mesh, "OFF\n0 0 0\n").unwrap();
    let pairs = dir.join("pairs.txt");
    let _ = std::fs::remove_file(&pairs);
    let out = tritri(&[
        "sim",
        "--scene",
        mesh.to_str().unwrap(),
        "@sphere",
        "--out",
        pairs.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("empty.off") && err.contains("no triangles"),
        "{err}"
    );
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        left,
        [std::ffi::OsString::from("empty.off")],
        "no pairs file and no temporary"
    );
}

/// A request far above `--max-cycles` is refused at once, before any
/// simulator starts (the estimate comes from the cycle model).
#[test]
fn long_simulation_is_refused_in_under_a_second() {
    let started = std::time::Instant::now();
    let out = tritri(&[
        "sim",
        "--engine",
        "verilator",
        "--broad-phase",
        "flat",
        "--subdivide",
        "4",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    // 969,418,087 + the memories' read latency + the pipeline's latency +
    // the counters' clock (the demo scene's flat estimate).
    let expected = 969_418_087
        + (tritri_rtl::system::MEMORY_READ_LATENCY
            + tritri_rtl::pipeline::triangle_pipeline::latency()
            + tritri_rtl::system::COUNT_LATENCY) as u64;
    assert!(
        err.contains(&format!("{expected} cycles is above --max-cycles")),
        "{err}"
    );
    assert!(
        String::from_utf8_lossy(&out.stdout).contains("estimate: "),
        "the estimate is printed"
    );
    // Generous against a loaded machine; the point is: no simulation ran.
    assert!(
        started.elapsed() < std::time::Duration::from_secs(20),
        "{:?}",
        started.elapsed()
    );
}

/// A full disk behind standard output is an error that names it, status 1,
/// not a panic (issue 68, item 2).
#[test]
fn a_full_standard_output_is_an_error_naming_it() {
    let pairs = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/data/six_pairs.txt"
    );
    for args in [
        &["eval", pairs][..],
        &["classify", pairs][..],
        &["sim", "--no-compare"][..],
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_tritri"))
            .args(args)
            .stdout(full)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains("writing to standard output: No space left on device"),
            "{args:?}: {err}"
        );
    }
}

/// An empty pair file is an empty answer, exit 0, with a note that says so
/// (it was silent: no output and no note).
#[test]
fn an_empty_pair_file_is_said_to_be_empty() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("empty-pairs");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("none.txt");
    std::fs::write(&file, "").unwrap();
    let out = tritri(&["classify", file.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(err.contains("no pairs in the file"), "{err}");
}

/// An output that names an input (by any path to the same file) is
/// refused before the work, and the input is left as it was.
#[test]
fn an_output_over_an_input_is_refused_and_the_input_kept() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("output-over-input");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n";
    let a = dir.join("a.obj");
    let b = dir.join("b.obj");
    std::fs::write(&a, mesh).unwrap();
    std::fs::write(&b, mesh).unwrap();
    let (a_s, b_s) = (a.to_str().unwrap(), b.to_str().unwrap());
    // The same file by another name.
    let b_other = format!("{}/./b.obj", dir.display());
    let cases: &[(&[&str], &str)] = &[
        (&["sim", "--scene", a_s, b_s, "--out", a_s], "--out"),
        (&["sim", "--scene", a_s, b_s, "--out", &b_other], "--out"),
        (&["sim", "--scene", a_s, b_s, "--json", a_s], "--json"),
        (
            &["voxelize", a_s, "--resolution", "8", "--out", a_s],
            "it is the input",
        ),
    ];
    for (args, names) in cases {
        let out = tritri(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(names) && stderr.contains("it is the input"),
            "{args:?}: {stderr}"
        );
        for input in [&a, &b] {
            assert_eq!(
                std::fs::read_to_string(input).unwrap(),
                mesh,
                "{args:?} changed {}",
                input.display()
            );
        }
    }
}

/// An output path that cannot be written (empty, or a directory that
/// cannot be made) is refused before the work, naming the option.
#[test]
fn an_unwritable_output_is_refused_before_the_work() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["sim", "--scene", "@torus", "@sphere", "--out", ""],
            "--out: an empty path",
        ),
        (
            &["sim", "--scene", "@torus", "@sphere", "--json", ""],
            "--json: an empty path",
        ),
        (
            &[
                "sim",
                "--scene",
                "@torus",
                "@sphere",
                "--broad-phase",
                "octree",
                "--engine",
                "icarus",
                "--vcd",
                "",
            ],
            "--vcd: an empty path",
        ),
        (
            &["report", "@hard", "--out", "/proc/x"],
            "--out /proc/x: cannot create",
        ),
    ];
    for (args, says) in cases {
        let out = tritri(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
        // Refused before the work: nothing was loaded, run or measured.
        assert!(
            out.stdout.is_empty(),
            "{args:?} printed {}",
            String::from_utf8_lossy(&out.stdout)
        );
    }
}

/// A file that holds more or other than it declares is refused at its
/// line, and errors say what the user needs (issue 68, items 8 and 9).
#[test]
fn files_that_say_more_than_they_declare_are_refused_at_the_line() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("extra-input");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let tet = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 0 2 3\n";
    let off_junk = write("junk.off", &format!("{tet}3 1 2 3 junk\n"));
    let off_extra = write("extra.off", &format!("{tet}3 1 2 3\n3 1 2 3\n"));
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let ply_extra = write("extra.ply", &format!("{ply}3 0 1 2\n"));
    let obj = write("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    let pairs_object = write("object.json", "{\"t1\": 1}\n");
    let cases: &[(Vec<&str>, String)] = &[
        (
            vec!["voxelize", &off_junk, "--out", "x.oct"],
            format!("{off_junk}:10: `junk` after the face's 3 vertex indices"),
        ),
        (
            vec!["voxelize", &off_extra, "--out", "x.oct"],
            format!("{off_extra}:11: more lines after the 4 faces"),
        ),
        (
            vec!["voxelize", &ply_extra, "--out", "x.oct"],
            format!("{ply_extra}:14: more data after the elements"),
        ),
        (
            vec!["voxelize", &obj, "--out", "x.oct"],
            format!(
                "{obj}:4: vertex index 4 out of range (the file has 3 vertices, numbered from 1)"
            ),
        ),
        (
            vec!["classify", &pairs_object],
            "must be an array of objects".to_string(),
        ),
        (
            vec!["octree", "render", &off_junk, "--png", "x.png"],
            "read from .oct files only".to_string(),
        ),
    ];
    for (args, expected) in cases {
        let out = tritri(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(expected.as_str()), "{args:?}: {stderr}");
    }
    // A file that cannot be read at all is told once, as that.
    let out = tritri(&["classify", dir.join("missing.txt").to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("No such file"), "{stderr}");
}
