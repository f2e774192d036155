//! The external cases of `../shared/testdata` (see its README), quantized,
//! through the hardware: the rust-hdl pipeline at W = 8, 16, 24 and 32 and
//! the emitted Verilog in Verilator (W = 8, 16, 24) and Icarus (W = 24,
//! peer cases) give exactly the fixed-point model's verdicts, pair by pair.
//!
//! * `peer_cases.json` (147 pairs from other libraries' tests and bug
//!   reports), each quantized in its own frame, in all 72 orderings;
//! * `shen_intersected.txt` and `shen_separated.txt` (5,000 pairs each),
//!   each pair quantized in its own frame.
//!
//! Run by `scripts/test-shared.sh` (`test = false`: `cargo test` runs it
//! only when named); a missing directory is a failure, not a skip.

use std::path::PathBuf;
use tritri_cosim::rusthdl_harness::{run_schedule_on, HarnessOptions};
use tritri_cosim::stream::{all_orderings, group_schedule, PairGroup, PairVerdict, StreamResult};
use tritri_geom::certificate::certified_intersects;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::quantize::quantize_pair;
use tritri_geom::TrianglePair;
use tritri_rtl::pipeline::pipeline_for_width::pipeline_for_width;

fn read_pairs(name: &str) -> Vec<TrianglePair> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/testdata");
    assert!(
        dir.is_dir(),
        "the external test data directory {} is missing",
        dir.display()
    );
    let file = tritri_geom::pairs_io::read_pairs(dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(file.errors().count(), 0, "{name}: unreadable records");
    file.good_pairs()
}

fn quantized(pair: &TrianglePair, width: usize) -> (FixedTriangle, FixedTriangle) {
    quantize_pair(pair, width as u32).expect("finite coordinates")
}

fn peer_groups(width: usize) -> Vec<PairGroup> {
    let pairs = read_pairs("peer_cases.json");
    assert_eq!(pairs.len(), 147);
    pairs
        .iter()
        .flat_map(|p| {
            let (a, b) = quantized(p, width);
            all_orderings(a, b)
        })
        .collect()
}

fn shen_groups(width: usize) -> Vec<PairGroup> {
    let mut groups = Vec::new();
    for name in ["shen_intersected.txt", "shen_separated.txt"] {
        let pairs = read_pairs(name);
        assert_eq!(pairs.len(), 5000, "{name}");
        groups.extend(pairs.iter().map(|p| {
            let (a, b) = quantized(p, width);
            (a, vec![b])
        }));
    }
    groups
}

/// Verdicts, ids included, equal the model's, output by output.
fn assert_equal(
    engine: &str,
    what: &str,
    width: usize,
    result: &StreamResult,
    expected: &[PairVerdict],
) {
    assert_eq!(
        result.verdicts.len(),
        expected.len(),
        "{engine} W={width} {what}: verdict count"
    );
    let wrong: Vec<usize> = result
        .verdicts
        .iter()
        .zip(expected)
        .enumerate()
        .filter(|(_, (v, e))| v != e)
        .map(|(i, _)| i)
        .collect();
    let hits = expected.iter().filter(|v| v.hit).count();
    eprintln!(
        "{engine} W={width} {what}: {} pairs ({hits} hits), {} mismatches",
        expected.len(),
        wrong.len()
    );
    assert!(
        wrong.is_empty(),
        "{engine} W={width} {what}: mismatches at outputs {:?}",
        &wrong[..wrong.len().min(10)]
    );
}

#[test]
fn rusthdl_pipeline_equals_model_on_shared_cases() {
    for width in [8, 16, 24, 32] {
        let mut pipeline = pipeline_for_width(width).unwrap();
        for (what, groups) in [
            ("peer cases x 72", peer_groups(width)),
            ("Shen pairs", shen_groups(width)),
        ] {
            let (cycles, expected) = group_schedule(&groups, certified_intersects);
            let result =
                run_schedule_on(pipeline.as_mut(), &cycles, &HarnessOptions::default()).unwrap();
            assert_equal("rust-hdl", what, width, &result, &expected);
        }
    }
}

#[test]
fn verilator_equals_model_on_shared_cases() {
    for width in [8, 16, 24] {
        for (what, groups) in [
            ("peer cases x 72", peer_groups(width)),
            ("Shen pairs", shen_groups(width)),
        ] {
            let (cycles, expected) = group_schedule(&groups, certified_intersects);
            let result = tritri_cosim::pipeline_rtl::run_schedule(
                tritri_cosim::simulator::Simulator::Verilator,
                width,
                &cycles,
                None,
            )
            .unwrap()
            .result;
            assert_equal("verilator", what, width, &result, &expected);
        }
    }
}

#[test]
fn icarus_equals_model_on_peer_cases() {
    let width = 24;
    let (cycles, expected) = group_schedule(&peer_groups(width), certified_intersects);
    let result = tritri_cosim::pipeline_rtl::run_schedule(
        tritri_cosim::simulator::Simulator::Icarus,
        width,
        &cycles,
        None,
    )
    .unwrap()
    .result;
    assert_equal("icarus", "peer cases x 72", width, &result, &expected);
}

