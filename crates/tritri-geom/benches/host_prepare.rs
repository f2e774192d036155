//! The host's share of the accelerator's route, against memory speed
//! (issue 66): what the host does before the hardware is to find the
//! common box, cull to it and quantize what is left (`scene::prepare`, the
//! whole of it for the DRAM top, which bins on chip). Beside it, in the
//! same run: the two objects' bounding boxes, one pass over every
//! coordinate (the memory-speed floor),
//! and the exact software path on the same scene (the baseline every
//! speed line is measured against). A torus of 100k triangles and a
//! sphere of 20k in contact; then two tori of 100k, one moved a little,
//! where nearly every triangle is in the common box (as on bunny x bunny),
//! so that quantizing, not culling, is most of the work.
//! `cargo bench -p tritri-geom --bench host_prepare`.

use criterion::measurement::WallTime;
use criterion::{black_box, criterion_group, criterion_main, BenchmarkGroup, Criterion};
use tritri_geom::bounding_volume::Aabb;
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::reference::exact_f64_pairs;
use tritri_geom::scene::{prepare, SceneOptions};

const OPTIONS: SceneOptions = SceneOptions {
    grid_bits: 16,
    depth: 256,
    split: true,
};

fn host_prepare(c: &mut Criterion) {
    let torus_100k = |centre| torus(centre, 1.0, 0.35, 500, 100);
    let a = SceneObject::from_triangles("torus", torus_100k([0.0, 0.0, 0.0]));
    let b = SceneObject::from_triangles("sphere", sphere([1.0, 0.0, 0.55], 0.4, 200, 50));
    let mut group = c.benchmark_group("host_prepare_100k");
    group.sample_size(20);
    boxes_and_prepare(&mut group, &a, &b);
    group.bench_function("exact_software_path", |bench| {
        bench.iter(|| {
            black_box(exact_f64_pairs(
                black_box(&a.triangles),
                black_box(&b.triangles),
            ))
            .pairs
            .len()
        })
    });
    group.finish();

    let b = SceneObject::from_triangles("torus", torus_100k([0.02, 0.01, 0.0]));
    let kept = prepare(&a, &b, &OPTIONS).unwrap();
    assert!(
        kept.kept_a.len() + kept.kept_b.len() > 190_000,
        "nearly all kept"
    );
    let mut group = c.benchmark_group("host_prepare_2x100k_all_kept");
    group.sample_size(20);
    boxes_and_prepare(&mut group, &a, &b);
    group.finish();
}

/// The floor (one pass over every coordinate, the two objects' boxes) and
/// the host's preparation of `a` and `b`.
fn boxes_and_prepare(group: &mut BenchmarkGroup<'_, WallTime>, a: &SceneObject, b: &SceneObject) {
    group.bench_function("bounding_boxes", |bench| {
        bench.iter(|| {
            (
                black_box(Aabb::of_triangles(black_box(&a.triangles))),
                black_box(Aabb::of_triangles(black_box(&b.triangles))),
            )
        })
    });
    group.bench_function("prepare", |bench| {
        bench.iter(|| {
            black_box(prepare(black_box(a), black_box(b), &OPTIONS).unwrap())
                .kept_a
                .len()
        })
    });
}

criterion_group!(benches, host_prepare);
criterion_main!(benches);
