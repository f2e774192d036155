//! Each reader on small files, good and bad: the triangles come out in file
//! order with their face indices, and every error names the line.

use super::*;

fn parse(name: &str, text: &[u8]) -> Result<Mesh, String> {
    let path = std::env::temp_dir().join(format!("tritri-mesh-test-{}-{name}", std::process::id()));
    std::fs::write(&path, text).unwrap();
    let result =
        Mesh::read(&path).map_err(|e| e.to_string().replace(&path.display().to_string(), "FILE"));
    std::fs::remove_file(&path).ok();
    result
}

const QUAD: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];

fn check_quad(mesh: &Mesh) {
    assert_eq!(
        mesh.triangles,
        vec![[QUAD[0], QUAD[1], QUAD[2]], [QUAD[0], QUAD[2], QUAD[3]]]
    );
    assert_eq!(mesh.face_of, vec![0, 0]);
}

#[test]
fn obj_quad_with_slashes_and_negative_indices_is_two_triangles() {
    let m = parse(
        "a.obj",
        b"# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 -2//1 -1//1\n",
    )
    .unwrap();
    check_quad(&m);
}

#[test]
fn obj_errors_name_the_line() {
    assert_eq!(
        parse("b.obj", b"v 0 0 0\nv 1 0 nan\n").unwrap_err(),
        "FILE:2: coordinate `nan` is not finite"
    );
    assert_eq!(
        parse("c.obj", b"v 0 0 0\nv 1 0\n").unwrap_err(),
        "FILE:2: vertex has 2 numbers, expected 3 (or 4 with w)"
    );
    assert_eq!(
        parse("d.obj", b"v 0 0 0\nf 1 2 3\n").unwrap_err(),
        "FILE:2: vertex index 2 out of range (the file has 1 vertices, numbered from 1)"
    );
    assert_eq!(
        parse("e.obj", b"v 0 0 0\nv x 0 0\n").unwrap_err(),
        "FILE:2: `x` is not a number"
    );
    assert_eq!(
        parse("f.obj", b"v 0 0 0\n\nf 1 1\n").unwrap_err(),
        "FILE:3: face has 2 vertices, at least 3 needed"
    );
}

#[test]
fn off_quad_is_two_triangles() {
    let m = parse(
        "a.off",
        b"OFF\n# c\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
    )
    .unwrap();
    check_quad(&m);
}

#[test]
fn off_errors_name_the_line() {
    assert_eq!(
        parse("b.off", b"OFF\n3 1 0\n0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n").unwrap_err(),
        "FILE:4: coordinate `inf` is not finite"
    );
    assert_eq!(
        parse("c.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n").unwrap_err(),
        "FILE:6: vertex index 7 out of range (the file has 3 vertices, numbered from 0)"
    );
    assert_eq!(
        parse("d.off", b"COFF\n").unwrap_err(),
        "FILE:1: expected `OFF`, found `COFF`"
    );
    assert_eq!(
        parse("e.off", b"OFF\n3 1 0\n0 0 0\n").unwrap_err(),
        "FILE:2: file ends after 1 of 3 vertices"
    );
}

#[test]
fn off_takes_a_face_colour_and_nothing_else_beyond_its_faces() {
    let tri = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
    for colour in ["", " 7", " 0.5 0.5 0.5", " 255 0 0 255"] {
        let text = [&tri[..], format!("3 0 1 2{colour}\n").as_bytes()].concat();
        assert_eq!(
            parse("f.off", &text).unwrap().triangles.len(),
            1,
            "{colour}"
        );
    }
    let junk = [&tri[..], b"3 0 1 2 junk\n"].concat();
    assert_eq!(
        parse("g.off", &junk).unwrap_err(),
        "FILE:6: `junk` after the face's 3 vertex indices is not a colour (1, 3 or 4 numbers)"
    );
    // A bad index is the error, not the fields after it.
    let bad_index = [&tri[..], b"3 0 1.5 2 junk\n"].concat();
    assert_eq!(
        parse("j.off", &bad_index).unwrap_err(),
        "FILE:6: face vertex index is not a non-negative integer"
    );
    let two = [&tri[..], b"3 0 1 2 1 1\n"].concat();
    assert!(parse("h.off", &two)
        .unwrap_err()
        .starts_with("FILE:6: `1 1` after"));
    let extra = [&tri[..], b"3 0 1 2\n3 2 1 0\n"].concat();
    assert_eq!(
        parse("i.off", &extra).unwrap_err(),
        "FILE:7: more lines after the 1 faces the counts declare"
    );
}

