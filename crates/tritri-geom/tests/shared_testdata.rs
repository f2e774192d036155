//! Checks against external cases with exact answers, in `../shared/testdata`
//! (see its README). Run by `scripts/test-shared.sh` (`test = false`: `cargo
//! test` runs it only when named). A missing directory is a failure, not a skip.
//!
//! * `peer_cases.json` (147 pairs from five libraries' unit tests and two bug
//!   reports): the exact model and the independent oracle both equal
//!   `exact_closed_f64`, in all 72 orderings;
//! * `shen_intersected.txt` / `shen_separated.txt` (5,000 + 5,000 random
//!   pairs): the exact model and the oracle equal the file a pair is in;
//! * on both, the fixed-point model at W = 8, 24, 32 equals the exact model
//!   on the same quantized coordinates (in all 72 orderings for the peer
//!   cases).
//!
//! Coordinates are read with Rust's correctly rounded `str::parse::<f64>`,
//! so they are the exact f64 values of the decimal text.

mod oracle;
mod support;

use std::path::PathBuf;
use support::{failures, Timer};
use tritri_geom::fixed_point::{self, FixedTriangle};
use tritri_geom::quantize::quantize_pair;
use tritri_geom::triangle::all_orderings;
use tritri_geom::{exact_f64, Triangle, TrianglePair};

fn testdata() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/testdata");
    assert!(
        dir.is_dir(),
        "the external test data directory {} is missing: these tests need ../shared/testdata next to the checkout",
        dir.display()
    );
    dir
}

fn read(name: &str) -> String {
    let path = testdata().join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

struct PeerCase {
    name: String,
    pair: TrianglePair,
    exact_closed_f64: bool,
}

/// The `[[x,y,z],[x,y,z],[x,y,z]]` that follows `"key":` at `text[at..]`,
/// parsed with `str::parse` (serde_json's default float parsing is not
/// guaranteed to be correctly rounded).
fn triangle_after(text: &str, key: &str, at: usize) -> (Triangle, usize) {
    let start = at
        + text[at..]
            .find(key)
            .unwrap_or_else(|| panic!("{key} not found"));
    let open = start + text[start..].find('[').unwrap();
    let mut depth = 0;
    let mut end = open;
    for (i, c) in text[open..].char_indices() {
        match c {
            '[' => depth += 1,
            ']' => {
                depth -= 1;
                if depth == 0 {
                    end = open + i;
                    break;
                }
            }
            _ => {}
        }
    }
    let numbers: Vec<f64> = text[open..end]
        .split(|c: char| c == '[' || c == ']' || c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse()
                .unwrap_or_else(|e| panic!("bad number {s:?}: {e}"))
        })
        .collect();
    assert_eq!(numbers.len(), 9, "a triangle has nine coordinates");
    let p = |i: usize| [numbers[3 * i], numbers[3 * i + 1], numbers[3 * i + 2]];
    ([p(0), p(1), p(2)], end)
}

