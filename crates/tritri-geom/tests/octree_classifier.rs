//! The octree engine's triangle–cell classifier against an independent
//! oracle, `oracle::triangle_touches_box`, which shares no code with the
//! classifier.

mod oracle;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tritri_geom::octree::cell::Cell;
use tritri_geom::octree::triangle_cell::TriangleCellTest;

/// Random triangles (segments and points among them) on a small grid
/// against every cell of a three-level octree, by interpolation and
/// directly: 0 disagreements with the oracle.
#[test]
fn classifier_equals_the_oracle_on_every_cell_of_small_octrees() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let root = Cell {
        lo: [0, 0, 0],
        level: 3,
    };
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
            let expected = oracle::triangle_touches_box(&t, &cell.as_box());
            assert_eq!(test.touches(&values), expected, "{t:?} in {cell:?}");
            assert_eq!(
                test.touches_box(&cell.as_box()),
                expected,
                "{t:?} in {cell:?} (direct)"
            );
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
    assert!(
        touching > checked / 20 && touching < checked / 2,
        "{touching} of {checked}"
    );
}