const PLY_HEADER: &str = "ply\nformat {} 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

#[test]
fn ply_ascii_and_binary_quads_are_two_triangles() {
    let ascii = PLY_HEADER.replace("{}", "ascii") + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    check_quad(&parse("a.ply", ascii.as_bytes()).unwrap());
    for (format, big) in [("binary_little_endian", false), ("binary_big_endian", true)] {
        let mut bytes = PLY_HEADER.replace("{}", format).into_bytes();
        for p in QUAD {
            for v in p {
                let v = v as f32;
                bytes.extend(if big {
                    v.to_be_bytes()
                } else {
                    v.to_le_bytes()
                });
            }
        }
        bytes.push(4);
        for i in 0..4i32 {
            bytes.extend(if big {
                i.to_be_bytes()
            } else {
                i.to_le_bytes()
            });
        }
        check_quad(&parse("b.ply", &bytes).unwrap());
    }
}

#[test]
fn ply_errors_name_the_line_or_element() {
    let ascii = PLY_HEADER.replace("{}", "ascii") + "0 0 0\n1 0 0\n1 z 0\n0 1 0\n4 0 1 2 3\n";
    assert_eq!(
        parse("c.ply", ascii.as_bytes()).unwrap_err(),
        "FILE:12: vertex 2: `z` is not a number"
    );
    let mut truncated = PLY_HEADER
        .replace("{}", "binary_little_endian")
        .into_bytes();
    truncated.extend([0u8; 10]);
    assert_eq!(
        parse("d.ply", &truncated).unwrap_err(),
        "FILE:9: vertex 0: binary body ends at byte 10 of the body"
    );
    assert_eq!(
        parse("e.ply", b"plx\n").unwrap_err(),
        "FILE:1: not a PLY file: the first line must be `ply`"
    );
}

#[test]
fn unknown_extension_is_refused() {
    assert!(parse("a.stl", b"solid")
        .unwrap_err()
        .contains("unknown mesh format"));
}

#[test]
fn a_ply_list_longer_than_the_file_is_an_error_not_an_abort() {
    // 4294967295 items would be a 34 GB allocation.
    let ascii = PLY_HEADER
        .replace("{}", "ascii")
        .replace("uchar int", "uint int")
        + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4294967295 0 1 2\n";
    let e = parse("huge.ply", ascii.as_bytes()).unwrap_err().to_string();
    assert!(
        e.contains("claims 4294967295 items") && e.contains("at most 3"),
        "{e}"
    );
    let mut bytes = PLY_HEADER
        .replace("{}", "binary_little_endian")
        .replace("uchar int", "uint int")
        .into_bytes();
    for v in [[0f32, 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]] {
        for c in v {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
    }
    bytes.extend_from_slice(&u32::MAX.to_le_bytes());
    for i in [0i32, 1, 2] {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    let e = parse("huge.ply", &bytes).unwrap_err().to_string();
    assert!(
        e.contains("claims 4294967295 items") && e.contains("at most 3"),
        "{e}"
    );
}

#[test]
fn a_ply_that_holds_more_than_its_header_declares_is_refused() {
    let quad = PLY_HEADER.replace("{}", "ascii") + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    let extra_face = quad.clone() + "3 0 1 2\n";
    assert_eq!(
        parse("f.ply", extra_face.as_bytes()).unwrap_err(),
        "FILE:15: more data after the elements the header declares"
    );
    let extra_value = quad.replace("4 0 1 2 3\n", "4 0 1 2 3 9\n");
    assert_eq!(
        parse("g.ply", extra_value.as_bytes()).unwrap_err(),
        "FILE:14: 1 extra values on the line"
    );
    let mut bytes = PLY_HEADER
        .replace("{}", "binary_little_endian")
        .into_bytes();
    bytes.extend(
        QUAD.iter()
            .flatten()
            .flat_map(|&v| (v as f32).to_le_bytes()),
    );
    bytes.push(4);
    bytes.extend((0..4i32).flat_map(i32::to_le_bytes));
    bytes.extend([0u8; 5]);
    assert_eq!(
        parse("h.ply", &bytes).unwrap_err(),
        "FILE:9: 5 bytes after the elements the header declares"
    );
}
