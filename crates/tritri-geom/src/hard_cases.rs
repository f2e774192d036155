//! Deterministic generators of hard triangle pairs, for tests and benches.
//!
//! Every generator is seeded (ChaCha8), so a seed names a set of pairs for
//! good. Each case carries a name, `category/parameter=value/...#index`, so a
//! failing test points at the configuration that broke.
//!
//! The categories are the configurations where inexact or careless tests go
//! wrong:
//!
//! * [`coplanar_axis_plane`], [`coplanar_integer_plane`]: both triangles on
//!   one plane, exactly (integer lattices, or an axis plane);
//! * [`vertex_on_plane`]: a vertex exactly on the other triangle's plane,
//!   then moved by a few ulps;
//! * [`shared_vertex`], [`shared_edge`], [`collinear_edges`];
//! * [`needles_and_slivers`]: a very short edge, or three nearly collinear
//!   vertices;
//! * [`near_miss`]: touching configurations moved apart or together by a
//!   relative gap from 1e-3 down to 1e-15;
//! * [`large_offsets`]: small cases with 1e5..1e9 added to every coordinate
//!   (the f64 values after the addition are the case);
//! * [`degenerate`]: segments and points against triangles, segments and
//!   points, coplanar and not.
//!
//! Exact coplanarity and collinearity are built on integer lattices: points
//! `o + i u + j v` with integer `o, u, v, i, j` lie exactly on the plane with
//! normal `u × v`, and their f64 coordinates are exact.
//!
//! ```
//! use tritri_geom::hard_cases::{hard_case_suite, random_pairs};
//! let suite = hard_case_suite();
//! assert!(suite.len() > 1000);
//! assert!(suite[0].name.contains('/'));
//! assert_eq!(random_pairs(10, 1), random_pairs(10, 1)); // deterministic
//! ```

use crate::triangle::{Point, Triangle, TrianglePair};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A named triangle pair.
#[derive(Clone, Debug, PartialEq)]
pub struct HardCase {
    /// `category/parameter=value/...#index`.
    pub name: String,
    pub pair: TrianglePair,
}

impl HardCase {
    fn new(name: String, t1: Triangle, t2: Triangle) -> Self {
        HardCase {
            name,
            pair: TrianglePair::new(t1, t2),
        }
    }
}

/// The standard suite: every category, a few thousand cases in all. Tests
/// run each case in all 72 orderings.
pub fn hard_case_suite() -> Vec<HardCase> {
    let mut cases = Vec::new();
    cases.extend(coplanar_axis_plane(400, 1));
    cases.extend(coplanar_integer_plane(400, 2));
    cases.extend(vertex_on_plane(500, 3));
    cases.extend(shared_vertex(200, 4));
    cases.extend(shared_edge(200, 5));
    cases.extend(collinear_edges(250, 6));
    cases.extend(needles_and_slivers(300, 7));
    cases.extend(near_miss(4, 8));
    cases.extend(large_offsets(5, 9));
    cases.extend(degenerate(25, 10));
    cases
}

/// Coplanar pairs for benchmarks: half on axis planes, half on arbitrary
/// integer planes.
pub fn coplanar_lattice_pairs(n: usize, seed: u64) -> Vec<TrianglePair> {
    let half = n / 2;
    coplanar_axis_plane(half, seed)
        .into_iter()
        .chain(coplanar_integer_plane(n - half, seed ^ 0x5eed))
        .map(|c| c.pair)
        .collect()
}

/// Random pairs with all six vertices uniform in the unit cube `[0, 1)^3`
/// (about a quarter of them intersect).
pub fn random_pairs(n: usize, seed: u64) -> Vec<TrianglePair> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| TrianglePair::new(unit_cube_triangle(&mut rng), unit_cube_triangle(&mut rng)))
        .collect()
}

/// Random pairs in the unit cube that are near-degenerate by construction:
/// coordinates snapped to a coarse grid (exact coplanarity, collinearity,
/// shared vertices and degenerate triangles happen often), shared vertices
/// and edges, exactly coplanar lattice pairs, and a vertex on the other
/// triangle's plane moved by a few ulps.
pub fn random_near_degenerate_pairs(n: usize, seed: u64) -> Vec<TrianglePair> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| match rng.gen_range(0..6) {
            0 => grid_snapped_pair(&mut rng, 4.0),
            1 => grid_snapped_pair(&mut rng, 16.0),
            2 => {
                let t1 = unit_cube_triangle(&mut rng);
                let shared = t1[rng.gen_range(0..3)];
                TrianglePair::new(
                    t1,
                    [shared, unit_cube_point(&mut rng), unit_cube_point(&mut rng)],
                )
            }
            3 => {
                let t1 = unit_cube_triangle(&mut rng);
                let i = rng.gen_range(0..3);
                TrianglePair::new(t1, [t1[i], t1[(i + 1) % 3], unit_cube_point(&mut rng)])
            }
            4 => {
                let plane = LatticePlane::random(&mut rng, 3, 4);
                let mut ij = || (rng.gen_range(-3..=3), rng.gen_range(-3..=3));
                let p: [_; 6] = std::array::from_fn(|_| {
                    let (i, j) = ij();
                    plane.point(i, j)
                });
                let scaled = |k: usize| lattice_to_point(p[k], 1.0 / 32.0);
                TrianglePair::new(
                    [scaled(0), scaled(1), scaled(2)],
                    [scaled(3), scaled(4), scaled(5)],
                )
            }
            _ => {
                let case = vertex_on_plane_case(&mut rng, 0);
                let s = 1.0 / 32.0; // a power of two: scaling is exact
                let scale = |t: Triangle| t.map(|p| p.map(|x| x * s));
                TrianglePair::new(scale(case.pair.t1), scale(case.pair.t2))
            }
        })
        .collect()
}