fn peer_cases() -> Vec<PeerCase> {
    let text = read("peer_cases.json");
    let records: Vec<serde_json::Value> =
        serde_json::from_str(&text).expect("peer_cases.json is a JSON array");
    let mut at = 0;
    let cases: Vec<PeerCase> = records
        .iter()
        .map(|r| {
            // The records' coordinates in document order, read from the text.
            let (t1, after) = triangle_after(&text, "\"t1\":", at);
            let (t2, after) = triangle_after(&text, "\"t2\":", after);
            at = after;
            let from_json = |key: &str| -> Vec<f64> {
                r[key]
                    .as_array()
                    .unwrap()
                    .iter()
                    .flat_map(|p| p.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
                    .collect()
            };
            let close = |a: &[f64], t: &Triangle| {
                a.iter()
                    .zip(t.iter().flatten())
                    .all(|(x, y)| (x - y).abs() <= 1e-12 * y.abs().max(1.0))
            };
            let name = format!(
                "{} / {}",
                r["src"].as_str().unwrap_or("?"),
                r["name"].as_str().unwrap_or("?")
            );
            assert!(
                close(&from_json("t1"), &t1) && close(&from_json("t2"), &t2),
                "{name}: text and JSON coordinates differ"
            );
            PeerCase {
                name,
                pair: TrianglePair::new(t1, t2),
                exact_closed_f64: r["exact_closed_f64"].as_bool().expect("exact_closed_f64"),
            }
        })
        .collect();
    assert_eq!(cases.len(), 147, "peer_cases.json holds 147 pairs");
    cases
}

fn shen(name: &str) -> Vec<TrianglePair> {
    let pairs: Vec<TrianglePair> = read(name)
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|line| {
            let v: Vec<f64> = line
                .split_whitespace()
                .map(|s| s.parse().expect("a number"))
                .collect();
            assert_eq!(v.len(), 18, "{name}: 18 numbers per line");
            let p = |i: usize| [v[3 * i], v[3 * i + 1], v[3 * i + 2]];
            TrianglePair::new([p(0), p(1), p(2)], [p(3), p(4), p(5)])
        })
        .collect();
    assert_eq!(pairs.len(), 5000, "{name} holds 5,000 pairs");
    pairs
}

fn quantized(pair: &TrianglePair, width: u32) -> (FixedTriangle, FixedTriangle) {
    quantize_pair(pair, width).expect("finite coordinates")
}

fn as_f64(t: &FixedTriangle) -> Triangle {
    t.map(|p| p.map(|c| c as f64))
}

fn as_integers(t: &Triangle) -> FixedTriangle {
    t.map(|p| p.map(|c| c as i64))
}

/// Fixed model == exact model on the quantized pair, in all 72 orderings
/// of the quantized pair when `orderings`.
fn fixed_agrees(pair: &TrianglePair, width: u32, orderings: bool) -> bool {
    let (q1, q2) = quantized(pair, width);
    let integer_pair = TrianglePair::new(as_f64(&q1), as_f64(&q2));
    let check = |p: &TrianglePair| {
        fixed_point::intersects(&as_integers(&p.t1), &as_integers(&p.t2))
            == exact_f64::intersects(&p.t1, &p.t2)
    };
    if orderings {
        let all = all_orderings(&integer_pair).all(|p| check(&p));
        all
    } else {
        check(&integer_pair)
    }
}

/// peer_cases.json: exact model and oracle == `exact_closed_f64` in all 72
/// orderings of every pair.
#[test]
fn peer_cases_exact_model_and_oracle_match_exact_closed_f64() {
    let timer = Timer::start();
    let cases = peer_cases();
    let mut model_wrong = 0;
    let mut oracle_wrong = 0;
    for case in &cases {
        let m = all_orderings(&case.pair)
            .filter(|p| exact_f64::intersects(&p.t1, &p.t2) != case.exact_closed_f64)
            .count();
        let o = all_orderings(&case.pair)
            .filter(|p| oracle::intersects(&p.t1, &p.t2) != case.exact_closed_f64)
            .count();
        if m + o > 0 {
            eprintln!(
                "  {}: expected {}, model wrong in {m}/72, oracle wrong in {o}/72",
                case.name, case.exact_closed_f64
            );
        }
        model_wrong += m;
        oracle_wrong += o;
    }
    let intersecting = cases.iter().filter(|c| c.exact_closed_f64).count();
    eprintln!(
        "peer cases: {} pairs ({intersecting} intersecting) x 72 orderings = {} checks each; exact model {model_wrong} \
         disagreements, oracle {oracle_wrong} disagreements, {:.2} s",
        cases.len(),
        cases.len() * 72,
        timer.seconds()
    );
    assert_eq!((model_wrong, oracle_wrong), (0, 0));
}

