//! Surface and solid voxelization against the brute-force oracles of
//! `oracle/voxels.rs`, on the cases voxelizers get wrong: faces on voxel
//! faces, edges and corners; rays from voxel centres through vertices and
//! edges; degenerate triangles. 0 voxels missing or extra.

mod oracle;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::voxelize::{self, VoxelFrame, SUB_BITS};

const S: i64 = 1 << SUB_BITS;

fn sorted(mut v: Vec<[i64; 3]>) -> Vec<[i64; 3]> {
    v.sort_unstable();
    v
}

/// Compares both voxelizations of `mesh` with the oracles; returns the
/// solid's voxel count.
fn check(mesh: &[FixedTriangle], level: u32, what: &str) -> u64 {
    let n = 1i64 << level;
    let frame = VoxelFrame {
        level,
        origin: [0.0; 3],
        voxel_size: 1.0,
    };
    let surface = voxelize::surface(mesh, level, &mut |_| {});
    assert_eq!(
        sorted(oracle::voxels::voxels_of(&surface)),
        oracle::voxels::surface(mesh, n, S),
        "surface of {what}"
    );
    let solid =
        voxelize::solid(mesh, &frame, &mut |_| {}).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_eq!(
        sorted(oracle::voxels::voxels_of(&solid)),
        sorted(oracle::voxels::solid(mesh, n, S)),
        "solid of {what}"
    );
    solid.count()
}

/// The four faces of a tetrahedron, outward or not (parity does not care).
fn tetrahedron(v: [[i64; 3]; 4]) -> Vec<FixedTriangle> {
    vec![
        [v[0], v[1], v[2]],
        [v[0], v[3], v[1]],
        [v[1], v[3], v[2]],
        [v[2], v[3], v[0]],
    ]
}

/// The eight faces of an octahedron with its vertices `r` from `c` along
/// the axes.
fn octahedron(c: [i64; 3], r: i64) -> Vec<FixedTriangle> {
    let mut out = Vec::new();
    for o in 0..8 {
        let axis = |k: usize| {
            let mut p = c;
            p[k] += if o >> k & 1 == 1 { r } else { -r };
            p
        };
        out.push([axis(0), axis(1), axis(2)]);
    }
    out
}

/// Tetrahedra with vertices on a half-voxel lattice: vertices at voxel
/// centres, on voxel faces, edges and corners, so rays from centres pass
/// through vertices and along edges, and faces lie on voxel faces.
#[test]
fn random_tetrahedra_on_the_half_voxel_lattice() {
    let mut rng = ChaCha8Rng::seed_from_u64(1994);
    let level = 3;
    let mut solids = 0;
    for round in 0..150 {
        let mut mesh = Vec::new();
        for _ in 0..rng.gen_range(1..=3) {
            let v = [0; 4].map(|_: i32| [0; 3].map(|_: i64| rng.gen_range(0..=16) * S / 2));
            mesh.extend(tetrahedron(v));
        }
        solids += check(&mesh, level, &format!("round {round}: {mesh:?}"));
    }
    assert!(solids > 1000, "the tetrahedra should hold voxels: {solids}");
}

/// Octahedra centred on voxel centres, corners and face centres: every ray
/// through its axis vertices, and its edges on centre lines.
#[test]
fn octahedra_with_vertices_on_centre_lines() {
    let level = 3;
    for centre in [
        [4 * S + S / 2; 3],
        [4 * S; 3],
        [4 * S, 4 * S + S / 2, 3 * S],
        [S / 2, S / 2, S / 2],
    ] {
        for r in [S / 2, S, 3 * S / 2, 2 * S, 3 * S] {
            let mesh: Vec<FixedTriangle> = octahedron(centre, r)
                .into_iter()
                .map(|t| t.map(|p| p.map(|c| c.clamp(0, 8 * S))))
                .collect();
            check(
                &mesh,
                level,
                &format!("octahedron at {centre:?} radius {r}"),
            );
        }
    }
}

/// Degenerate triangles glued into closed meshes: a tetrahedron with a
/// zero-area sliver on an edge (a triangle and its reverse, so edges stay
/// paired) and point triangles at voxel centres.
#[test]
fn degenerate_triangles_in_closed_meshes() {
    let level = 3;
    let v = [
        [S / 2, S / 2, S / 2],
        [7 * S + S / 2, S / 2, S / 2],
        [S / 2, 7 * S + S / 2, S / 2],
        [S / 2, S / 2, 7 * S + S / 2],
    ];
    let mut mesh = tetrahedron(v);
    let mid = [4 * S, S / 2, S / 2];
    mesh.push([v[0], mid, v[1]]);
    mesh.push([v[1], mid, v[0]]);
    mesh.push([[2 * S + S / 2; 3]; 3]);
    mesh.push([
        [S / 2, 3 * S + S / 2, S / 2],
        [S / 2, 5 * S + S / 2, S / 2],
        [S / 2, 3 * S + S / 2, S / 2],
    ]);
    check(&mesh, level, "tetrahedron with slivers");
}