// ---------------------------------------------------------------------------
// Categories
// ---------------------------------------------------------------------------

/// Both triangles on one axis plane (`x = c`, `y = c` or `z = c`), with
/// in-plane coordinates on a small integer lattice times a scale. The axis
/// coordinate is the same f64 for all six vertices, so the pair is exactly
/// coplanar even when the scale (0.1, sqrt 3) makes the in-plane values
/// inexact decimals.
pub fn coplanar_axis_plane(count: usize, seed: u64) -> Vec<HardCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scales = [
        ("1", 1.0),
        ("0.1", 0.1),
        ("2^-20", 2f64.powi(-20)),
        ("1000", 1000.0),
        ("sqrt3", 3f64.sqrt()),
    ];
    (0..count)
        .map(|k| {
            let axis = k % 3;
            let (scale_name, scale) = scales[(k / 3) % scales.len()];
            let level = match rng.gen_range(0..3) {
                0 => 0.0,
                1 => rng.gen_range(-5..=5) as f64,
                _ => rng.gen::<f64>(),
            };
            let mut vertex = || {
                let mut p = [0.0; 3];
                p[axis] = level;
                p[(axis + 1) % 3] = rng.gen_range(-4..=4) as f64 * scale;
                p[(axis + 2) % 3] = rng.gen_range(-4..=4) as f64 * scale;
                p
            };
            let t1 = [vertex(), vertex(), vertex()];
            let t2 = [vertex(), vertex(), vertex()];
            let name = format!(
                "coplanar_axis_plane/axis={}/scale={scale_name}#{k}",
                ["x", "y", "z"][axis]
            );
            HardCase::new(name, t1, t2)
        })
        .collect()
}

/// Both triangles on one plane with a random integer normal, vertices on the
/// plane's integer lattice (exact), optionally scaled by a power of two.
pub fn coplanar_integer_plane(count: usize, seed: u64) -> Vec<HardCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|k| {
            let plane = LatticePlane::random(&mut rng, 3, 5);
            let (scale_name, scale) = [
                ("1", 1.0),
                ("2^-10", 2f64.powi(-10)),
                ("2^20", 2f64.powi(20)),
            ][k % 3];
            let mut vertex = || {
                lattice_to_point(
                    plane.point(rng.gen_range(-3..=3), rng.gen_range(-3..=3)),
                    scale,
                )
            };
            let t1 = [vertex(), vertex(), vertex()];
            let t2 = [vertex(), vertex(), vertex()];
            let n = plane.normal();
            let name = format!(
                "coplanar_integer_plane/normal=({},{},{})/scale={scale_name}#{k}",
                n[0], n[1], n[2]
            );
            HardCase::new(name, t1, t2)
        })
        .collect()
}

/// T1 has a vertex exactly on T2's plane (inside T2, on an edge, at a vertex,
/// or outside), its other vertices on one side, or (variant `edge`) a whole
/// edge on the plane; then the on-plane vertex is moved by -3..=3 ulps in one
/// or all coordinates.
pub fn vertex_on_plane(count: usize, seed: u64) -> Vec<HardCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|k| vertex_on_plane_case(&mut rng, k))
        .collect()
}

