use super::load::{Pose, SceneObject};
use super::reference::{exact_f64_pairs, fixed_point_pairs, quantized_exact_pairs, PairSet};
use super::*;
use crate::{exact_f64, fixed_point};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn options(width: u32, depth: usize) -> SceneOptions {
    SceneOptions {
        grid_bits: width,
        depth,
        split: true,
    }
}

/// Random triangles around `centre`, some of them degenerate (segments,
/// points, zero-area), on a coarse grid so that touching happens often.
/// Non-degenerate triangles have edges up to `edge / 8 * spread` per axis.
fn random_object(
    rng: &mut ChaCha8Rng,
    n: usize,
    centre: [f64; 3],
    spread: f64,
    edge: i32,
) -> SceneObject {
    let point =
        |rng: &mut ChaCha8Rng| centre.map(|c| c + (rng.gen_range(-8i32..=8) as f64) * spread / 8.0);
    let triangles = (0..n)
        .map(|_| {
            let p = point(rng);
            match rng.gen_range(0..10) {
                0 => [p, p, p],
                1 => {
                    let q = point(rng);
                    [p, q, q]
                }
                2 => {
                    // three collinear points: zero area, not coincident
                    let q = point(rng);
                    [
                        p,
                        q,
                        [2.0 * q[0] - p[0], 2.0 * q[1] - p[1], 2.0 * q[2] - p[2]],
                    ]
                }
                _ => {
                    let small = |rng: &mut ChaCha8Rng, c: f64| {
                        c + rng.gen_range(-edge..=edge) as f64 * spread / 8.0
                    };
                    [p, p.map(|c| small(rng, c)), p.map(|c| small(rng, c))]
                }
            }
        })
        .collect();
    SceneObject::from_triangles("random", triangles)
}

fn brute_force(
    a: &[Triangle],
    b: &[Triangle],
    test: impl Fn(&Triangle, &Triangle) -> bool,
) -> PairSet {
    let mut out = PairSet::new();
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            if test(x, y) {
                out.insert((i as u32, j as u32));
            }
        }
    }
    out
}

/// Objects whose boxes do not meet: no common BV, no batch, zero pairs.
#[test]
fn no_overlap_gives_no_common_bv_and_zero_pairs() {
    let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let a = SceneObject::from_triangles("a", vec![t]);
    let b = a.posed(&Pose::translation([1.5, 0.0, 0.0]));
    let scene = prepare(&a, &b, &options(24, 16)).unwrap();
    assert_eq!(scene.common, None);
    assert!(scene.batches().is_empty() && scene.kept_a.is_empty() && scene.kept_b.is_empty());
    assert_eq!(scene.pairs_tested(), 0);
    assert_eq!(fixed_point_pairs(&scene.batches(), &|_| {}), PairSet::new());
    // An empty object has no box either.
    let empty = SceneObject::from_triangles("empty", vec![]);
    assert_eq!(
        prepare(&a, &empty, &options(24, 16))
            .unwrap()
            .pairs_tested(),
        0
    );
}

/// Boxes that only touch still give a (flat) common BV, and the touching
/// triangles are found.
#[test]
fn touching_boxes_give_a_flat_common_bv_and_the_touching_pair() {
    let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let a = SceneObject::from_triangles("a", vec![t]);
    let b = a.posed(&Pose::translation([1.0, 0.0, 0.0])); // shares the vertex (1,0,0)
    let scene = prepare(&a, &b, &options(24, 16)).unwrap();
    let common = scene.common.unwrap();
    assert_eq!(common.lo[0], common.hi[0]);
    assert_eq!(
        fixed_point_pairs(&scene.batches(), &|_| {}),
        PairSet::from([(0, 0)])
    );
    assert_eq!(
        exact_f64_pairs(&a.triangles, &b.triangles).pairs,
        PairSet::from([(0, 0)])
    );
}

