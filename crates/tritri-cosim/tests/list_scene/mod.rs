//! The lists of a real scene for the tests of the units that read them
//! from external memory (`tests/list_pass.rs`, `tests/leaf_reader.rs`).

use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::octree::cell::Cell;
use tritri_geom::scene::load::SceneObject;
use tritri_geom::scene::{prepare_octree, SceneOptions, TaggedTriangle};
use tritri_rtl::broad_phase::list_entry::{pack, ENTRY_BYTES};
use tritri_rtl::system::SystemConfig;

/// A torus and a sphere in contact on a `grid_bits`-bit grid: each
/// object's kept triangles as list entries, and the root cell of the broad
/// phase.
pub fn scene(
    grid_bits: usize,
    torus_segments: usize,
    sphere_segments: usize,
) -> ([Vec<[u8; ENTRY_BYTES]>; 2], Cell) {
    let a = SceneObject::from_triangles(
        "torus",
        torus(
            [0.0, 0.0, 0.0],
            1.0,
            0.35,
            torus_segments,
            torus_segments / 2,
        ),
    );
    let b = SceneObject::from_triangles(
        "sphere",
        sphere([1.0, 0.0, 0.55], 0.4, sphere_segments, sphere_segments / 2),
    );
    let depth = 8;
    let options = SceneOptions {
        grid_bits: grid_bits as u32,
        depth,
        split: true,
    };
    let config = SystemConfig::new(grid_bits, 2).with_depth(depth);
    let prepared = prepare_octree(&a, &b, &options, &config, None).unwrap();
    let entries = |kept: &[TaggedTriangle]| {
        kept.iter()
            .map(|t| pack(t.id, &t.triangle, grid_bits))
            .collect::<Vec<_>>()
    };
    let root = prepared.octree.as_ref().unwrap().root.unwrap();
    ([entries(&prepared.kept_a), entries(&prepared.kept_b)], root)
}
