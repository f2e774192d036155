//! Pairs per second of every arithmetic (criterion; `cargo bench -p tritri-geom`).
//!
//! * `shen`: the 10,000 Shen pairs (`../shared/testdata/shen_*.txt`, read
//!   from beside the project); when the files are missing, 10,000 random
//!   unit-cube pairs instead (a note says so).
//! * `coplanar`: 2,000 exactly coplanar lattice pairs
//!   (`hard_cases::coplanar_lattice_pairs`), where the exact predicates leave
//!   their fast paths.
//!
//! Each `fixed<W>` entry is the whole batch call: one frame fitted over the
//! batch, quantization, then the integer test; `fixed24-kernel` is the
//! integer test alone on pre-quantized pairs.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::path::PathBuf;
use std::time::Duration;
use tritri_geom::arithmetic::{classify, quantize_pairs, Arithmetic};
use tritri_geom::{fixed_point, hard_cases, pairs_io, TrianglePair};

fn shen_pairs() -> Vec<TrianglePair> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/testdata");
    let mut pairs = Vec::new();
    for name in ["shen_intersected.txt", "shen_separated.txt"] {
        match pairs_io::read_pairs(dir.join(name)) {
            Ok(file) => pairs.extend(file.good_pairs()),
            Err(e) => {
                eprintln!("note: {e}; benchmarking 10,000 random unit-cube pairs instead of the Shen sets");
                return hard_cases::random_pairs(10_000, 1);
            }
        }
    }
    pairs
}

fn bench_set(c: &mut Criterion, group_name: &str, pairs: &[TrianglePair]) {
    let mut group = c.benchmark_group(group_name);
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    group.throughput(Throughput::Elements(pairs.len() as u64));
    for arith in Arithmetic::all(&[16, 24, 32]).unwrap() {
        group.bench_with_input(BenchmarkId::from_parameter(arith), pairs, |b, pairs| {
            b.iter(|| classify(arith, black_box(pairs)).unwrap().verdicts)
        });
    }
    let (_, quantized) = quantize_pairs(pairs, 24).unwrap();
    group.bench_with_input(
        BenchmarkId::from_parameter("fixed24-kernel"),
        &quantized,
        |b, q| {
            b.iter(|| {
                black_box(q)
                    .iter()
                    .map(|p| fixed_point::intersects(&p[0], &p[1]))
                    .collect::<Vec<_>>()
            })
        },
    );
    group.finish();
}

fn arithmetics(c: &mut Criterion) {
    bench_set(c, "shen", &shen_pairs());
    bench_set(c, "coplanar", &hard_cases::coplanar_lattice_pairs(2_000, 1));
}

criterion_group!(benches, arithmetics);
criterion_main!(benches);