/// Points, segments and zero-area triangles go through filtering,
/// quantization, tiling and both models without panic, and their verdicts
/// are the exact ones.
#[test]
fn degenerate_and_zero_area_triangles_survive_the_whole_flow() {
    let point = [[0.5, 0.5, 0.0]; 3];
    let segment = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
    let collinear = [[0.0, 1.0, 0.0], [0.5, 0.5, 0.0], [1.0, 0.0, 0.0]];
    let flat = [[-1.0, -1.0, 0.0], [2.0, -1.0, 0.0], [-1.0, 2.0, 0.0]];
    let a = SceneObject::from_triangles("a", vec![point, segment, collinear]);
    let b = SceneObject::from_triangles("b", vec![flat, point, segment]);
    let scene = prepare(&a, &b, &options(16, 2)).unwrap();
    assert_eq!(scene.kept_a.len(), 3);
    assert_eq!(scene.kept_b.len(), 3);
    assert!(scene.tiling.is_split());
    let expected = brute_force(&a.triangles, &b.triangles, exact_f64::intersects);
    assert_eq!(
        expected.len(),
        9,
        "every one of these degenerate pieces meets every other: {expected:?}"
    );
    assert_eq!(fixed_point_pairs(&scene.batches(), &|_| {}), expected);
    assert_eq!(quantized_exact_pairs(&scene.batches()), expected);
    assert_eq!(exact_f64_pairs(&a.triangles, &b.triangles).pairs, expected);
}

/// Tiles partition the pairs of the kept arrays: every pair lies in exactly
/// one batch, and the deduplicated pairs of the tiles are those of one
/// untiled batch.
#[test]
fn tiling_covers_every_pair_exactly_once() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let a = random_object(&mut rng, 37, [0.0; 3], 1.0, 6);
    let b = random_object(&mut rng, 23, [0.5, 0.0, 0.0], 1.0, 6);
    let untiled = prepare(&a, &b, &options(12, 1 << 20)).unwrap();
    assert_eq!(untiled.batches().len(), 1);
    for depth in [1, 2, 5, 7, 23, 36] {
        let tiled = prepare(&a, &b, &options(12, depth)).unwrap();
        assert_eq!(
            tiled.batches().len(),
            tiled.tiling.a_tiles * tiled.tiling.b_tiles
        );
        assert!(tiled
            .batches()
            .iter()
            .all(|batch| batch.a.len() <= depth && batch.b.len() <= depth));
        let mut seen = std::collections::HashMap::new();
        for batch in &tiled.batches() {
            for x in batch.a {
                for y in batch.b {
                    *seen.entry((x.id, y.id)).or_insert(0) += 1;
                }
            }
        }
        assert_eq!(seen.len() as u64, untiled.pairs_tested(), "depth {depth}");
        assert!(
            seen.values().all(|&n| n == 1),
            "depth {depth}: a pair is in two batches"
        );
        assert_eq!(tiled.pairs_tested(), untiled.pairs_tested());
        assert_eq!(
            fixed_point_pairs(&tiled.batches(), &|_| {}),
            fixed_point_pairs(&untiled.batches(), &|_| {})
        );
    }
}

/// Refusing to split names both array sizes and the depth.
#[test]
fn no_split_refuses_arrays_deeper_than_the_memory() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let a = random_object(&mut rng, 20, [0.0; 3], 1.0, 6);
    let b = random_object(&mut rng, 20, [0.2, 0.0, 0.0], 1.0, 6);
    let scene = prepare(&a, &b, &options(16, 1000)).unwrap();
    let (ka, kb) = (scene.kept_a.len(), scene.kept_b.len());
    let err = prepare(
        &a,
        &b,
        &SceneOptions {
            grid_bits: 16,
            depth: 4,
            split: false,
        },
    )
    .unwrap_err();
    assert_eq!(
        err,
        SceneError::ExceedsDepth {
            kept_a: ka,
            kept_b: kb,
            depth: 4,
            needed: ka.max(kb)
        }
    );
    let text = err.to_string();
    assert!(
        text.contains(&format!("{ka} (A)")) && text.contains("memory depth 4"),
        "{text}"
    );
}