fn vertex_on_plane_case(rng: &mut ChaCha8Rng, k: usize) -> HardCase {
    let plane = LatticePlane::random(rng, 3, 5);
    let t2 = [plane.point(0, 0), plane.point(4, 0), plane.point(0, 4)];
    let places = [
        ("inside", (1, 1)),
        ("edge", (2, 0)),
        ("hypotenuse", (2, 2)),
        ("vertex", (4, 0)),
        ("outside_beyond_hypotenuse", (3, 3)),
        ("outside_behind_edge", (-1, 1)),
    ];
    let (place, (i, j)) = places[rng.gen_range(0..places.len())];
    let p = plane.point(i, j);
    let above = lattice_add(p, plane.off_plane_vector(rng, 3));
    let whole_edge = rng.gen_bool(0.3);
    let second = if whole_edge {
        plane.point(i + rng.gen_range(-2..=2), j + rng.gen_range(1..=2))
    } else {
        lattice_add(p, plane.off_plane_vector(rng, 3))
    };
    let ulps = rng.gen_range(-3..=3);
    let all_coordinates = rng.gen_bool(0.3);
    let axis = rng.gen_range(0..3);
    let mut moved = lattice_to_point(p, 1.0);
    for (k, x) in moved.iter_mut().enumerate() {
        if all_coordinates || k == axis {
            *x = nudge(*x, ulps);
        }
    }
    let t1 = [
        moved,
        lattice_to_point(second, 1.0),
        lattice_to_point(above, 1.0),
    ];
    let t2 = t2.map(|q| lattice_to_point(q, 1.0));
    let touching = if whole_edge { "edge" } else { "vertex" };
    let moved_what = if all_coordinates {
        "xyz".to_string()
    } else {
        ["x", "y", "z"][axis].to_string()
    };
    let name = format!("vertex_on_plane/{touching}/at={place}/ulps={ulps}/moved={moved_what}#{k}");
    HardCase::new(name, t1, t2)
}

/// The triangles share exactly one vertex (same f64 values): random unit-cube
/// triangles, or both on one integer plane (then they may also overlap).
pub fn shared_vertex(count: usize, seed: u64) -> Vec<HardCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|k| {
            let (t1, t2, kind) = if k % 2 == 0 {
                let t1 = unit_cube_triangle(&mut rng);
                let t2 = [
                    t1[rng.gen_range(0..3)],
                    unit_cube_point(&mut rng),
                    unit_cube_point(&mut rng),
                ];
                (t1, t2, "general")
            } else {
                let plane = LatticePlane::random(&mut rng, 3, 5);
                let mut v = || {
                    lattice_to_point(
                        plane.point(rng.gen_range(-3..=3), rng.gen_range(-3..=3)),
                        1.0,
                    )
                };
                let t1 = [v(), v(), v()];
                let t2 = [t1[k % 3], v(), v()];
                (t1, t2, "coplanar")
            };
            HardCase::new(format!("shared_vertex/{kind}#{k}"), t1, t2)
        })
        .collect()
}

/// The triangles share an edge: third vertices random (general), or both on
/// one integer plane, on opposite sides of the edge (touching along it only)
/// or on the same side (overlapping).
pub fn shared_edge(count: usize, seed: u64) -> Vec<HardCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|k| {
            let (t1, t2, kind) = match k % 3 {
                0 => {
                    let t1 = unit_cube_triangle(&mut rng);
                    let i = rng.gen_range(0..3);
                    (
                        t1,
                        [t1[(i + 1) % 3], t1[i], unit_cube_point(&mut rng)],
                        "general",
                    )
                }
                side => {
                    let plane = LatticePlane::random(&mut rng, 3, 5);
                    // The edge from (0,0) to (a,0); third vertices at j > 0 and
                    // j < 0 (opposite) or both j > 0 (same side).
                    let a = rng.gen_range(1..=3);
                    let j1 = rng.gen_range(1..=3);
                    let j2 = if side == 1 {
                        -rng.gen_range(1..=3)
                    } else {
                        rng.gen_range(1..=3)
                    };
                    let v = |i, j| lattice_to_point(plane.point(i, j), 1.0);
                    let t1 = [v(0, 0), v(a, 0), v(rng.gen_range(-2..=4), j1)];
                    let t2 = [v(a, 0), v(0, 0), v(rng.gen_range(-2..=4), j2)];
                    (
                        t1,
                        t2,
                        if side == 1 {
                            "coplanar_opposite_sides"
                        } else {
                            "coplanar_same_side"
                        },
                    )
                }
            };
            HardCase::new(format!("shared_edge/{kind}#{k}"), t1, t2)
        })
        .collect()
}

