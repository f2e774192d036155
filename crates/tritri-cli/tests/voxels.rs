//! `tritri voxelize` and `tritri octree` end to end: a built-in mesh
//! voxelized to an octree file, the set-operation laws on files, the
//! half-space cut and clipping, conversion to every format; bad input
//! refused with exit status 2 and a message naming it.

use std::path::PathBuf;
use std::process::{Command, Output};

fn tritri(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tritri"))
        .args(args)
        .output()
        .expect("run tritri")
}

fn ok(args: &[&str]) -> String {
    let out = tritri(args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The number after `label` in `text`.
fn number_after(text: &str, label: &str) -> u64 {
    let at = text
        .find(label)
        .unwrap_or_else(|| panic!("no `{label}` in {text}"))
        + label.len();
    text[at..]
        .trim_start()
        .split(|c: char| !c.is_ascii_digit())
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn voxelized_models_obey_the_laws_of_set_operations() {
    let d = dir("voxels-laws");
    let p = |name: &str| d.join(name).to_str().unwrap().to_string();
    let surface = ok(&[
        "voxelize",
        "@torus",
        "--resolution",
        "32",
        "--out",
        &p("surface.oct"),
    ]);
    let solid = ok(&[
        "voxelize",
        "@torus",
        "--resolution",
        "32",
        "--solid",
        "--out",
        &p("solid.oct"),
        "--out",
        &p("solid.binvox"),
        "--out",
        &p("solid.vox"),
        "--out",
        &p("solid.obj"),
        "--png",
        &p("solid.png"),
    ]);
    let (n_surface, n_solid) = (
        number_after(&surface, "surface:"),
        number_after(&solid, "solid:"),
    );
    assert!(
        n_surface > 500 && n_solid > n_surface / 2,
        "{surface}\n{solid}"
    );
    for ext in ["binvox", "vox", "obj", "png"] {
        assert!(
            std::fs::metadata(p(&format!("solid.{ext}"))).unwrap().len() > 100,
            "{ext}"
        );
    }
    // A ∪ B ⊇ A ⊇ A ∩ B; A \ A is empty; (A ∪ B) \ B = A \ B; union commutes.
    let union = ok(&[
        "octree",
        "union",
        &p("surface.oct"),
        &p("solid.oct"),
        "--out",
        &p("union.oct"),
    ]);
    let union_ba = ok(&[
        "octree",
        "union",
        &p("solid.oct"),
        &p("surface.oct"),
        "--out",
        &p("union_ba.oct"),
    ]);
    assert_eq!(
        std::fs::read(p("union.oct")).unwrap(),
        std::fs::read(p("union_ba.oct")).unwrap(),
        "{union}\n{union_ba}"
    );
    let inter = ok(&[
        "octree",
        "intersection",
        &p("surface.oct"),
        &p("solid.oct"),
        "--out",
        &p("inter.oct"),
    ]);
    let (n_union, n_inter) = (
        number_after(&union, "Union:"),
        number_after(&inter, "Intersection:"),
    );
    assert!(
        n_inter <= n_surface.min(n_solid) && n_union >= n_surface.max(n_solid),
        "{union}\n{inter}"
    );
    assert_eq!(n_union + n_inter, n_surface + n_solid);
    let empty = ok(&["octree", "difference", &p("solid.oct"), &p("solid.oct")]);
    assert_eq!(number_after(&empty, "Difference:"), 0);
    ok(&[
        "octree",
        "difference",
        &p("union.oct"),
        &p("solid.oct"),
        "--out",
        &p("u_minus_b.oct"),
    ]);
    ok(&[
        "octree",
        "difference",
        &p("surface.oct"),
        &p("solid.oct"),
        "--out",
        &p("a_minus_b.oct"),
    ]);
    assert_eq!(
        std::fs::read(p("u_minus_b.oct")).unwrap(),
        std::fs::read(p("a_minus_b.oct")).unwrap()
    );
    // The half-space cut keeps what the plane leaves, and clipping to the
    // whole grid keeps everything.
    let cut = ok(&[
        "octree",
        "plane",
        &p("solid.oct"),
        "--normal",
        "1,0,0",
        "--offset",
        "16",
        "--out",
        &p("cut.oct"),
    ]);
    let kept = number_after(&cut, "cut:");
    assert!(kept > 0 && kept < n_solid, "{cut}");
    let clip = ok(&["octree", "clip", &p("solid.oct"), "--box", "0,0,0,32,32,32"]);
    // Display data: the boundary's edges clipped to half the grid.
    let seg = ok(&[
        "octree",
        "clip",
        &p("solid.oct"),
        "--box",
        "0,0,0,16,32,32",
        "--segments",
        &p("edges.obj"),
    ]);
    let obj = std::fs::read_to_string(p("edges.obj")).unwrap();
    let lines = obj.lines().filter(|l| l.starts_with("l ")).count() as u64;
    assert!(
        lines > 0 && seg.contains(&format!("({lines} segments)")),
        "{seg}"
    );
    let edges = number_after(&seg, "segments:");
    assert!(lines < edges, "half the grid keeps fewer edges: {seg}");
    // The hardware units agree with the model (the command fails if not).
    let hardware = ok(&[
        "octree",
        "intersection",
        &p("surface.oct"),
        &p("solid.oct"),
        "--engine",
        "rusthdl",
    ]);
    assert!(
        hardware.contains("hardware (rusthdl): 512 words of 64 voxels, the model's result"),
        "{hardware}"
    );
    let clipped = ok(&[
        "octree",
        "clip",
        &p("solid.oct"),
        "--box",
        "3,-5,7,20,31,40",
        "--engine",
        "rusthdl",
    ]);
    assert!(
        clipped.contains("hardware (rusthdl): the model's"),
        "{clipped}"
    );
    let voxelized = ok(&[
        "voxelize",
        "@torus",
        "--resolution",
        "16",
        "--engine",
        "verilator",
    ]);
    assert!(
        voxelized.contains("hardware (verilator): ")
            && voxelized.contains("the model's voxels")
            && voxelized.contains("octree builder"),
        "{voxelized}"
    );
    let filled = ok(&["octree", "convert", &p("solid.oct"), "--engine", "rusthdl"]);
    assert!(filled.contains("the model's voxels"), "{filled}");
    assert!(
        filled.contains("octree builder") && filled.contains("nodes out"),
        "{filled}"
    );
    let plane = ok(&[
        "octree",
        "plane",
        &p("solid.oct"),
        "--normal",
        "1,-2,3",
        "--offset",
        "20",
        "--engine",
        "rusthdl",
    ]);
    assert!(
        plane.contains("the same half-space and crossed voxels as the model"),
        "{plane}"
    );
    assert!(clip.contains(&format!("; {n_solid} voxels kept")), "{clip}");
    let half = ok(&["octree", "clip", &p("solid.oct"), "--box", "0,0,0,16,32,32"]);
    assert!(
        half.contains(&format!("; {kept} voxels kept")),
        "the x < 16 box keeps what x <= 16 by centres keeps: {half}\n{cut}"
    );
}

#[test]
fn bad_voxel_input_is_refused_naming_it() {
    let d = dir("voxels-bad");
    let p = |name: &str| d.join(name).to_str().unwrap().to_string();
    std::fs::write(p("garbage.oct"), b"TRIOCT1\n\x03").unwrap();
    std::fs::write(
        p("open.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 2 3 4\n",
    )
    .unwrap();
    ok(&[
        "voxelize",
        "@sphere",
        "--resolution",
        "8",
        "--out",
        &p("eight.oct"),
    ]);
    ok(&[
        "voxelize",
        "@sphere",
        "--resolution",
        "16",
        "--out",
        &p("sixteen.oct"),
    ]);
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![
                "voxelize".into(),
                "@torus".into(),
                "--resolution".into(),
                "100".into(),
            ],
            "--resolution",
        ),
        (
            vec![
                "voxelize".into(),
                "@torus".into(),
                "--resolution".into(),
                "2048".into(),
            ],
            "--resolution",
        ),
        (
            vec![
                "voxelize".into(),
                "@torus".into(),
                "--resolution".into(),
                "512".into(),
                "--out".into(),
                p("big.vox"),
            ],
            "256",
        ),
        (
            vec![
                "voxelize".into(),
                "@torus".into(),
                "--out".into(),
                p("model.xyz"),
            ],
            "model.xyz",
        ),
        (
            vec![
                "voxelize".into(),
                "@torus".into(),
                "--eye".into(),
                "0,0,0".into(),
            ],
            "--eye",
        ),
        (vec!["voxelize".into(), p("missing.obj")], "missing.obj"),
        (
            vec!["voxelize".into(), p("open.obj"), "--solid".into()],
            "not closed",
        ),
        (
            vec![
                "voxelize".into(),
                "@torus".into(),
                "--solid".into(),
                "--engine".into(),
                "rusthdl".into(),
            ],
            "--engine rusthdl",
        ),
        (
            vec![
                "octree".into(),
                "convert".into(),
                p("garbage.oct"),
                "--out".into(),
                p("x.binvox"),
            ],
            "garbage.oct",
        ),
        (
            vec![
                "octree".into(),
                "union".into(),
                p("eight.oct"),
                p("sixteen.oct"),
            ],
            "one grid",
        ),
        (
            vec![
                "octree".into(),
                "plane".into(),
                "--normal".into(),
                "0,0,0".into(),
                "--offset".into(),
                "1".into(),
            ],
            "--normal",
        ),
        (
            vec![
                "octree".into(),
                "clip".into(),
                p("eight.oct"),
                "--box".into(),
                "4,0,0,2,8,8".into(),
            ],
            "--box",
        ),
        (
            vec![
                "octree".into(),
                "render".into(),
                p("eight.oct"),
                "--png".into(),
                p("eight.jpg"),
            ],
            "--png",
        ),
    ];
    for (args, needle) in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = tritri(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    // Refused before the work: no half-written model left behind.
    assert!(!std::path::Path::new(&p("big.vox")).exists());
}