/// peer_cases.json: fixed W = 8, 24, 32 == exact on the quantized
/// coordinates, all 72 orderings.
#[test]
fn peer_cases_fixed_point_equals_exact_on_quantized() {
    let cases = peer_cases();
    let mut total_bad = 0;
    for width in [8, 24, 32] {
        let bad = failures(&cases, |c| fixed_agrees(&c.pair, width, true));
        let changed = cases
            .iter()
            .filter(|c| {
                let (q1, q2) = quantized(&c.pair, width);
                fixed_point::intersects(&q1, &q2) != c.exact_closed_f64
            })
            .count();
        eprintln!(
            "peer cases, fixed W={width} vs exact on quantized coordinates: {} pairs x 72 orderings, {} pairs with a \
             disagreement (quantization changed the verdict of {changed})",
            cases.len(),
            bad.len()
        );
        for &i in &bad {
            eprintln!("  W={width}: {}", cases[i].name);
        }
        total_bad += bad.len();
    }
    assert_eq!(total_bad, 0);
}

/// Shen et al.'s 10,000 pairs: exact model and oracle == the file the pair
/// is in.
#[test]
fn shen_pairs_exact_model_and_oracle_match_file_membership() {
    let timer = Timer::start();
    let mut total_bad = 0;
    for (file, expected) in [
        ("shen_intersected.txt", true),
        ("shen_separated.txt", false),
    ] {
        let pairs = shen(file);
        let model_bad = failures(&pairs, |p| exact_f64::intersects(&p.t1, &p.t2) == expected);
        let oracle_bad = failures(&pairs, |p| oracle::intersects(&p.t1, &p.t2) == expected);
        eprintln!(
            "{file}: {} pairs, exact model {} disagreements, oracle {} disagreements",
            pairs.len(),
            model_bad.len(),
            oracle_bad.len()
        );
        for &i in model_bad.iter().chain(&oracle_bad).take(10) {
            eprintln!("  line {}: {:?}", i + 1, pairs[i]);
        }
        total_bad += model_bad.len() + oracle_bad.len();
    }
    eprintln!("shen pairs checked in {:.2} s", timer.seconds());
    assert_eq!(total_bad, 0);
}

/// Shen et al.'s 10,000 pairs: fixed W = 8, 24, 32 == exact on the quantized
/// coordinates (each pair in its own frame).
#[test]
fn shen_pairs_fixed_point_equals_exact_on_quantized() {
    let mut pairs = shen("shen_intersected.txt");
    let separated = shen("shen_separated.txt");
    let expected: Vec<bool> = (0..pairs.len())
        .map(|_| true)
        .chain(separated.iter().map(|_| false))
        .collect();
    pairs.extend(separated);
    let mut total_bad = 0;
    for width in [8, 24, 32] {
        let bad = failures(&pairs, |p| fixed_agrees(p, width, false));
        let changed = (0..pairs.len())
            .filter(|&i| {
                let (q1, q2) = quantized(&pairs[i], width);
                fixed_point::intersects(&q1, &q2) != expected[i]
            })
            .count();
        eprintln!(
            "shen pairs, fixed W={width} vs exact on quantized coordinates: {} pairs, {} disagreements (quantization \
             changed the verdict of {changed})",
            pairs.len(),
            bad.len()
        );
        total_bad += bad.len();
    }
    assert_eq!(total_bad, 0);
}