/// The filters lose nothing, on random small scenes at coarse and fine
/// widths:
/// * every pair of quantized candidates that intersects (all pairs, no
///   integer filter) is found in the batches;
/// * every pair that intersects in f64 (all N1*N2 pairs, brute force) is a
///   pair of candidates of the f64 filter;
/// * the fixed-point model equals the exact model on the quantized
///   coordinates, and the f64 sweep equals brute force.
#[test]
fn filter_never_drops_an_intersecting_pair() {
    let mut rng = ChaCha8Rng::seed_from_u64(2005);
    for round in 0..40 {
        let width = [8, 10, 16, 24][round % 4];
        let edge = [2, 6][round / 4 % 2];
        let a = random_object(&mut rng, 30, [0.0; 3], 1.0, edge);
        let offset = [rng.gen_range(-2.0..2.0), rng.gen_range(-1.0..1.0), 0.0];
        let b = random_object(&mut rng, 30, offset, 1.0, edge);
        let b = b.posed(&Pose {
            translation: [0.0; 3],
            rotation_degrees: [rng.gen_range(0.0..360.0), 0.0, 0.0],
        });
        let scene = prepare(&a, &b, &options(width, 8)).unwrap();
        let found = fixed_point_pairs(&scene.batches(), &|_| {});
        assert_eq!(
            found,
            quantized_exact_pairs(&scene.batches()),
            "round {round}"
        );

        let truth = brute_force(&a.triangles, &b.triangles, exact_f64::intersects);
        assert_eq!(
            exact_f64_pairs(&a.triangles, &b.triangles).pairs,
            truth,
            "round {round}"
        );
        for &(i, j) in &truth {
            assert!(
                scene.candidates_a.contains(&i) && scene.candidates_b.contains(&j),
                "round {round}: f64 pair ({i},{j}) dropped"
            );
        }
        if let Some(frame) = scene.frame {
            for &i in &scene.candidates_a {
                for &j in &scene.candidates_b {
                    let (qa, qb) = (
                        frame.quantize(&a.triangles[i as usize]),
                        frame.quantize(&b.triangles[j as usize]),
                    );
                    if fixed_point::intersects(&qa, &qb) {
                        assert!(
                            found.contains(&(i, j)),
                            "round {round}: quantized pair ({i},{j}) dropped by the integer filter"
                        );
                    }
                }
            }
        }
    }
}

/// The default scene: the common BV cuts the work, and the 24-bit answer is
/// close to the exact one.
#[test]
fn default_scene_filter_saves_pairs_and_keeps_every_hit() {
    let (a, b) = crate::builtin_scene::default_scene();
    let (a, b) = (
        SceneObject::from_triangles("@torus", a),
        SceneObject::from_triangles("@sphere", b),
    );
    let scene = prepare(&a, &b, &options(24, 4096)).unwrap();
    assert!(
        scene.pairs_tested() * 4 < scene.all_pairs(),
        "{} of {}",
        scene.pairs_tested(),
        scene.all_pairs()
    );
    let quantized = fixed_point_pairs(&scene.batches(), &|_| {});
    let truth = exact_f64_pairs(&a.triangles, &b.triangles).pairs;
    assert!(truth.len() > 10);
    let diff = reference::PairDiff::between(&truth, &quantized);
    assert!(
        diff.missing.len() + diff.extra.len() <= truth.len() / 20,
        "{diff:?}"
    );
}

/// The system's batch cost with overlapped banks (a copy for these tests;
/// the real one is the hardware crate's cycle model).
struct OverlappedCycles {
    pipelines: usize,
}

impl octree::BatchCost for OverlappedCycles {
    fn batch_cycles(&self, a: usize, b: usize) -> u64 {
        ((a + b + 1) as u64).max((1 + a + a.div_ceil(self.pipelines) * b) as u64)
    }
}

/// [`OverlappedCycles`] with a binning unit that classifies a cell of `a`
/// and `b` entries in `max(a, b) + 6` clocks (like the hardware crate's
/// model, with one classifier per object).
struct WithBinning(OverlappedCycles);