/// An edge of T1 and an edge of T2 on one line (exact, integer lattice), the
/// two edges overlapping, nested, touching at an end point or one unit apart;
/// the third vertices off the line, in general position or coplanar.
pub fn collinear_edges(count: usize, seed: u64) -> Vec<HardCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let layouts = [
        ("overlapping", (0, 4), (2, 6)),
        ("nested", (0, 6), (2, 4)),
        ("identical", (0, 4), (0, 4)),
        ("touching_end", (0, 3), (3, 6)),
        ("one_apart", (0, 3), (4, 7)),
    ];
    (0..count)
        .map(|k| {
            let origin = lattice_vector(&mut rng, 5);
            let direction = nonzero_lattice_vector(&mut rng, 3);
            let (layout, (t0, t1), (s0, s1)) = layouts[k % layouts.len()];
            let on_line =
                |t: i64| lattice_to_point(lattice_add(origin, lattice_scale(direction, t)), 1.0);
            let w1 = off_line_vector(&mut rng, direction, 3);
            let (w2, third) = match rng.gen_range(0..3) {
                0 => (off_line_vector(&mut rng, direction, 3), "general"),
                1 => (
                    lattice_add(
                        lattice_scale(w1, -1),
                        lattice_scale(direction, rng.gen_range(-2..=2)),
                    ),
                    "coplanar_opposite",
                ),
                _ => (
                    lattice_add(w1, lattice_scale(direction, rng.gen_range(-2..=2))),
                    "coplanar_same_side",
                ),
            };
            let tri1 = [
                on_line(t0),
                on_line(t1),
                lattice_to_point(lattice_add(origin, w1), 1.0),
            ];
            let tri2 = [
                on_line(s0),
                lattice_to_point(
                    lattice_add(lattice_add(origin, lattice_scale(direction, s0)), w2),
                    1.0,
                ),
                on_line(s1),
            ];
            HardCase::new(
                format!("collinear_edges/{layout}/third={third}#{k}"),
                tri1,
                tri2,
            )
        })
        .collect()
}

/// Needles (one edge of relative length 1e-6 .. a few ulps) and slivers
/// (the third vertex 1e-6 .. a few ulps off the line of the other two),
/// against a large triangle through a point of the thin one, another thin
/// triangle through the same point, or a random triangle.
pub fn needles_and_slivers(count: usize, seed: u64) -> Vec<HardCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let sizes = [
        ("1e-6", Some(1e-6)),
        ("1e-9", Some(1e-9)),
        ("1e-12", Some(1e-12)),
        ("1e-15", Some(1e-15)),
        ("ulps", None),
    ];
    (0..count)
        .map(|k| {
            let needle = k % 2 == 0;
            let (size_name, size) = sizes[(k / 2) % sizes.len()];
            let a = unit_cube_point(&mut rng);
            let b = unit_cube_point(&mut rng);
            let base = if needle {
                b
            } else {
                [0, 1, 2].map(|i| a[i] + (b[i] - a[i]) / 2.0)
            };
            let w = [0, 1, 2].map(|_| rng.gen_range(-1.0..1.0));
            let c = match size {
                Some(s) => [0, 1, 2].map(|i| base[i] + s * w[i]),
                None => base.map(|x| nudge(x, rng.gen_range(-3..=3))),
            };
            let thin = [a, b, c];
            // A point on the thin triangle's long edge: an end, or inside.
            let t = [0.0, 0.5, 1.0, 0.25][rng.gen_range(0..4)];
            let m = [0, 1, 2].map(|i| a[i] + t * (b[i] - a[i]));
            let (opponent, kind) = match rng.gen_range(0..3) {
                0 => {
                    let r1 = [0, 1, 2].map(|_| rng.gen_range(-0.5..0.5));
                    let r2 = [0, 1, 2].map(|_| rng.gen_range(-0.5..0.5));
                    (
                        [
                            add3(m, r1),
                            add3(m, r2),
                            [0, 1, 2].map(|i| m[i] - r1[i] - r2[i]),
                        ],
                        "large_through",
                    )
                }
                1 => {
                    let d = [0, 1, 2].map(|_| rng.gen_range(-0.5..0.5));
                    let e = [0, 1, 2].map(|_| rng.gen_range(-1e-9..1e-9));
                    (
                        [
                            add3(m, d),
                            [0, 1, 2].map(|i| m[i] - d[i]),
                            [0, 1, 2].map(|i| m[i] - d[i] + e[i]),
                        ],
                        "thin_through",
                    )
                }
                _ => (unit_cube_triangle(&mut rng), "random"),
            };
            let shape = if needle { "needle" } else { "sliver" };
            HardCase::new(
                format!("needles_and_slivers/{shape}/size={size_name}/opponent={kind}/t={t}#{k}"),
                thin,
                opponent,
            )
        })
        .collect()
}