/// The teapot (`teapot.bpt`, tessellated at 6 × 6 per patch) against a
/// posed copy and against itself goes through the whole scene flow (common
/// BV, filters, one frame, tiles of 64): the fixed-point model equals the
/// exact model on the quantized coordinates; every pair that intersects in
/// f64 survives the f64 filter; tiled equals untiled; against an identical
/// copy every triangle meets its twin (identical coordinates quantize
/// identically, so the W = 8 grid keeps them too). The octree broad phase
/// finds the same pairs in every case, the identical copy (every triangle
/// coplanar with its twin, collapsed patch corners) included.
#[test]
fn teapot_scene_flows_through_filters_and_tiles() {
    use tritri_geom::scene::load::{load_object, Pose};
    use tritri_geom::scene::octree::BatchCost;
    use tritri_geom::scene::reference::{
        exact_f64_pairs, fixed_point_pairs, quantized_exact_pairs,
    };
    use tritri_geom::scene::{prepare, prepare_octree, SceneOptions};
    /// The system's overlapped batch cost at P = 2 (the hardware crate's
    /// cycle model, restated for this crate's tests).
    struct Cycles;
    impl BatchCost for Cycles {
        fn batch_cycles(&self, a: usize, b: usize) -> u64 {
            ((a + b + 1) as u64).max((1 + a + a.div_ceil(2) * b) as u64)
        }
    }
    let path = testdata().join("teapot.bpt");
    let teapot = load_object(path.to_str().unwrap(), 6).unwrap();
    assert_eq!(
        teapot.triangles.len(),
        2272,
        "32 patches x 72 triangles, less those with coincident vertices"
    );
    let posed = teapot.posed(&Pose {
        translation: [0.5, 0.3, 1.0],
        rotation_degrees: [0.0, 0.0, 40.0],
    });
    let truth = exact_f64_pairs(&teapot.triangles, &posed.triangles).pairs;
    for width in [8, 16, 24] {
        let tiled = prepare(
            &teapot,
            &posed,
            &SceneOptions {
                grid_bits: width,
                depth: 64,
                split: true,
            },
        )
        .unwrap();
        let untiled = prepare(
            &teapot,
            &posed,
            &SceneOptions {
                grid_bits: width,
                depth: 1 << 15,
                split: true,
            },
        )
        .unwrap();
        let found = fixed_point_pairs(&tiled.batches(), &|_| {});
        assert_eq!(
            found,
            quantized_exact_pairs(&tiled.batches()),
            "W = {width}"
        );
        assert_eq!(
            found,
            fixed_point_pairs(&untiled.batches(), &|_| {}),
            "W = {width}"
        );
        let octree = prepare_octree(
            &teapot,
            &posed,
            &SceneOptions {
                grid_bits: width,
                depth: 64,
                split: true,
            },
            &Cycles,
            None,
        )
        .unwrap();
        assert_eq!(
            fixed_point_pairs(&octree.batches(), &|_| {}),
            found,
            "octree, W = {width}"
        );
        for (i, j) in &truth {
            assert!(
                tiled.candidates_a.binary_search(i).is_ok()
                    && tiled.candidates_b.binary_search(j).is_ok()
            );
        }
        eprintln!(
            "teapot W = {width}: {} pairs tested of {}, {} hits, {} exact f64",
            tiled.pairs_tested(),
            tiled.all_pairs(),
            found.len(),
            truth.len()
        );
    }
    let itself = prepare(
        &teapot,
        &teapot,
        &SceneOptions {
            grid_bits: 8,
            depth: 256,
            split: true,
        },
    )
    .unwrap();
    let found = fixed_point_pairs(&itself.batches(), &|_| {});
    assert!((0..teapot.triangles.len() as u32).all(|i| found.contains(&(i, i))));
    let octree = prepare_octree(
        &teapot,
        &teapot,
        &SceneOptions {
            grid_bits: 8,
            depth: 256,
            split: true,
        },
        &Cycles,
        None,
    )
    .unwrap();
    assert_eq!(
        fixed_point_pairs(&octree.batches(), &|_| {}),
        found,
        "octree, teapot against itself"
    );
}

