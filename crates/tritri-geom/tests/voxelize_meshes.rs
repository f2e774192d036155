//! Voxelization of real meshes against the brute-force oracles of
//! `oracle/voxels.rs`: CGAL's bunny, armadillo, camel and elephant
//! (`bash scripts/fetch-meshes.sh` puts them in build/meshes) solid and
//! surface, and the Utah teapot (../shared/testdata/teapot.bpt, open, so
//! surface only; its lid and bottom patches collapse to a point, so
//! tessellation gives zero-area triangles there), at several resolutions.
//! 0 voxels missing or extra. Run by `scripts/test-shared.sh`.

mod oracle;
mod support;

use std::path::PathBuf;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::voxelize::{self, VoxelFrame, SUB_BITS};
use tritri_geom::scene::load::load_object;

const S: i64 = 1 << SUB_BITS;

fn workspace() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn quantized(spec: &PathBuf, level: u32) -> (Vec<FixedTriangle>, VoxelFrame) {
    assert!(spec.exists(), "{} is missing: run bash scripts/fetch-meshes.sh (CGAL meshes) or check ../shared/testdata (teapot)", spec.display());
    let object = load_object(spec.to_str().unwrap(), 8).unwrap();
    let frame = VoxelFrame::fit(&object.triangles, level).unwrap();
    (
        object.triangles.iter().map(|t| frame.quantize(t)).collect(),
        frame,
    )
}

/// Compares the model's surface with the oracle's, split over the cores.
fn check_surface(mesh: &[FixedTriangle], level: u32, name: &str) -> usize {
    let model = oracle::voxels::voxels_of(&voxelize::surface(mesh, level, &mut |_| {}));
    let n = 1i64 << level;
    let chunks: Vec<&[FixedTriangle]> = mesh.chunks(mesh.len().div_ceil(8).max(1)).collect();
    let parts = std::sync::Mutex::new(Vec::new());
    support::failures(&chunks, |chunk| {
        let found = oracle::voxels::surface(chunk, n, S);
        parts.lock().unwrap().extend(found);
        true
    });
    let mut expected = parts.into_inner().unwrap();
    expected.sort_unstable();
    expected.dedup();
    let missing = expected
        .iter()
        .filter(|v| model.binary_search(v).is_err())
        .count();
    let extra = model
        .iter()
        .filter(|v| expected.binary_search(v).is_err())
        .count();
    println!(
        "{name} at {n}^3: surface {} voxels, {missing} missing, {extra} extra",
        model.len()
    );
    assert_eq!((missing, extra), (0, 0), "{name} surface at {n}^3");
    model.len()
}

fn check_solid(mesh: &[FixedTriangle], frame: &VoxelFrame, name: &str) -> usize {
    let model = oracle::voxels::voxels_of(&voxelize::solid(mesh, frame, &mut |_| {}).unwrap());
    let n = 1i64 << frame.level;
    let expected = oracle::voxels::solid_by_columns(mesh, n, S);
    let missing = expected
        .iter()
        .filter(|v| model.binary_search(v).is_err())
        .count();
    let extra = model
        .iter()
        .filter(|v| expected.binary_search(v).is_err())
        .count();
    println!(
        "{name} at {n}^3: solid {} voxels, {missing} missing, {extra} extra",
        model.len()
    );
    assert_eq!((missing, extra), (0, 0), "{name} solid at {n}^3");
    model.len()
}

#[test]
fn cgal_meshes_surface_and_solid_equal_the_oracle() {
    for name in ["elephant", "camel", "armadillo", "bunny"] {
        let path = workspace().join("build/meshes").join(format!("{name}.off"));
        for level in [4, 5, 6] {
            let (mesh, frame) = quantized(&path, level);
            let solid = check_solid(&mesh, &frame, name);
            let surface = check_surface(&mesh, level, name);
            assert!(solid > 0 && surface > 0);
        }
    }
}

#[test]
fn teapot_surface_equals_the_oracle() {
    let path = workspace().join("../shared/testdata/teapot.bpt");
    for level in [4, 5, 6] {
        let (mesh, _) = quantized(&path, level);
        let zero_area = mesh.iter().filter(|t| {
            let d = |a: [i64; 3], b: [i64; 3]| [0, 1, 2].map(|k| (b[k] - a[k]) as i128);
            let (u, v) = (d(t[0], t[1]), d(t[0], t[2]));
            [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ] == [0; 3]
        });
        assert!(
            zero_area.count() > 0,
            "the collapsed patch corners give zero-area triangles"
        );
        check_surface(&mesh, level, "teapot");
    }
}