/// Touching configurations moved by a relative gap `g` in 1e-3 ..= 1e-15:
/// `side=gap` moves them apart (separated), `side=touching` moves them
/// together by the same amount (intersecting). Kinds: a vertex over a face,
/// an edge over an edge (crossing), an edge parallel over a face. In
/// `frame=axis` the gap is an exact coordinate; in `frame=rotated` a random
/// rotation, scale and translation follow (the rounded f64s are the case).
/// `repeats` copies of each combination (13 gaps x 2 sides x 3 kinds x 2 frames).
pub fn near_miss(repeats: usize, seed: u64) -> Vec<HardCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut cases = Vec::new();
    for r in 0..repeats {
        for exponent in 3..=15 {
            let g = 10f64.powi(-exponent);
            for (side, h) in [("gap", g), ("touching", -g)] {
                for kind in ["vertex_face", "edge_edge", "edge_face"] {
                    let (t1, t2) = match kind {
                        // T2 in z = 0 around the origin; T1's apex at height h.
                        "vertex_face" => (
                            [[0.0, 0.0, h], [0.3, -0.2, 1.0], [-0.2, 0.4, 0.8]],
                            [[-1.0, -1.0, 0.0], [2.0, -1.0, 0.0], [-1.0, 2.0, 0.0]],
                        ),
                        // T2's top edge on the x axis, T2 below z = 0 (plane 2y = z);
                        // T1's bottom edge along y at height h.
                        "edge_edge" => (
                            [[0.0, -1.0, h], [0.0, 1.0, h], [0.3, 0.1, 1.0]],
                            [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, -0.5, -1.0]],
                        ),
                        // T1's bottom edge parallel to T2's plane, over its interior.
                        _ => (
                            [[-0.5, 0.0, h], [0.5, 0.0, h], [0.0, 0.3, 1.0]],
                            [[-1.0, -1.0, 0.0], [2.0, -1.0, 0.0], [-1.0, 2.0, 0.0]],
                        ),
                    };
                    let name = |frame: &str| {
                        format!(
                            "near_miss/kind={kind}/gap=1e-{exponent}/side={side}/frame={frame}#{r}"
                        )
                    };
                    cases.push(HardCase::new(name("axis"), t1, t2));
                    let motion = RigidMotion::random(&mut rng);
                    cases.push(HardCase::new(
                        name("rotated"),
                        t1.map(|p| motion.apply(p)),
                        t2.map(|p| motion.apply(p)),
                    ));
                }
            }
        }
    }
    cases
}

/// Small base cases (near misses at gap 1e-3 on both sides, shared edges,
/// coplanar lattice pairs, touching collinear edges, a vertex on a plane)
/// with an offset of 1e5 ..= 1e9 added to every coordinate: the same offset
/// on every axis (`offset=1eK`) or a different one per axis (`offset=1eK*(1,-1/3,2)`).
/// `repeats` copies of each (base, offset) combination.
pub fn large_offsets(repeats: usize, seed: u64) -> Vec<HardCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut bases: Vec<HardCase> = Vec::new();
    for r in 0..repeats as u64 {
        let s = seed.wrapping_mul(1000).wrapping_add(r);
        let mut these = Vec::new();
        these.extend(
            near_miss(1, s)
                .into_iter()
                .filter(|c| c.name.contains("gap=1e-3/")),
        );
        these.extend(shared_edge(3, s));
        these.extend(coplanar_integer_plane(1, s));
        these.extend(
            collinear_edges(5, s)
                .into_iter()
                .filter(|c| c.name.contains("touching_end")),
        );
        these.push(vertex_on_plane_case(&mut rng, r as usize));
        // The base generators number from 0 in every repeat: name the repeat.
        bases.extend(these.into_iter().map(|c| HardCase {
            name: format!("repeat={r}/base={}", c.name),
            ..c
        }));
    }
    let mut cases = Vec::new();
    for base in &bases {
        for exponent in 5..=9 {
            let o = 10f64.powi(exponent);
            for (offset_name, offset) in [
                (format!("1e{exponent}"), [o, o, o]),
                (format!("1e{exponent}*(1,-1/3,2)"), [o, -o / 3.0, 2.0 * o]),
            ] {
                let shift = |t: Triangle| t.map(|p| [0, 1, 2].map(|i| p[i] + offset[i]));
                cases.push(HardCase::new(
                    format!("large_offsets/offset={offset_name}/{}", base.name),
                    shift(base.pair.t1),
                    shift(base.pair.t2),
                ));
            }
        }
    }
    cases
}

/// Degenerate triangles: segments (three collinear vertices, in several
/// layouts: repeated end, middle vertex listed first or last) and points
/// (three equal vertices), against triangles, segments and points, coplanar
/// and not, touching, crossing and apart. `repeats` copies of each layout.
pub fn degenerate(repeats: usize, seed: u64) -> Vec<HardCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut cases = Vec::new();
    for r in 0..repeats {
        segment_vs_triangle(&mut rng, r, &mut cases);
        segment_vs_segment(&mut rng, r, &mut cases);
        point_vs_triangle(&mut rng, r, &mut cases);
        point_vs_segment(&mut rng, r, &mut cases);
        point_vs_point(&mut rng, r, &mut cases);
    }
    cases
}

