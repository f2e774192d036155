//! Brute-force voxelization oracles, for tests only: every voxel decided
//! on its own, with code that shares nothing with `octree::voxelize`.
//!
//! * Surface: voxel `v` is marked iff [`super::triangle_touches_box`] says
//!   some triangle meets its closed cube (only voxels in a triangle's
//!   bounding box are asked).
//! * Solid: voxel `v` is marked iff its centre lies on some closed
//!   triangle, or a ray from the centre along `+x` (not `+z` as the model's)
//!   crosses an odd number of triangles, its foot moved symbolically to
//!   `(y + ε, z + ε²)`.

use tritri_geom::bounding_volume::Aabb;
use tritri_geom::octree::voxels::VoxelGrid;

/// The occupied voxels of a grid, sorted (x, then y, then z), for
/// comparing with the oracles' lists.
pub fn voxels_of(grid: &VoxelGrid) -> Vec<[i64; 3]> {
    let n = grid.side();
    let mut out = Vec::new();
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                if grid.get([x, y, z]) {
                    out.push([x as i64, y as i64, z as i64]);
                }
            }
        }
    }
    out
}

/// Fine-grid vertices; `s` fine steps per voxel, `n` voxels per side.
pub type Mesh = [[[i64; 3]; 3]];

pub fn surface(mesh: &Mesh, n: i64, s: i64) -> Vec<[i64; 3]> {
    let mut out = std::collections::BTreeSet::new();
    for t in mesh {
        let lo = [0, 1, 2].map(|k| (t.iter().map(|v| v[k]).min().unwrap() / s - 1).max(0));
        let hi = [0, 1, 2].map(|k| (t.iter().map(|v| v[k]).max().unwrap() / s + 1).min(n - 1));
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    let cube = Aabb {
                        lo: [x * s, y * s, z * s],
                        hi: [(x + 1) * s, (y + 1) * s, (z + 1) * s],
                    };
                    if super::triangle_touches_box(t, &cube) {
                        out.insert([x, y, z]);
                    }
                }
            }
        }
    }
    out.into_iter().collect()
}

pub fn solid(mesh: &Mesh, n: i64, s: i64) -> Vec<[i64; 3]> {
    let mut out = Vec::new();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let c = [x * s + s / 2, y * s + s / 2, z * s + s / 2].map(i128::from);
                if inside_or_on(mesh, c) {
                    out.push([x, y, z]);
                }
            }
        }
    }
    out
}

/// [`solid`] for large meshes: the same per-centre decision, but each
/// centre asks only the triangles whose bounding box spans its (y, z) foot
/// (no other triangle can hold the centre or cross its +x ray). Sorted.
pub fn solid_by_columns(mesh: &Mesh, n: i64, s: i64) -> Vec<[i64; 3]> {
    let foot = |i: i64| i * s + s / 2;
    let mut columns: Vec<Vec<usize>> = vec![Vec::new(); (n * n) as usize];
    for (index, t) in mesh.iter().enumerate() {
        let range = |k: usize| {
            let lo = t.iter().map(|v| v[k]).min().unwrap();
            let hi = t.iter().map(|v| v[k]).max().unwrap();
            (0..n).filter(move |&i| lo <= foot(i) && foot(i) <= hi)
        };
        for z in range(2) {
            for y in range(1) {
                columns[(z * n + y) as usize].push(index);
            }
        }
    }
    let mut out = Vec::new();
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                let candidates: Vec<[[i64; 3]; 3]> = columns[(z * n + y) as usize]
                    .iter()
                    .map(|&i| mesh[i])
                    .collect();
                if inside_or_on(&candidates, [foot(x), foot(y), foot(z)].map(i128::from)) {
                    out.push([x, y, z]);
                }
            }
        }
    }
    out
}

fn inside_or_on(mesh: &Mesh, c: [i128; 3]) -> bool {
    let mut parity = false;
    for t in mesh {
        let p = t.map(|v| v.map(i128::from));
        if point_on_triangle(&p, c) {
            return true;
        }
        // Cheap rejections: the ray only goes towards +x.
        let all = |k: usize, below: bool| {
            p.iter()
                .all(|v| if below { v[k] < c[k] } else { v[k] > c[k] })
        };
        if all(0, true) || all(1, true) || all(1, false) || all(2, true) || all(2, false) {
            continue;
        }
        let u = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
        let w = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
        let normal = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        if normal[0] == 0 {
            continue;
        }
        // Perturbed foot strictly inside the yz projection?
        let ccw = normal[0] > 0;
        let inside = (0..3).all(|e| {
            let (a, b) = (p[e], p[(e + 1) % 3]);
            let exact = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]);
            // d/dy = -(b_z - a_z) (the ε term), d/dz = b_y - a_y (ε²).
            let sign = [exact, a[2] - b[2], b[1] - a[1]]
                .into_iter()
                .find(|&v| v != 0)
                .unwrap_or(0)
                .signum();
            (sign > 0) == ccw && sign != 0
        });
        if !inside {
            continue;
        }
        // The crossing's x: n_x x = n · p0 - n_y c_y - n_z c_z; ahead of c?
        let r = normal[0] * p[0][0] + normal[1] * (p[0][1] - c[1]) + normal[2] * (p[0][2] - c[2]);
        if (r - normal[0] * c[0]).signum() == normal[0].signum() {
            parity = !parity;
        }
    }
    parity
}

/// Is `c` on the closed triangle (any triangle, degenerate ones too)?
fn point_on_triangle(p: &[[i128; 3]; 3], c: [i128; 3]) -> bool {
    let d = |a: [i128; 3], b: [i128; 3]| [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let x = |u: [i128; 3], v: [i128; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let dot = |u: [i128; 3], v: [i128; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let normal = x(d(p[0], p[1]), d(p[0], p[2]));
    if normal == [0; 3] {
        // A segment or a point: on one of its three edges.
        return (0..3).any(|e| {
            let (a, b) = (p[e], p[(e + 1) % 3]);
            x(d(a, b), d(a, c)) == [0; 3] && dot(d(a, c), d(b, c)) <= 0
        });
    }
    if dot(normal, d(p[0], c)) != 0 {
        return false;
    }
    // In the plane: on the inner side of (or on) every edge.
    (0..3).all(|e| dot(x(d(p[e], p[(e + 1) % 3]), d(p[e], c)), normal) >= 0)
}