impl octree::BatchCost for WithBinning {
    fn batch_cycles(&self, a: usize, b: usize) -> u64 {
        self.0.batch_cycles(a, b)
    }
    fn classify_cycles(&self, a: usize, b: usize) -> u64 {
        a.max(b) as u64 + 6
    }
}

/// Every intersecting pair of `a × b` (integer triangles), brute force.
fn brute_force_fixed(a: &[TaggedTriangle], b: &[TaggedTriangle]) -> PairSet {
    let mut out = PairSet::new();
    for x in a {
        for y in b {
            if fixed_point::intersects(&x.triangle, &y.triangle) {
                out.insert((x.id, y.id));
            }
        }
    }
    out
}

/// The owner rule: every pair found is owned by exactly one leaf, the first
/// that holds both triangles, and reporting each leaf's hits only where it
/// owns them gives every pair once.
fn assert_each_pair_reported_once(
    schedule: &octree::OctreeSchedule,
    expected: &PairSet,
    context: &str,
) {
    assert_slots_decide_as_the_owner_rule(schedule, context);
    let mut reported = Vec::new();
    for (k, leaf) in schedule.leaves.iter().enumerate() {
        let (la, lb) = schedule.leaf_arrays(leaf);
        for x in la {
            for y in lb {
                if fixed_point::intersects(&x.triangle, &y.triangle) {
                    let owner = schedule
                        .owner(x.id, y.id)
                        .expect("a pair tested in a leaf has an owner");
                    assert!(
                        owner <= k,
                        "{context}: owner {owner} after a leaf {k} holding both"
                    );
                    if owner == k {
                        reported.push((x.id, y.id));
                    }
                }
            }
        }
    }
    let unique: PairSet = reported.iter().copied().collect();
    assert_eq!(
        unique.len(),
        reported.len(),
        "{context}: a pair reported twice"
    );
    assert_eq!(&unique, expected, "{context}");
}

/// The hardware's form of the owner rule (`owner_slots`): for every pair of
/// every leaf, intersecting or not, the slots' merge says "owner" exactly
/// when the leaf is the first holding both triangles, within the bound on
/// comparisons the hardware's cycle model relies on.
fn assert_slots_decide_as_the_owner_rule(schedule: &octree::OctreeSchedule, context: &str) {
    let slots = owner_slots::OwnerSlots::of(schedule);
    assert_eq!(
        slots.a.len(),
        schedule.a.len(),
        "{context}: one slot per entry"
    );
    for (k, leaf) in schedule.leaves.iter().enumerate() {
        for i in leaf.a.clone() {
            for j in leaf.b.clone() {
                let (sa, sb) = (slots.a_slot[i], slots.b_slot[j]);
                let (x, y) = (slots.a[sa as usize], slots.b[sb as usize]);
                assert_eq!(
                    (x.id, y.id, x.leaf, y.leaf),
                    (schedule.a[i].id, schedule.b[j].id, k as u32, k as u32),
                    "{context}"
                );
                let decision = slots.decide(sa, sb);
                let owner = schedule.owner(x.id, y.id) == Some(k);
                assert_eq!(
                    decision.owner, owner,
                    "{context}: leaf {k}, pair ({}, {})",
                    x.id, y.id
                );
                assert!(
                    decision.comparisons <= (sa - x.first) + (sb - y.first) + 1,
                    "{context}"
                );
            }
        }
    }
}