/// T = (0,0), (4,0), (0,4) on a lattice plane; segments `x .. x + 2d` given
/// as `(x, d)` in plane or lattice coordinates.
fn segment_vs_triangle(rng: &mut ChaCha8Rng, r: usize, cases: &mut Vec<HardCase>) {
    let plane = LatticePlane::random(rng, 3, 5);
    let t =
        [plane.point(0, 0), plane.point(4, 0), plane.point(0, 4)].map(|p| lattice_to_point(p, 1.0));
    let w = plane.off_plane_vector(rng, 3);
    let minus = |p: [i64; 3], v: [i64; 3]| lattice_add(p, lattice_scale(v, -1));
    let in_plane = |i0, j0, i1, j1| {
        (
            plane.point(i0, j0),
            lattice_sub(plane.point(i1, j1), plane.point(i0, j0)),
        )
    };
    let layouts: Vec<(&str, Segment)> = vec![
        ("crossing_interior", (minus(plane.point(1, 1), w), w)),
        ("crossing_edge", (minus(plane.point(2, 0), w), w)),
        ("crossing_vertex", (minus(plane.point(0, 0), w), w)),
        ("end_on_face", (plane.point(1, 1), w)),
        ("end_on_edge", (plane.point(0, 2), w)),
        ("above", (lattice_add(plane.point(1, 1), w), w)),
        ("crossing_plane_outside", (minus(plane.point(3, 3), w), w)),
        ("coplanar_crossing", in_plane(-1, 1, 5, 1)),
        ("coplanar_inside_to_hypotenuse", in_plane(1, 1, 1, 2)),
        ("coplanar_outside", in_plane(3, 3, 5, 1)),
        ("coplanar_touching_vertex", in_plane(4, 0, 6, -2)),
        ("coplanar_along_edge", in_plane(-2, 0, 2, 0)),
    ];
    for (layout, (x, d)) in layouts {
        let form = rng.gen_range(0..4);
        let seg = segment_triangle_form(x, d, form);
        cases.push(HardCase::new(
            format!("degenerate/segment_vs_triangle/{layout}/form={form}#{r}"),
            seg,
            t,
        ));
    }
}

fn segment_vs_segment(rng: &mut ChaCha8Rng, r: usize, cases: &mut Vec<HardCase>) {
    let p = lattice_vector(rng, 5);
    let w1 = nonzero_lattice_vector(rng, 3);
    let w2 = off_line_vector(rng, w1, 3);
    let n = lattice_cross(w1, w2);
    let at = |base: [i64; 3], k: i64| lattice_add(base, lattice_scale(w1, k));
    let minus = |a: [i64; 3], b: [i64; 3]| lattice_sub(a, b);
    // Each segment as (start, half direction): start .. start + 2 * half.
    let layouts: Vec<(&str, Segment, Segment)> = vec![
        ("crossing", (minus(p, w1), w1), (minus(p, w2), w2)),
        ("t_junction", (p, w1), (minus(p, w2), w2)),
        ("shared_end", (p, w1), (p, w2)),
        (
            "skew",
            (minus(p, w1), w1),
            (minus(lattice_add(p, n), w2), w2),
        ),
        (
            "coplanar_apart",
            (minus(p, w1), w1),
            (minus(at(p, 3), w2), w2),
        ),
        ("collinear_overlapping", (minus(p, w1), w1), (p, w1)),
        ("collinear_touching", (minus(p, w1), w1), (at(p, 1), w1)),
        ("collinear_apart", (minus(p, w1), w1), (at(p, 2), w1)),
        (
            "parallel",
            (minus(p, w1), w1),
            (minus(lattice_add(p, w2), w1), w1),
        ),
    ];
    for (layout, (x1, d1), (x2, d2)) in layouts {
        let (f1, f2) = (rng.gen_range(0..4), rng.gen_range(0..4));
        cases.push(HardCase::new(
            format!("degenerate/segment_vs_segment/{layout}/forms={f1}{f2}#{r}"),
            segment_triangle_form(x1, d1, f1),
            segment_triangle_form(x2, d2, f2),
        ));
    }
}

fn point_vs_triangle(rng: &mut ChaCha8Rng, r: usize, cases: &mut Vec<HardCase>) {
    let plane = LatticePlane::random(rng, 3, 5);
    let t =
        [plane.point(0, 0), plane.point(4, 0), plane.point(0, 4)].map(|p| lattice_to_point(p, 1.0));
    let w = plane.off_plane_vector(rng, 3);
    let inside = lattice_to_point(plane.point(1, 1), 1.0);
    let places = [
        ("inside", inside),
        ("on_edge", lattice_to_point(plane.point(2, 0), 1.0)),
        ("on_hypotenuse", lattice_to_point(plane.point(1, 3), 1.0)),
        ("on_vertex", lattice_to_point(plane.point(0, 4), 1.0)),
        ("coplanar_outside", lattice_to_point(plane.point(3, 2), 1.0)),
        (
            "above",
            lattice_to_point(lattice_add(plane.point(1, 1), w), 1.0),
        ),
        ("inside_moved_1ulp", inside.map(|x| nudge(x, 1))),
        (
            "vertex_moved_1ulp",
            lattice_to_point(plane.point(0, 4), 1.0).map(|x| nudge(x, -1)),
        ),
    ];
    for (place, q) in places {
        cases.push(HardCase::new(
            format!("degenerate/point_vs_triangle/{place}#{r}"),
            [q, q, q],
            t,
        ));
    }
}

