//! The shared rare-case unit (`tritri_rtl::pipeline::shared_rare_cases`)
//! on the hard-case suite's rare pairs (coplanar, a segment in the other's
//! plane, two segments) at W = 16, in all orderings (every
//! `suites::hard_case_step()`-th case; `scripts/test-long.sh` takes all): the rust-hdl model
//! gives the models' verdicts, and Icarus and Verilator run the emitted
//! unit to the same verdicts at the same edges.

use tritri_cosim::shared_rare_cases::{run_emitted, run_rusthdl, RareJob};
use tritri_cosim::simulator::Simulator;
use tritri_cosim::suites::{hard_case_groups, hard_case_step};

fn jobs() -> Vec<RareJob> {
    hard_case_groups(16, hard_case_step())
        .iter()
        .flat_map(|(base, streamed)| {
            streamed
                .iter()
                .filter_map(|t2| RareJob::of(*base, *t2))
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn shared_rare_cases_in_every_engine() {
    let jobs = jobs();
    let coplanar = jobs.iter().filter(|j| !j.segments).count();
    let hits = jobs.iter().filter(|j| j.expected()).count();
    assert!(
        coplanar > 100 && jobs.len() - coplanar > 100 && hits > 100 && jobs.len() - hits > 100,
        "{} jobs: {coplanar} coplanar, {hits} hits",
        jobs.len()
    );
    let model = run_rusthdl(&jobs);
    let verdicts: Vec<bool> = model.verdicts.iter().map(|v| v.1).collect();
    let expected: Vec<bool> = jobs.iter().map(RareJob::expected).collect();
    assert_eq!(verdicts, expected, "rust-hdl against the models");
    for simulator in [Simulator::Icarus, Simulator::Verilator] {
        let run = run_emitted(&jobs, simulator).unwrap();
        assert_eq!(run, model, "{simulator:?} against rust-hdl");
    }
    eprintln!(
        "{} jobs ({coplanar} coplanar, {} segment pairs, {hits} hits) in {} clocks",
        jobs.len(),
        jobs.len() - coplanar,
        model.verdicts.last().unwrap().0
    );
}
