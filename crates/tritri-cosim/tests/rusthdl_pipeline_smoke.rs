use tritri_cosim::rusthdl_harness::run_pairs;
use tritri_geom::fixed_point::intersects;

#[test]
fn smoke() {
    let t = [[0, 0, 0], [100, 0, 0], [0, 100, 0]];
    let s = [[10, 10, -5], [10, 10, 5], [20, 30, 5]];
    let far = [[10, 10, 5], [10, 10, 6], [20, 30, 5]];
    let t0 = std::time::Instant::now();
    let r = run_pairs(24, &[(7, t), (8, s)], &[(9, s), (10, far), (11, t)]).unwrap();
    eprintln!("{:?} in {:?}", r, t0.elapsed());
    let expect: Vec<_> = [(7, t), (8, s)]
        .iter()
        .flat_map(|&(b, bt)| [(9, s), (10, far), (11, t)].map(|(i, st)| (b, i, intersects(&bt, &st))))
        .collect();
    assert_eq!(r.pairs, expect);
}
