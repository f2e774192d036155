//! The file readers under mutated input: meshes (OBJ, OFF, PLY in ASCII
//! and binary), pair files (text and JSON), `.oct` and `.bpt`.
//!
//! Each case starts from a small valid file and applies a few mutations a
//! hostile or broken file has: a byte changed, a token that lies (a count
//! of 4294967295, `1e999`, `nan`, a negative index), a line duplicated, the
//! file cut short. The property is the readers' contract: an answer or an
//! error, never a panic or an abort (an allocation sized by a count the
//! file states would abort the test binary), and an error names a line
//! inside the file. The number of cases per reader is fixed, so the run
//! takes the same few seconds every time (`READER_FUZZ_CASES`).

use crate::bezier::parse_bpt;
use crate::octree::tree::{Node, Octree, OctreeFile, Placement};
use crate::pairs_io::parse_pairs;
use proptest::prelude::*;

/// Cases per reader: about half a second for all seven in a release build.
const READER_FUZZ_CASES: u32 = 20_000;

/// Tokens that lie about sizes and values, or change a file's shape.
const LIES: &[&str] = &[
    "4294967295",
    "18446744073709551615",
    "-1",
    "0",
    "1e999",
    "nan",
    "-inf",
    "3 0 1 2",
    "\n",
    "#",
    "{",
    "[",
    "]",
    "end_header",
    "element face 99999999",
    "property list uint int vertex_indices",
    "format binary_little_endian 1.0",
    "f 1 2 3",
    "v 1 2 3",
    "3 3",
    "\u{00ff}",
];

#[derive(Clone, Debug)]
enum Mutation {
    /// Overwrite the byte at this fraction of the file.
    Byte(f64, u8),
    /// Insert a lie at this fraction, with spaces around it.
    Lie(f64, usize),
    /// Cut the file at this fraction.
    Cut(f64),
    /// Repeat the line around this fraction.
    RepeatLine(f64),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (0.0..1.0f64, any::<u8>()).prop_map(|(at, b)| Mutation::Byte(at, b)),
        (0.0..1.0f64, 0..LIES.len()).prop_map(|(at, k)| Mutation::Lie(at, k)),
        (0.0..1.0f64).prop_map(Mutation::Cut),
        (0.0..1.0f64).prop_map(Mutation::RepeatLine),
    ]
}