fn point_vs_segment(rng: &mut ChaCha8Rng, r: usize, cases: &mut Vec<HardCase>) {
    let p = lattice_vector(rng, 5);
    let w = nonzero_lattice_vector(rng, 3);
    let v = off_line_vector(rng, w, 3);
    let seg = segment_triangle_form(lattice_sub(p, w), w, rng.gen_range(0..4));
    let places = [
        ("interior", p),
        ("end", lattice_add(p, w)),
        ("on_line_outside", lattice_add(p, lattice_scale(w, 2))),
        ("off_line", lattice_add(p, v)),
    ];
    for (place, q) in places {
        let q = lattice_to_point(q, 1.0);
        cases.push(HardCase::new(
            format!("degenerate/point_vs_segment/{place}#{r}"),
            [q, q, q],
            seg,
        ));
    }
    let q = lattice_to_point(p, 1.0).map(|x| nudge(x, 1));
    cases.push(HardCase::new(
        format!("degenerate/point_vs_segment/interior_moved_1ulp#{r}"),
        [q, q, q],
        seg,
    ));
}

fn point_vs_point(rng: &mut ChaCha8Rng, r: usize, cases: &mut Vec<HardCase>) {
    let p = unit_cube_point(rng);
    let axis = rng.gen_range(0..3);
    let mut q = p;
    q[axis] = nudge(q[axis], 1);
    let far = unit_cube_point(rng);
    for (place, other) in [("equal", p), ("one_ulp_apart", q), ("apart", far)] {
        cases.push(HardCase::new(
            format!("degenerate/point_vs_point/{place}#{r}"),
            [p, p, p],
            [other, other, other],
        ));
    }
    // A point against a segment of a triangle's three vertices listed with a repeat.
    cases.push(HardCase::new(
        format!("degenerate/point_vs_point/repeated_vertex_segment#{r}"),
        [p, p, p],
        [p, far, p],
    ));
}

/// The segment `x .. x + 2d` as a degenerate triangle, in one of four vertex
/// layouts: (ends, middle), (middle, ends), (end, end, repeated end),
/// (repeated start, end).
fn segment_triangle_form(x: [i64; 3], d: [i64; 3], form: usize) -> Triangle {
    let start = lattice_to_point(x, 1.0);
    let middle = lattice_to_point(lattice_add(x, d), 1.0);
    let end = lattice_to_point(lattice_add(x, lattice_scale(d, 2)), 1.0);
    match form {
        0 => [start, end, middle],
        1 => [middle, start, end],
        2 => [start, end, end],
        _ => [start, start, end],
    }
}

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

/// `x` moved by `ulps` representable steps (up when positive).
pub fn nudge(x: f64, ulps: i32) -> f64 {
    let mut y = x;
    for _ in 0..ulps.unsigned_abs() {
        y = if ulps > 0 { y.next_up() } else { y.next_down() };
    }
    y
}

fn unit_cube_point(rng: &mut ChaCha8Rng) -> Point {
    [rng.gen(), rng.gen(), rng.gen()]
}

fn unit_cube_triangle(rng: &mut ChaCha8Rng) -> Triangle {
    [
        unit_cube_point(rng),
        unit_cube_point(rng),
        unit_cube_point(rng),
    ]
}

/// Six coordinates-on-a-grid vertices: `k / cells` for `k` in `0..=cells`.
fn grid_snapped_pair(rng: &mut ChaCha8Rng, cells: f64) -> TrianglePair {
    let n = cells as i64;
    let mut p = || [0, 1, 2].map(|_| rng.gen_range(0..=n) as f64 / cells);
    TrianglePair::new([p(), p(), p()], [p(), p(), p()])
}