/// The octree broad phase finds exactly the flat system's pairs (the exact
/// model on the same quantized coordinates), each reported once, on random
/// scenes full of degenerate and touching triangles, at several widths and
/// with small memories so that the tree must split.
#[test]
fn octree_finds_the_flat_pairs_each_once() {
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    let (mut split_scenes, mut fewer_cells) = (0, 0);
    for round in 0..40 {
        let width = [8, 10, 16, 24][round % 4];
        let edge = [1, 2, 6][round % 3];
        let a = random_object(&mut rng, 120, [0.0; 3], 1.0, edge);
        let offset = [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), 0.0];
        let b = random_object(&mut rng, 120, offset, 1.0, edge);
        let depth = [4, 16, 64][round % 3];
        let flat = prepare(&a, &b, &options(width, depth)).unwrap();
        let tree = prepare_octree(
            &a,
            &b,
            &options(width, depth),
            &OverlappedCycles { pipelines: 2 },
            None,
        )
        .unwrap();
        let expected = fixed_point_pairs(&flat.batches(), &|_| {});
        assert_eq!(
            fixed_point_pairs(&tree.batches(), &|_| {}),
            expected,
            "round {round}"
        );
        assert_eq!(
            quantized_exact_pairs(&tree.batches()),
            expected,
            "round {round}"
        );
        let schedule = tree.octree.as_ref().expect("octree scheduled");
        assert_each_pair_reported_once(schedule, &expected, &format!("round {round}"));
        assert!(tree
            .batches()
            .iter()
            .all(|b| b.a.len() <= depth && b.b.len() <= depth));
        split_scenes += (schedule.tree_depth > 0) as usize;
        // Charging the binning unit's classifications: the same pairs, each
        // once, from no more cells, and the cycles of those charged.
        let binned = prepare_octree(
            &a,
            &b,
            &options(width, depth),
            &WithBinning(OverlappedCycles { pipelines: 2 }),
            None,
        )
        .unwrap();
        assert_eq!(
            fixed_point_pairs(&binned.batches(), &|_| {}),
            expected,
            "round {round}, binning charged"
        );
        let binned_schedule = binned.octree.as_ref().expect("octree scheduled");
        assert_each_pair_reported_once(
            binned_schedule,
            &expected,
            &format!("round {round}, binning charged"),
        );
        assert!(
            binned_schedule.cells_visited <= schedule.cells_visited,
            "round {round}"
        );
        fewer_cells += (binned_schedule.cells_visited < schedule.cells_visited) as usize;
        assert_eq!(schedule.classify_cycles, 0);
        assert!(
            binned_schedule.classify_cycles >= binned_schedule.cells_visited * 6,
            "round {round}"
        );
    }
    assert!(split_scenes > 30, "only {split_scenes} scenes split");
    assert!(
        fewer_cells > 10,
        "charging classification cut cells in only {fewer_cells} scenes"
    );
}

/// Triangles lying exactly on cell faces, along cell edges and at cell
/// corners of every level (coordinates on multiples of powers of two),
/// touching each other there: the schedule finds the brute-force pairs,
/// each once.
#[test]
fn octree_pairs_straddling_cell_faces_edges_and_corners() {
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    for round in 0..30 {
        let level = [2u32, 4, 6][round % 3];
        let side = 1i64 << level;
        // Points on the lattice of cell corners of the levels below, so
        // faces, edges and corners of many cells are hit exactly.
        let lattice = |rng: &mut ChaCha8Rng| {
            let step = 1i64 << rng.gen_range(0..level);
            [0; 3].map(|_: i64| rng.gen_range(0..=side / step) * step)
        };
        let object = |rng: &mut ChaCha8Rng, base: u32| -> Vec<TaggedTriangle> {
            (0..60)
                .map(|i| {
                    let p = lattice(rng);
                    let (q, r) = match rng.gen_range(0..4) {
                        // a face-aligned triangle: one coordinate shared by all three
                        0 => {
                            let k = rng.gen_range(0..3);
                            let (mut q, mut r) = (lattice(rng), lattice(rng));
                            q[k] = p[k];
                            r[k] = p[k];
                            (q, r)
                        }
                        1 => (p, p),
                        2 => (lattice(rng), lattice(rng)),
                        _ => {
                            let q = lattice(rng);
                            (q, q)
                        }
                    };
                    TaggedTriangle {
                        id: base + i,
                        triangle: [p, q, r],
                    }
                })
                .collect()
        };
        let (a, b) = (object(&mut rng, 0), object(&mut rng, 0));
        let root = Aabb {
            lo: [0; 3],
            hi: [side; 3],
        };
        let expected = brute_force_fixed(&a, &b);
        for depth in [2, 8] {
            let schedule = octree::schedule(
                &a,
                &b,
                &root,
                depth,
                &OverlappedCycles { pipelines: 1 },
                None,
            );
            assert_each_pair_reported_once(
                &schedule,
                &expected,
                &format!("round {round}, depth {depth}"),
            );
        }
    }
}

