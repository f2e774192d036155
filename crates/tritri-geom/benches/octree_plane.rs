//! The octree engine seed's table, software side: a 512^3 grid classified
//! against a plane (the voxels it crosses, and the half-space as an octree
//! whose uniform cells are leaves; `oblique_and_fill` also writes it into a
//! voxel memory), beside the seed's 13 s on a 150-MIPS workstation in 1995. `cargo bench -p tritri-geom --bench octree_plane`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use tritri_geom::octree::plane::classify_plane;

fn plane_512(c: &mut Criterion) {
    let mut group = c.benchmark_group("octree_plane_512");
    group.sample_size(10);
    // A plane oblique to every axis through the middle of the grid.
    for (name, normal, d) in [
        ("oblique", [3i64, 5, 7], 7 * 256 + 5 * 256 + 3 * 256),
        ("axis_aligned", [0, 0, 1], 256),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| black_box(classify_plane(9, black_box(normal), black_box(d))).crossed_voxels)
        });
    }
    // The half-space written into a voxel memory too (a word at a time).
    group.bench_function("oblique_and_fill", |b| {
        b.iter(|| {
            black_box(
                classify_plane(9, black_box([3, 5, 7]), black_box(3840))
                    .half_space
                    .to_voxels(),
            )
            .count()
        })
    });
    group.finish();
}

criterion_group!(benches, plane_512);
criterion_main!(benches);