fn add3(a: Point, b: Point) -> Point {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

type LatticeVector = [i64; 3];

/// A segment `start .. start + 2 * half` on the lattice, as `(start, half)`.
type Segment = (LatticeVector, LatticeVector);

fn lattice_vector(rng: &mut ChaCha8Rng, radius: i64) -> LatticeVector {
    [0, 1, 2].map(|_| rng.gen_range(-radius..=radius))
}

fn nonzero_lattice_vector(rng: &mut ChaCha8Rng, radius: i64) -> LatticeVector {
    loop {
        let v = lattice_vector(rng, radius);
        if v != [0, 0, 0] {
            return v;
        }
    }
}

/// A lattice vector not parallel to `d`.
fn off_line_vector(rng: &mut ChaCha8Rng, d: LatticeVector, radius: i64) -> LatticeVector {
    loop {
        let v = lattice_vector(rng, radius);
        if lattice_cross(d, v) != [0, 0, 0] {
            return v;
        }
    }
}

fn lattice_add(a: LatticeVector, b: LatticeVector) -> LatticeVector {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn lattice_sub(a: LatticeVector, b: LatticeVector) -> LatticeVector {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn lattice_scale(a: LatticeVector, k: i64) -> LatticeVector {
    a.map(|c| c * k)
}

fn lattice_cross(u: LatticeVector, v: LatticeVector) -> LatticeVector {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

fn lattice_dot(u: LatticeVector, v: LatticeVector) -> i64 {
    u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
}

/// Integer coordinates to f64 (exact for these small integers), times
/// `scale` (exact when it is a power of two).
fn lattice_to_point(p: LatticeVector, scale: f64) -> Point {
    p.map(|c| c as f64 * scale)
}

/// The points `origin + i u + j v`: exactly on the plane through `origin`
/// with normal `u × v`.
struct LatticePlane {
    origin: LatticeVector,
    u: LatticeVector,
    v: LatticeVector,
}

impl LatticePlane {
    fn random(rng: &mut ChaCha8Rng, radius: i64, origin_radius: i64) -> Self {
        let origin = lattice_vector(rng, origin_radius);
        let u = nonzero_lattice_vector(rng, radius);
        let v = off_line_vector(rng, u, radius);
        LatticePlane { origin, u, v }
    }

    fn point(&self, i: i64, j: i64) -> LatticeVector {
        lattice_add(
            self.origin,
            lattice_add(lattice_scale(self.u, i), lattice_scale(self.v, j)),
        )
    }

    fn normal(&self) -> LatticeVector {
        lattice_cross(self.u, self.v)
    }

    /// A lattice vector on the positive side of the plane.
    fn off_plane_vector(&self, rng: &mut ChaCha8Rng, radius: i64) -> LatticeVector {
        loop {
            let w = lattice_vector(rng, radius);
            match lattice_dot(w, self.normal()) {
                0 => continue,
                d if d > 0 => return w,
                _ => return lattice_scale(w, -1),
            }
        }
    }
}

/// A random rotation (unit quaternion), uniform scale in [0.5, 4) and
/// translation in [-10, 10)^3, applied in f64 (rounded).
struct RigidMotion {
    rotation: [[f64; 3]; 3],
    scale: f64,
    translation: Point,
}

impl RigidMotion {
    fn random(rng: &mut ChaCha8Rng) -> Self {
        let q = loop {
            let q: [f64; 4] = [0, 1, 2, 3].map(|_| rng.gen_range(-1.0..1.0));
            let n2: f64 = q.iter().map(|x| x * x).sum();
            if n2 > 0.01 && n2 <= 1.0 {
                break q.map(|x| x / n2.sqrt());
            }
        };
        let [w, x, y, z] = q;
        let rotation = [
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - w * z),
                2.0 * (x * z + w * y),
            ],
            [
                2.0 * (x * y + w * z),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - w * x),
            ],
            [
                2.0 * (x * z - w * y),
                2.0 * (y * z + w * x),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ];
        RigidMotion {
            rotation,
            scale: rng.gen_range(0.5..4.0),
            translation: [0, 1, 2].map(|_| rng.gen_range(-10.0..10.0)),
        }
    }

    fn apply(&self, p: Point) -> Point {
        let m = &self.rotation;
        [0, 1, 2].map(|i| {
            self.scale * (m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2]) + self.translation[i]
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generators_are_deterministic_and_names_are_unique() {
        let a = hard_case_suite();
        let b = hard_case_suite();
        assert_eq!(a, b);
        let mut names: Vec<&str> = a.iter().map(|c| c.name.as_str()).collect();
        names.sort_unstable();
        let before = names.len();
        names.dedup();
        assert_eq!(before, names.len(), "case names must be unique");
    }

    #[test]
    fn nudge_moves_by_whole_ulps() {
        assert_eq!(nudge(1.0, 1), 1.0 + f64::EPSILON);
        assert_eq!(nudge(1.0, -2), 1.0 - f64::EPSILON);
        assert_eq!(nudge(0.0, 1), f64::from_bits(1));
        assert_eq!(nudge(3.0, 0), 3.0);
    }

    #[test]
    fn lattice_planes_are_exactly_coplanar() {
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        for _ in 0..100 {
            let plane = LatticePlane::random(&mut rng, 3, 5);
            let n = plane.normal();
            let d = lattice_dot(n, plane.origin);
            for (i, j) in [(0, 0), (3, -2), (-4, 7)] {
                assert_eq!(lattice_dot(n, plane.point(i, j)), d);
            }
        }
    }
}