/// Many coplanar triangles overlapping over an area stay together in every
/// cell around them however deep the tree goes: the planner must stop
/// (tiling the leaf) instead of multiplying cells, and stay exact.
#[test]
fn octree_stops_on_coplanar_overlaps_deeper_than_the_memory() {
    let big = 1i64 << 22;
    let object = |shift: i64| -> Vec<TaggedTriangle> {
        (0..12)
            .map(|i| TaggedTriangle {
                id: i as u32,
                triangle: [[-big + shift * i, -big, 0], [big, -big + i, 0], [0, big, 0]],
            })
            .collect()
    };
    let (a, b) = (object(3), object(-5));
    let root = Aabb {
        lo: [-big; 3],
        hi: [big; 3],
    };
    let schedule = octree::schedule(&a, &b, &root, 2, &OverlappedCycles { pipelines: 2 }, None);
    assert!(
        schedule.cells_visited < 10_000,
        "{} cells",
        schedule.cells_visited
    );
    assert_each_pair_reported_once(&schedule, &brute_force_fixed(&a, &b), "coplanar");
}

/// Small triangles (up to 0.02 across, some degenerate) and a few long ones
/// (up to 0.3) in the thin slab [-0.3, 0.3]^2 x [-0.01, 0.01], where they
/// meet often.
fn slab_object(rng: &mut ChaCha8Rng, n: usize) -> SceneObject {
    let triangles = (0..n)
        .map(|i| {
            let p = [
                rng.gen_range(-0.3..0.3),
                rng.gen_range(-0.3..0.3),
                rng.gen_range(-0.01..0.01),
            ];
            let size = if i % 20 == 0 { 0.3 } else { 0.02 };
            let mut near = || {
                [0, 1, 2]
                    .map(|k| p[k] + rng.gen_range(-size..size) / if k == 2 { 4.0 } else { 2.0 })
            };
            match i % 10 {
                0 => [p, p, p],
                1 => [p, near(), p],
                _ => [p, near(), near()],
            }
        })
        .collect();
    SceneObject::from_triangles("slab", triangles)
}

/// Local frames: the scene on a G-bit grid, leaves sent as W-bit
/// coordinates around their centres, long triangles' pairs to the host.
/// The union of leaf hits and host hits is the flat system's answer on the
/// same G-bit grid, every batch coordinate fits W bits, and translation
/// leaves the verdicts alone. A grid 24 bits finer than W (every triangle
/// too long for a window) goes to the host without splitting cells.
#[test]
fn local_frames_keep_the_grid_answer_with_fewer_bits() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let (mut hosted, mut sent, mut hits) = (0, 0, 0);
    for round in 0..24 {
        let (grid, width) = [(16, 12), (20, 16), (24, 20), (12, 8), (32, 8)][round % 5];
        let (a, b) = (slab_object(&mut rng, 1500), slab_object(&mut rng, 1500));
        let flat = prepare(&a, &b, &options(grid, 32)).unwrap();
        let local = Some(octree::LocalFrames { width });
        let tree = prepare_octree(
            &a,
            &b,
            &options(grid, 32),
            &OverlappedCycles { pipelines: 2 },
            local,
        )
        .unwrap();
        let mut found = fixed_point_pairs(&tree.batches(), &|_| {});
        found.extend(fixed_point_pairs(&tree.host_batches(), &|_| {}));
        assert_eq!(
            found,
            fixed_point_pairs(&flat.batches(), &|_| {}),
            "round {round}"
        );
        hits += found.len();
        let half = 1i64 << (width - 1);
        for batch in tree.batches() {
            assert!(
                batch.a.iter().chain(batch.b).all(|t| t
                    .triangle
                    .iter()
                    .flatten()
                    .all(|c| (-half..half).contains(c))),
                "round {round}"
            );
        }
        let schedule = tree.octree.as_ref().unwrap();
        assert!(schedule.leaves.iter().all(|l| l.cell.level <= width - 2));
        assert!(
            schedule.cells_visited < 100_000,
            "round {round}: {} cells",
            schedule.cells_visited
        );
        hosted += tree.host_pairs();
        sent += tree.pairs_tested();
    }
    // Both routes are exercised.
    assert!(
        hosted > 0 && sent > 0 && hits > 300,
        "host {hosted}, hardware {sent}, intersecting {hits}"
    );
}

