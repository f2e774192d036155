//! The octree engine's triangle–cell classifier against an independent
//! oracle: a closed triangle meets a closed box iff it meets one of the 12
//! triangles of the box's surface or has a vertex inside the box (a convex
//! set meeting a box either crosses its boundary or lies inside it). The
//! surface test is the rational separating-axis oracle of `oracle/`, which
//! shares no code with the classifier.

mod oracle;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_geom::bounding_volume::Aabb;
use tritri_geom::fixed_point::FixedTriangle;
use tritri_geom::octree::cell::Cell;
use tritri_geom::octree::triangle_cell::TriangleCellTest;

fn oracle_touches(t: &FixedTriangle, b: &Aabb<i64>) -> bool {
    let inside = |p: &[i64; 3]| (0..3).all(|k| b.lo[k] <= p[k] && p[k] <= b.hi[k]);
    if t.iter().any(inside) {
        return true;
    }
    let corner = |o: usize| [0, 1, 2].map(|k| if o >> k & 1 == 1 { b.hi[k] } else { b.lo[k] } as f64);
    let tf = t.map(|p| p.map(|c| c as f64));
    // Each face of the box as two triangles: the four corners with bit k fixed.
    for k in 0..3 {
        for side in 0..2 {
            let corners: Vec<usize> = (0..8).filter(|o| o >> k & 1 == side).collect();
            // corners in the face, ordered around it: 0, 1, 3, 2 of the two free bits.
            let quad = [corners[0], corners[1], corners[3], corners[2]].map(corner);
            if oracle::intersects(&tf, &[quad[0], quad[1], quad[2]]) || oracle::intersects(&tf, &[quad[0], quad[2], quad[3]]) {
                return true;
            }
        }
    }
    false
}

/// Random triangles (segments and points among them) on a small grid
/// against every cell of a three-level octree, by interpolation and
/// directly: 0 disagreements with the oracle.
#[test]
fn classifier_equals_the_oracle_on_every_cell_of_small_octrees() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let root = Cell { lo: [0, 0, 0], level: 3 };
    let mut checked = 0u64;
    let mut touching = 0u64;
    for _ in 0..400 {
        let point = |rng: &mut ChaCha8Rng| [0; 3].map(|_: i64| rng.gen_range(-1..=9));
        let p = point(&mut rng);
        let t = match rng.gen_range(0..6) {
            0 => [p, p, p],
            1 => [p, point(&mut rng), p],
            _ => [p, point(&mut rng), point(&mut rng)],
        };
        let test = TriangleCellTest::new(&t);
        // Walk the tree by interpolation; compare every cell with the oracle.
        let mut stack = vec![(root, test.values(&root))];
        while let Some((cell, values)) = stack.pop() {
            let expected = oracle_touches(&t, &cell.as_box());
            assert_eq!(test.touches(&values), expected, "{t:?} in {cell:?}");
            assert_eq!(test.touches_box(&cell.as_box()), expected, "{t:?} in {cell:?} (direct)");
            checked += 1;
            touching += expected as u64;
            if cell.splittable() {
                let mask = test.children_touched(&values);
                for o in 0..8 {
                    let child = test.child(&values, o);
                    assert_eq!(mask >> o & 1 == 1, test.touches(&child));
                    stack.push((cell.child(o), child));
                }
            }
        }
    }
    assert_eq!(checked, 400 * (1 + 8 + 64 + 512));
    assert!(touching > checked / 20 && touching < checked / 2, "{touching} of {checked}");
}