/// Eight eyes around the teapot, three to five of its sizes away.
fn teapot_eyes() -> Vec<nalgebra::Point3<f64>> {
    (0..8)
        .map(|i| {
            let t = i as f64 * std::f64::consts::TAU / 8.0;
            let r = 9.0 + 3.0 * (i % 3) as f64;
            nalgebra::Point3::new(r * t.cos(), r * t.sin(), 2.0 + 4.0 * ((i % 4) as f64 - 1.5))
        })
        .collect()
}

/// The cone-of-normals unit on the teapot at 32 to 512 patches from eight
/// eyes, through the emitted Verilog in Verilator: the fixed-point model's
/// classes. Against the f64 guarantee (`bezier::cone::back_facing`), the
/// number of answers that differ is printed, and no patch the unit culls
/// has a sampled point facing the eye.
#[test]
fn cone_unit_equals_model_on_the_teapot() {
    use tritri_cosim::cone_unit::{expected, inputs_for, run_emitted, run_rusthdl};
    use tritri_geom::bezier::cone::{back_facing, NormalCone};
    use tritri_geom::bezier::cone_fixed::Facing;
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/testdata");
    let base = tritri_geom::bezier::oriented_outwards(
        &tritri_geom::bezier::read_bpt(&dir.join("teapot.bpt")).unwrap(),
    )
    .0;
    let eyes = teapot_eyes();
    for times in 0..=4u32 {
        let patches = tritri_geom::bezier::subdivide::subdivide(&base, times);
        let inputs = inputs_for(&patches, &eyes, 24).unwrap();
        let want = expected(&inputs);
        assert_eq!(
            run_rusthdl(24, &inputs).unwrap(),
            want,
            "rust-hdl, {} patches",
            patches.len()
        );
        assert_eq!(
            run_emitted(24, &inputs, tritri_cosim::simulator::Simulator::Verilator).unwrap(),
            want,
            "Verilator, {} patches",
            patches.len()
        );
        let (mut culled, mut differ) = (0, 0);
        for (n, facing) in want.iter().enumerate() {
            let (patch, eye) = (&patches[n / eyes.len()], eyes[n % eyes.len()]);
            let f64_back = NormalCone::of(patch).is_some_and(|c| back_facing(&c, patch, eye));
            differ += usize::from(f64_back != (*facing == Facing::Back));
            if *facing != Facing::Back {
                continue;
            }
            culled += 1;
            for i in 0..=8 {
                for j in 0..=8 {
                    let s = patch.evaluate_with_derivatives(i as f64 / 8.0, j as f64 / 8.0);
                    let normal = s.du.cross(&s.dv);
                    let view = s.point - eye;
                    assert!(
                        normal.dot(&view) >= -1e-9 * normal.norm() * view.norm(),
                        "patch {} culled from eye {} faces it at ({i}, {j})",
                        n / eyes.len(),
                        n % eyes.len()
                    );
                }
            }
        }
        eprintln!("teapot, {} patches x {} eyes: {culled} culled by the unit, {differ} answers differ from the f64 guarantee", patches.len(), eyes.len());
        assert!(culled > 0);
    }
}

/// The patch tessellation unit on the teapot at 32 to 512 patches (a
/// 24-bit grid fit to the teapot, 8 steps a side): rust-hdl and the
/// emitted Verilog in Verilator give the fixed-point model's vertices, in
/// the timing formula's clocks.
#[test]
fn patch_tessellator_equals_model_on_the_teapot() {
    use tritri_cosim::patch_tessellator::{run_emitted, run_rusthdl};
    use tritri_geom::bezier::fixed::{fixed_grid, PatchFrame};
    use tritri_rtl::bezier::patch_tessellator::tessellation_clocks;
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/testdata");
    let base = tritri_geom::bezier::read_bpt(&dir.join("teapot.bpt")).unwrap();
    let (w, k) = (24usize, 3usize);
    for times in 0..=4u32 {
        let patches = tritri_geom::bezier::subdivide::subdivide(&base, times);
        let frame = PatchFrame::fit(&patches, w as u32);
        let nets: Vec<_> = patches.iter().map(|p| frame.quantize(p)).collect();
        let runs = [
            ("rust-hdl", run_rusthdl(w, k, &nets, &|_| true)),
            (
                "Verilator",
                run_emitted(w, k, &nets, tritri_cosim::simulator::Simulator::Verilator).unwrap(),
            ),
        ];
        for (name, runs) in runs {
            assert_eq!(runs.len(), nets.len(), "{name}");
            for (run, net) in runs.iter().zip(&nets) {
                let vertices: Vec<[i64; 3]> = run.vertices.iter().map(|v| v.2).collect();
                assert_eq!(
                    vertices,
                    fixed_grid(net, k as u32),
                    "{name}, {} patches",
                    patches.len()
                );
                assert_eq!(run.clocks, tessellation_clocks(k as u32), "{name}: clocks");
            }
        }
        eprintln!("teapot, {} patches: the tessellator's {} vertices equal the model's in rust-hdl and Verilator", patches.len(), nets.len() * 81);
    }
}
