//! The software baseline is CGAL's answer: on the built-in torus and
//! sphere in contact, CGAL's `box_intersection_d` with `do_intersect`
//! (exact predicates) finds the same pairs as the project's exact software
//! path on one and two threads, after deciding the same box-overlapping
//! pairs. (The times are compared in `examples/software_baseline`, never
//! in a test.)

use tritri_cosim::cgal::cgal_pairs;
use tritri_geom::builtin_scene::{sphere, torus};
use tritri_geom::scene::reference::{exact_f64_pairs, exact_f64_pairs_threads};

#[test]
fn cgal_and_the_software_path_find_the_same_pairs() {
    let a = torus([0.0, 0.0, 0.0], 1.0, 0.35, 48, 24);
    let b = sphere([1.0, 0.0, 0.55], 0.4, 32, 16);
    let ours = exact_f64_pairs(&a, &b);
    let cgal = cgal_pairs(&a, &b, 2).unwrap();
    assert!(ours.pairs.len() > 50, "{} pairs", ours.pairs.len());
    assert_eq!(cgal.pairs, ours.pairs);
    assert_eq!(cgal.box_pairs, ours.pairs_decided);
    assert_eq!(cgal.times.len(), 2);
    assert_eq!(exact_f64_pairs_threads(&a, &b, 2), ours);
}