/// Fidelity of `published_float` (our translation of Guigue and
/// Devillers' C code) to the C code: on each of the 147 peer cases, the
/// translation is wrong in exactly as many of the 36 orderings as the
/// original double-precision C code (`guigue_c_double_wrong_of_36`:
/// 3 rotations of T1 × 3 of T2 × both orientations reversed or not ×
/// triangles swapped or not).
#[test]
fn wrong_as_often_as_the_c_code_on_peer_cases() {
    use tritri_geom::published_float::intersects_f64;
    use tritri_geom::triangle::{permute, VERTEX_PERMUTATIONS};
    let text = read("peer_cases.json");
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    let records = tritri_geom::pairs_io::parse_pairs("peer_cases.json", &text).unwrap();
    let mut mismatches = Vec::new();
    for (record, case) in records.iter().zip(doc.as_array().unwrap()) {
        let pair = record.pair.clone().unwrap();
        let want = case["exact_closed_f64"].as_bool().unwrap();
        let c_wrong = case["guigue_c_double_wrong_of_36"].as_u64().unwrap();
        let mut wrong = 0;
        for &r1 in &VERTEX_PERMUTATIONS[..3] {
            for &r2 in &VERTEX_PERMUTATIONS[..3] {
                for reverse in [false, true] {
                    for swap in [false, true] {
                        let (mut a, mut b) = (permute(pair.t1, r1), permute(pair.t2, r2));
                        if reverse {
                            (a, b) = (permute(a, [0, 2, 1]), permute(b, [0, 2, 1]));
                        }
                        if swap {
                            (a, b) = (b, a);
                        }
                        wrong += u64::from(intersects_f64(&a, &b) != want);
                    }
                }
            }
        }
        if wrong != c_wrong {
            mismatches.push(format!("{}: {wrong} wrong, C code {c_wrong}", case["name"]));
        }
    }
    assert_eq!(records.len(), 147);
    assert!(mismatches.is_empty(), "{mismatches:#?}");
}

/// The cone of normals is a guarantee on the teapot: at 32, 64, 128, 256
/// and 512 patches, no normal sampled on a 17 × 17 grid of a patch lies
/// outside its cone; and from eight eyes around and inside the teapot's
/// box, no patch the conservative test culls has a sampled point facing the
/// eye. The paper's test as stated (equation 3.1) is counted beside it.
#[test]
fn teapot_normal_cones_hold_every_sampled_normal() {
    use tritri_geom::bezier::cone::{back_facing, paper_back_facing, NormalCone};
    use tritri_geom::bezier::subdivide::subdivide;
    use tritri_geom::bezier::{oriented_outwards, read_bpt};
    let (patches, turned) = oriented_outwards(&read_bpt(&testdata().join("teapot.bpt")).unwrap());
    assert!(turned, "the teapot's d_u x d_v points inwards");
    let eyes = [
        [10.0, 0.0, 1.5],
        [-10.0, 3.0, 1.5],
        [0.0, -8.0, 6.0],
        [0.0, 0.0, -6.0],
        [0.0, 0.0, 1.0],
        [2.0, 2.0, 8.0],
        [4.0, -4.0, 0.5],
        [-1.0, 0.5, 2.0],
    ]
    .map(nalgebra::Point3::from);
    let m = 16;
    for times in 0..=4 {
        let level = subdivide(&patches, times);
        let (mut culled, mut paper_culled, mut paper_wrong) = (0, 0, 0);
        // The paper's test read with inward normals (the cone turned round).
        let (mut inward_culled, mut inward_wrong) = (0, 0);
        for (index, p) in level.iter().enumerate() {
            let Some(cone) = NormalCone::of(p) else {
                continue;
            };
            let samples: Vec<(nalgebra::Point3<f64>, nalgebra::Vector3<f64>)> = (0..=m)
                .flat_map(|i| (0..=m).map(move |j| (i as f64 / m as f64, j as f64 / m as f64)))
                .filter_map(|(u, v)| p.normal(u, v).map(|n| (p.evaluate(u, v), n)))
                .collect();
            for (_, n) in &samples {
                assert!(
                    cone.contains(*n, 1e-9),
                    "{} patches, patch {index}: a normal outside the cone",
                    level.len()
                );
            }
            for eye in eyes {
                let faces_eye = samples.iter().any(|(q, n)| n.dot(&(q - eye)) < 0.0);
                if back_facing(&cone, p, eye) {
                    culled += 1;
                    assert!(!faces_eye, "{} patches, patch {index}: culled from {eye:?} with a point facing the eye", level.len());
                }
                if paper_back_facing(&cone, p, eye) {
                    paper_culled += 1;
                    paper_wrong += faces_eye as usize;
                }
                // Facing the eye with the normals turned round too.
                let faces_eye_inward = samples.iter().any(|(q, n)| n.dot(&(q - eye)) > 0.0);
                let inward = NormalCone {
                    axis: -cone.axis,
                    ..cone
                };
                if paper_back_facing(&inward, p, eye) {
                    inward_culled += 1;
                    inward_wrong += faces_eye_inward as usize;
                }
            }
        }
        println!(
            "teapot at {} patches, 8 eyes: the conservative test culls {culled} patch views; the paper's test as stated culls {paper_culled}, {paper_wrong} of them with a point facing the eye; read with inward normals (both the cone and facing turned round) {inward_culled}, {inward_wrong} of them with a point facing the eye",
            level.len()
        );
        assert!(culled > 0, "the conservative test should cull something");
    }
}