fn apply(seed: &[u8], mutations: &[Mutation]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for m in mutations {
        let at = |f: f64, len: usize| ((f * len as f64) as usize).min(len);
        match *m {
            Mutation::Byte(f, b) => {
                if !bytes.is_empty() {
                    let i = at(f, bytes.len() - 1);
                    bytes[i] = b;
                }
            }
            Mutation::Lie(f, k) => {
                let i = at(f, bytes.len());
                let lie = format!(" {} ", LIES[k]);
                bytes.splice(i..i, lie.bytes());
            }
            Mutation::Cut(f) => bytes.truncate(at(f, bytes.len())),
            Mutation::RepeatLine(f) => {
                let i = at(f, bytes.len());
                let start = bytes[..i]
                    .iter()
                    .rposition(|&b| b == b'\n')
                    .map_or(0, |p| p + 1);
                let end = bytes[i..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map_or(bytes.len(), |p| i + p + 1);
                let line = bytes[start..end].to_vec();
                bytes.splice(end..end, line);
            }
        }
    }
    bytes
}

fn lines_of(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&b| b == b'\n').count() + 1
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: READER_FUZZ_CASES,
        // A failure is shrunk to a small file; no files are written.
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

const OBJ: &str =
    "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\nf -1 -2 -3\n";
const OFF: &str = "OFF\n# c\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n3 0 1 2 255 0 0\n";
const PLY_ASCII: &str = "ply\nformat ascii 1.0\ncomment x\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";

fn ply_binary() -> Vec<u8> {
    let header = PLY_ASCII
        .replace("format ascii", "format binary_little_endian")
        .replace("uchar int", "uint int");
    let header = &header[..header.find("end_header\n").unwrap() + "end_header\n".len()];
    let mut bytes = header.as_bytes().to_vec();
    for v in [[0f32, 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]] {
        bytes.extend(v.iter().flat_map(|c| c.to_le_bytes()));
    }
    bytes.extend(4u32.to_le_bytes());
    bytes.extend((0..4i32).flat_map(i32::to_le_bytes));
    bytes
}

const PAIRS_TEXT: &str =
    "# two pairs\n0 0 0 1 0 0 0 1 0  0 0 -1 0 0 1 1 1 0\n0 0 0 1 0 0 0 1 0  5 5 5 6 5 5 5 6 5\n";
const PAIRS_JSON: &str = "[\n {\"t1\": [[0,0,0],[1,0,0],[0,1,0]], \"t2\": [[0,0,-1],[0,0,1],[1,1,0]]},\n {\"t1\": [[0,0,0],[1,0,0],[0,1,0]], \"t2\": [[5,5,5],[6,5,5],[5,6,5]]}\n]\n";

fn bpt() -> String {
    let mut text = String::from("1\n3 3\n");
    for i in 0..4 {
        for j in 0..4 {
            text.push_str(&format!("{i} {j} {}\n", (i * j) as f64 * 0.1));
        }
    }
    text
}

fn oct() -> Vec<u8> {
    let mut nodes = vec![Node::Mixed, Node::Full];
    nodes.extend([Node::Empty; 6]);
    nodes.push(Node::Full);
    let tree = Octree::from_preorder(1, &nodes).expect("a canonical tree");
    OctreeFile {
        tree,
        placement: Placement::default(),
    }
    .to_bytes()
}

/// A mesh reader's answer: triangles with finite coordinates, one face
/// index each; or an error on a line of the file.
fn check_mesh(extension: &str, bytes: &[u8]) -> Result<(), TestCaseError> {
    match crate::mesh::parse_as(extension, bytes).expect("a mesh format") {
        Ok(mesh) => {
            prop_assert_eq!(mesh.triangles.len(), mesh.face_of.len());
            prop_assert!(mesh
                .triangles
                .iter()
                .flatten()
                .flatten()
                .all(|v| v.is_finite()));
        }
        Err(e) => {
            prop_assert!(
                e.line >= 1 && e.line <= lines_of(bytes) + 1,
                "line {} of {}: {}",
                e.line,
                lines_of(bytes),
                e.message
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn obj_reader(mutations in prop::collection::vec(mutation(), 1..6)) {
        check_mesh("obj", &apply(OBJ.as_bytes(), &mutations))?;
    }

    #[test]
    fn off_reader(mutations in prop::collection::vec(mutation(), 1..6)) {
        check_mesh("off", &apply(OFF.as_bytes(), &mutations))?;
    }

    #[test]
    fn ply_ascii_reader(mutations in prop::collection::vec(mutation(), 1..6)) {
        check_mesh("ply", &apply(PLY_ASCII.as_bytes(), &mutations))?;
    }

    #[test]
    fn ply_binary_reader(mutations in prop::collection::vec(mutation(), 1..6)) {
        check_mesh("ply", &apply(&ply_binary(), &mutations))?;
    }

    #[test]
    fn pair_readers(json in any::<bool>(), mutations in prop::collection::vec(mutation(), 1..6)) {
        let seed = if json { PAIRS_JSON } else { PAIRS_TEXT };
        let bytes = apply(seed.as_bytes(), &mutations);
        // The readers take text: a file that is not is refused before
        // (read_pairs, tested in pairs_io).
        if let Ok(text) = std::str::from_utf8(&bytes) {
            if let Ok(records) = parse_pairs("p", text) {
                for record in records {
                    prop_assert!(record.location.line >= 1 && record.location.line <= lines_of(&bytes));
                    if let Ok(pair) = record.pair {
                        prop_assert!(pair.t1.iter().chain(&pair.t2).flatten().all(|v| v.is_finite()));
                    }
                }
            }
        }
    }

    #[test]
    fn bpt_reader(mutations in prop::collection::vec(mutation(), 1..6)) {
        let bytes = apply(bpt().as_bytes(), &mutations);
        if let Ok(text) = std::str::from_utf8(&bytes) {
            match parse_bpt(text) {
                Ok(patches) => prop_assert!(patches.iter().all(|p| p.net.iter().flatten().all(|q| q.coords.iter().all(|v| v.is_finite())))),
                Err((line, _)) => prop_assert!(line >= 1 && line <= lines_of(&bytes) + 1),
            }
        }
    }

    #[test]
    fn oct_reader(mutations in prop::collection::vec(mutation(), 1..6)) {
        let bytes = apply(&oct(), &mutations);
        if let Ok(file) = OctreeFile::from_bytes(&bytes) {
            // What is read writes back to the same bytes: one canonical form.
            prop_assert_eq!(file.to_bytes(), bytes);
        }
    }
}
