//! The leaf cost's Verilog (`broad_phase::leaf_cost::leaf_cost_verilog`), run in
//! Icarus, equals the closed form `leaf_cost` on the ends of its ranges
//! (counts 0, 1, around the depth and its multiples, up to 2^20 - 1) and on
//! random counts, for depths 1 to 2^16 and 1 to 16 pipelines: its
//! registers are cut to their largest values, so a width too narrow shows
//! here.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fmt::Write as _;
use tritri_rtl::broad_phase::leaf_cost::{
    leaf_cost, leaf_cost_verilog, COST_BITS, COUNT_BITS, LEAF_COST_LATENCY,
};
use tritri_rtl::tools::{run, IVERILOG, VVP};

fn counts(log_depth: u32, rng: &mut ChaCha8Rng) -> Vec<u64> {
    let max = (1u64 << COUNT_BITS) - 1;
    let depth = 1u64 << log_depth;
    let mut out = vec![
        0,
        1,
        2,
        max,
        max - 1,
        depth - 1,
        depth,
        depth + 1,
        2 * depth - 1,
    ];
    out.extend((0..12).map(|_| rng.gen_range(0..=max)));
    out.retain(|&c| c <= max);
    out
}

#[test]
fn the_verilog_equals_the_closed_form_at_the_ends_of_its_ranges() {
    let dir = std::env::temp_dir().join(format!("tritri-leaf-cost-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for (ld, lp) in [
        (0, 0),
        (1, 1),
        (4, 2),
        (8, 1),
        (8, 4),
        (12, 0),
        (16, 3),
        (16, 4),
    ] {
        let values = counts(ld, &mut rng);
        let pairs: Vec<(u64, u64)> = values
            .iter()
            .flat_map(|&a| values.iter().map(move |&b| (a, b)))
            .collect();
        let mut tb = format!(
            "module leaf_cost_dut(input clock, input [{c1}:0] a, input [{c1}:0] b, output reg [{k1}:0] cost);\n{}\nendmodule\n",
            leaf_cost_verilog(ld, lp),
            c1 = COUNT_BITS - 1,
            k1 = COST_BITS - 1
        );
        tb.push_str(&format!(
            "module tb;\nreg clock = 0;\nreg [{c1}:0] a = 0, b = 0;\nwire [{k1}:0] cost;\n\
             leaf_cost_dut dut(.clock(clock), .a(a), .b(b), .cost(cost));\ninitial begin\n",
            c1 = COUNT_BITS - 1,
            k1 = COST_BITS - 1
        ));
        // A query a clock; the cost of the query `LATENCY` clocks back is
        // printed in each clock.
        for (a, b) in pairs
            .iter()
            .chain(std::iter::repeat_n(&(0, 0), LEAF_COST_LATENCY))
        {
            let _ = writeln!(
                tb,
                "a = {a}; b = {b}; #1 clock = 1; #1 clock = 0; $display(\"%0d\", cost);"
            );
        }
        tb.push_str("$finish;\nend\nendmodule\n");
        let source = dir.join(format!("tb_{ld}_{lp}.v"));
        let binary = dir.join(format!("tb_{ld}_{lp}.vvp"));
        std::fs::write(&source, tb).unwrap();
        run(IVERILOG
            .command()
            .unwrap()
            .args(["-g2012", "-o"])
            .arg(&binary)
            .arg(&source))
        .unwrap();
        let output = run(VVP.command().unwrap().arg(&binary)).unwrap();
        let printed: Vec<u64> = String::from_utf8_lossy(&output.stdout)
            .lines()
            .filter_map(|l| l.trim().parse().ok())
            .collect();
        // After the edge of query i, the output holds query i + 1 - LATENCY.
        let got = &printed[LEAF_COST_LATENCY - 1..];
        assert!(got.len() >= pairs.len(), "{} costs printed", printed.len());
        for (i, &(a, b)) in pairs.iter().enumerate() {
            assert_eq!(
                got[i],
                leaf_cost(a, b, ld, lp),
                "a {a} b {b} D 2^{ld} P 2^{lp}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
