//! The Bezier LOD paper's timing table (`bezier_lod_gpu.txt`), this
//! machine's side: the Utah teapot cut by De Casteljau into 32 to 512
//! patches, seen from `tritri bezier render`'s default eye. `adaptive` is
//! the paper's display work per frame on the CPU: each patch's cone of
//! normals, the back-facing cull, the silhouette test, the distance level,
//! and the tessellation at that level; `uniform_20` tessellates every
//! patch at 20 x 20, the baseline the ratio in `docs/bezier-lod.md` is
//! taken against, in the same run.
//!
//! `cargo bench -p tritri-geom --bench bezier_lod` (reads
//! `../shared/testdata/teapot.bpt` beside the checkout).

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use std::path::PathBuf;
use tritri_geom::bezier::subdivide::subdivide;
use tritri_geom::bezier::view::plan;
use tritri_geom::bezier::{oriented_outwards, read_bpt, BezierPatch};

/// `tritri bezier render`'s defaults.
const EYE: [f64; 3] = [7.0, -10.0, 6.0];
const NEAR: f64 = 4.0;

fn teapot() -> Vec<BezierPatch> {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/testdata/teapot.bpt");
    let patches = read_bpt(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e} (the bench reads the shared test data)",
            path.display()
        )
    });
    oriented_outwards(&patches).0
}

/// Culling, levels and tessellation: the triangles drawn.
fn adaptive(patches: &[BezierPatch]) -> usize {
    plan(patches, EYE.into(), NEAR)
        .iter()
        .zip(patches)
        .filter(|(view, _)| !view.culled)
        .map(|(view, patch)| patch.tessellate(view.samples).len())
        .sum()
}

/// Every patch at 20 x 20.
fn uniform(patches: &[BezierPatch]) -> usize {
    patches.iter().map(|patch| patch.tessellate(20).len()).sum()
}

fn teapot_lod(c: &mut Criterion) {
    let base = teapot();
    let mut group = c.benchmark_group("teapot_lod");
    group.sample_size(20);
    for times in 0..=4 {
        let patches = subdivide(&base, times);
        let n = patches.len();
        eprintln!(
            "{n} patches: adaptive draws {} triangles, uniform 20 x 20 {}",
            adaptive(&patches),
            uniform(&patches)
        );
        group.bench_with_input(BenchmarkId::new("adaptive", n), &patches, |b, p| {
            b.iter(|| adaptive(black_box(p)))
        });
        group.bench_with_input(BenchmarkId::new("uniform_20", n), &patches, |b, p| {
            b.iter(|| uniform(black_box(p)))
        });
    }
    group.finish();
}

criterion_group!(benches, teapot_lod);
criterion_main!(benches);