/// The host's preparation as it was written before it fused its passes:
/// the frame fitted over the candidates, every candidate quantized, the
/// integer box from the quantized candidates, then the kept ones.
fn prepare_in_passes(
    a: &SceneObject,
    b: &SceneObject,
    grid_bits: u32,
) -> (
    Frame,
    Option<Aabb<i64>>,
    Vec<TaggedTriangle>,
    Vec<TaggedTriangle>,
) {
    let scene = prepare(a, b, &options(grid_bits, 64)).unwrap();
    let candidates = |ids: &[u32], ts: &[Triangle]| -> Vec<Triangle> {
        ids.iter().map(|&i| ts[i as usize]).collect()
    };
    let (ca, cb) = (
        candidates(&scene.candidates_a, &a.triangles),
        candidates(&scene.candidates_b, &b.triangles),
    );
    let frame = Frame::fit(ca.iter().chain(&cb), grid_bits).unwrap();
    let quantize = |ids: &[u32], ts: &[Triangle]| -> Vec<TaggedTriangle> {
        ids.iter()
            .map(|&id| TaggedTriangle {
                id,
                triangle: frame.quantize(&ts[id as usize]),
            })
            .collect()
    };
    let qa = quantize(&scene.candidates_a, &a.triangles);
    let qb = quantize(&scene.candidates_b, &b.triangles);
    let margin = BROAD_PHASE_MARGIN as i64;
    let ibox = match (
        Aabb::of_triangles(qa.iter().map(|t| &t.triangle)),
        Aabb::of_triangles(qb.iter().map(|t| &t.triangle)),
    ) {
        (Some(x), Some(y)) => x.grown(margin).overlap(&y.grown(margin)),
        _ => None,
    };
    let keep = |q: Vec<TaggedTriangle>| -> Vec<TaggedTriangle> {
        match ibox {
            Some(ibox) => q
                .into_iter()
                .filter(|t| grown_triangle_touches_box(&t.triangle, BROAD_PHASE_MARGIN, &ibox))
                .collect(),
            None => Vec::new(),
        }
    };
    (frame, ibox, keep(qa), keep(qb))
}

/// `prepare`'s one pass (the integer box from the candidates' f64 bounds
/// quantized, each candidate kept as it is quantized) gives the frame, the
/// integer box and the kept arrays of the passes it replaced, on random
/// scenes at every grid width, apart, touching and overlapping.
#[test]
fn the_fused_preparation_is_the_passes_it_replaced() {
    let mut rng = ChaCha8Rng::seed_from_u64(61);
    for round in 0..300 {
        let spread = 10f64.powi(rng.gen_range(-3..=3));
        let offset = [0; 3].map(|_| rng.gen_range(-1.5..1.5) * spread);
        let a = random_object(&mut rng, 60, [0.0; 3], spread, 3);
        let b = random_object(&mut rng, 60, offset, spread, 3);
        let grid_bits = rng.gen_range(8..=32);
        let scene = prepare(&a, &b, &options(grid_bits, 64)).unwrap();
        let (frame, ibox, kept_a, kept_b) = prepare_in_passes(&a, &b, grid_bits);
        let context = format!("round {round}, G = {grid_bits}");
        assert_eq!(scene.frame, Some(frame), "{context}");
        assert_eq!(scene.integer_box, ibox, "{context}");
        assert_eq!(scene.kept_a, kept_a, "{context}");
        assert_eq!(scene.kept_b, kept_b, "{context}");
    }
}