/// Tessellation driven by a query (`bezier::query`): against a sphere
/// pressed into the teapot at several places, every patch the query leaves
/// out, tessellated in full at the same tolerance, meets none of the
/// sphere's triangles (exact predicates), so nothing left out could have
/// been a contact; the kept pieces give fewer triangles than the whole
/// teapot at that tolerance, and contacts are found.
#[test]
fn teapot_patches_left_out_touch_nothing() {
    use tritri_geom::bezier::lod::error_level;
    use tritri_geom::bezier::query::{
        net_box, patches_box, tessellate_for_query, MAX_SAMPLES, MAX_SPLITS,
    };
    use tritri_geom::bezier::read_bpt;
    use tritri_geom::bounding_volume::Aabb;
    use tritri_geom::scene::load::{load_object, Pose};
    use tritri_geom::scene::reference::exact_f64_pairs;

    let patches = read_bpt(&testdata().join("teapot.bpt")).unwrap();
    let tolerance = 0.01;
    // The built-in sphere, 0.6 across, centred at the origin.
    let sphere = load_object("@sphere", 8).unwrap();
    let bounds = Aabb::of_triangles(&sphere.triangles).unwrap();
    let centre_of = [0, 1, 2].map(|k| -(bounds.lo[k] + bounds.hi[k]) / 2.0);
    let sphere = sphere
        .posed(&Pose {
            translation: centre_of,
            rotation_degrees: [0.0; 3],
        })
        .scaled(0.6 / bounds.extent());
    let mut contacts = 0;
    // The body's side, the handle, the lid's knob, the spout's tip, the base.
    for (i, centre) in [
        [1.45, 0.0, 1.2],
        [-2.6, 0.0, 1.9],
        [0.0, 0.0, 3.1],
        [3.1, 0.0, 2.3],
        [0.0, 1.2, 0.1],
    ]
    .iter()
    .enumerate()
    {
        let sphere = sphere.posed(&Pose {
            translation: *centre,
            rotation_degrees: [0.0, 20.0 * i as f64, 0.0],
        });
        let region = patches_box(&patches)
            .and_then(|p| p.overlap(&Aabb::of_triangles(&sphere.triangles).unwrap()));
        let kept = tessellate_for_query(&patches, region.as_ref(), tolerance, MAX_SPLITS);
        let kept_patches: std::collections::BTreeSet<usize> =
            kept.face_of.iter().copied().collect();
        for (index, patch) in patches
            .iter()
            .enumerate()
            .filter(|(index, _)| !kept_patches.contains(index))
        {
            let whole = patch.tessellate(error_level(patch, tolerance, MAX_SAMPLES));
            let hits = exact_f64_pairs(&whole, &sphere.triangles).pairs;
            assert!(hits.is_empty(), "sphere at {centre:?}: patch {index} was left out but meets the sphere ({} pairs); its net's box {:?}", hits.len(), net_box(patch));
        }
        let found = exact_f64_pairs(&kept.triangles, &sphere.triangles)
            .pairs
            .len();
        contacts += (found > 0) as usize;
        assert!(
            kept.triangles.len() < kept.uniform_triangles,
            "sphere at {centre:?}: {} triangles kept of {}",
            kept.triangles.len(),
            kept.uniform_triangles
        );
    }
    assert!(
        contacts >= 4,
        "the spheres touch the teapot: {contacts} of 5 placements found contacts"
    );
}
