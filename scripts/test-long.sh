#!/usr/bin/env bash
# The long runs the test command leaves out to stay within CI's hour
# (scripts/test.sh): the rust-hdl pipeline on the whole hard-case suite
# (340,128 pairs per width) and 100,000 random pairs per width, the shared
# rare-case unit on every rare pair of the suite in three engines, and
# Yosys' formal equivalence and synth_xilinx figures at W = 24 as well as
# W = 8. About 25 minutes on 2 cores after a warm build.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export TRITRI_LONG=1 TRITRI_HARD_CASES=1 TRITRI_PAIRS=100000
cargo test --release --workspace --test rusthdl_pipeline --test shared_rare_cases --test emit_pipeline -- --nocapture
