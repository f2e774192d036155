//! Certified verdicts (`tritri_geom::certificate`) are the exact verdicts on
//! the original coordinates: on the hard-case suite in all 72 orderings,
//! each category quantized into one frame as `tritri classify` does, at
//! W = 8, 12, 16 and 24, no certain grid verdict differs from exact f64.
//! (Uncertain verdicts are decided again with exact predicates, so the
//! certified answer is exact exactly when this holds.)

use std::collections::BTreeMap;
use tritri_geom::certificate::certified_intersects;
use tritri_geom::exact_f64;
use tritri_geom::hard_cases::hard_case_suite;
use tritri_geom::quantize::Frame;
use tritri_geom::triangle::all_orderings;
use tritri_geom::TrianglePair;

#[test]
fn certain_verdicts_are_exact_on_the_hard_case_suite_in_all_orderings() {
    let mut by_category: BTreeMap<String, Vec<TrianglePair>> = BTreeMap::new();
    for case in hard_case_suite() {
        let category = case.name.split(['/', '#']).next().unwrap_or("").to_string();
        by_category
            .entry(category)
            .or_default()
            .extend(all_orderings(&case.pair));
    }
    for width in [8, 12, 16, 24] {
        let (mut pairs, mut certain, mut grid_wrong) = (0, 0, 0);
        for (category, batch) in &by_category {
            let frame = Frame::fit(batch.iter().flat_map(|p| [&p.t1, &p.t2]), width).unwrap();
            for pair in batch {
                let v = certified_intersects(&frame.quantize(&pair.t1), &frame.quantize(&pair.t2));
                let exact = exact_f64::intersects(&pair.t1, &pair.t2);
                pairs += 1;
                grid_wrong += (v.hit != exact) as usize;
                if v.certain {
                    certain += 1;
                    assert_eq!(
                        v.hit, exact,
                        "W = {width}, {category}: a certain verdict is wrong: {pair:?}"
                    );
                }
            }
        }
        eprintln!("W = {width}: {pairs} pairs, {grid_wrong} grid verdicts wrong, {certain} certain (all right)");
        assert!(
            grid_wrong > 0,
            "W = {width}: the suite should trip the grid"
        );
    }
}
