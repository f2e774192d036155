//! Scenes for the system tests: a small torus and sphere in contact,
//! filtered to the common bounding volume, quantized into one W-bit frame
//! and tiled into batches of at most `depth` triangles per array.
#![allow(dead_code)]

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_cosim::stream::IdTriangle;
use tritri_cosim::system_harness::Batch;
use tritri_geom::bounding_volume::{triangle_box_overlap_conservative, Aabb};
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::quantize::Frame;
use tritri_geom::triangle::Triangle;

/// The triangles of each object inside the common box, with their indices
/// in the mesh as ids, quantized together at `width` bits.
pub fn small_scene(width: u32, nu: usize, nv: usize) -> (Vec<IdTriangle>, Vec<IdTriangle>) {
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
    let q = |v: Vec<(u32, Triangle)>| v.into_iter().map(|(id, t)| IdTriangle { id, triangle: frame.quantize(&t) }).collect();
    (q(ka), q(kb))
}

/// Every (A chunk, B chunk) pair of chunks of at most `depth` triangles.
pub fn tile(a: &[IdTriangle], b: &[IdTriangle], depth: usize) -> Vec<Batch> {
    let mut batches = Vec::new();
    for ca in a.chunks(depth) {
        for cb in b.chunks(depth) {
            batches.push(Batch { a: ca.to_vec(), b: cb.to_vec() });
        }
    }
    batches
}

/// `n` random W-bit triangles with ids from `first_id`.
pub fn random_triangles(rng: &mut ChaCha8Rng, n: usize, width: u32, first_id: u32) -> Vec<IdTriangle> {
    let half = 1i64 << (width - 1);
    (0..n)
        .map(|i| {
            let mut t = [[0i64; 3]; 3];
            for v in t.iter_mut() {
                for c in v.iter_mut() {
                    *c = rng.gen_range(-half..half);
                }
            }
            IdTriangle { id: first_id + i as u32, triangle: t }
        })
        .collect()
}

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}
