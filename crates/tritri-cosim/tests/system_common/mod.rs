//! Scenes for the system tests: a small torus and sphere in contact,
//! filtered to the common bounding volume, quantized into one W-bit frame
//! and tiled into batches of at most `depth` triangles per array.
#![allow(dead_code)]

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_geom::bounding_volume::{triangle_box_overlap_conservative, Aabb};
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::quantize::Frame;
use tritri_geom::scene::{Batch, TaggedTriangle};
use tritri_geom::triangle::Triangle;

/// The triangles of each object inside the common box, with their indices
/// in the mesh as ids, quantized together at `width` bits.
pub fn small_scene(width: u32, nu: usize, nv: usize) -> (Vec<TaggedTriangle>, Vec<TaggedTriangle>) {
    let a = torus([0.0, 0.0, 0.0], 1.0, 0.35, nu, nv);
    let b = sphere([1.0, 0.0, 0.55], 0.4, nu.max(4) / 2 + 2, nv.max(4) / 2 + 2);
    let box_a = Aabb::of_triangles(a.iter()).unwrap();
    let box_b = Aabb::of_triangles(b.iter()).unwrap();
    let common = box_a.overlap(&box_b).expect("the objects' boxes overlap");
    let keep = |ts: &[Triangle]| -> Vec<(u32, Triangle)> {
        ts.iter()
            .enumerate()
            .filter(|(_, t)| triangle_box_overlap_conservative(t, &common))
            .map(|(i, t)| (i as u32, *t))
            .collect()
    };
    let (ka, kb) = (keep(&a), keep(&b));
    let frame = Frame::fit(ka.iter().chain(kb.iter()).map(|(_, t)| t), width).unwrap();
    let q = |v: Vec<(u32, Triangle)>| {
        v.into_iter()
            .map(|(id, t)| TaggedTriangle {
                id,
                triangle: frame.quantize(&t),
            })
            .collect()
    };
    (q(ka), q(kb))
}

/// The arrays of one batch, owned (a [`Batch`] borrows them).
pub type Arrays = (Vec<TaggedTriangle>, Vec<TaggedTriangle>);

/// Random arrays of the given `(A, B)` sizes; batch k's ids start at
/// `k * id_step` (A) and `k * id_step + id_step / 2` (B).
pub fn random_arrays(
    rng: &mut ChaCha8Rng,
    shapes: &[(usize, usize)],
    width: u32,
    id_step: u32,
) -> Vec<Arrays> {
    shapes
        .iter()
        .enumerate()
        .map(|(k, &(a, b))| {
            let first = id_step * k as u32;
            (
                random_triangles(rng, a, width, first),
                random_triangles(rng, b, width, first + id_step / 2),
            )
        })
        .collect()
}

/// The batches over owned arrays.
pub fn batches(arrays: &[Arrays]) -> Vec<Batch<'_>> {
    arrays.iter().map(|(a, b)| Batch { a, b }).collect()
}

/// `n` random W-bit triangles with ids from `first_id`.
pub fn random_triangles(
    rng: &mut ChaCha8Rng,
    n: usize,
    width: u32,
    first_id: u32,
) -> Vec<TaggedTriangle> {
    let half = 1i64 << (width - 1);
    (0..n)
        .map(|i| {
            let mut t = [[0i64; 3]; 3];
            for v in t.iter_mut() {
                for c in v.iter_mut() {
                    *c = rng.gen_range(-half..half);
                }
            }
            TaggedTriangle {
                id: first_id + i as u32,
                triangle: t,
            }
        })
        .collect()
}

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// `pairs a / b, cycles c / d, stalls e / f`: the emitted system's run
/// against rust-hdl's, for a test's log line.
pub fn rtl_against_hdl(
    rtl: &tritri_cosim::system_harness::SystemResult,
    hdl: &tritri_cosim::system_harness::SystemResult,
) -> String {
    format!(
        "pairs {} / {}, cycles {} / {}, stalls {} / {}",
        rtl.pairs.len(),
        hdl.pairs.len(),
        rtl.cycles,
        hdl.cycles,
        rtl.stall_cycles,
        hdl.stall_cycles
    )
}
