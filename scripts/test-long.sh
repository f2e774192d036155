#!/usr/bin/env bash
# The long runs the test command leaves out to stay within CI's hour
# (scripts/test.sh): the rust-hdl pipeline on the whole hard-case suite
# (340,128 pairs per width) and 100,000 random pairs per width, the shared
# rare-case unit on every rare pair of the suite in three engines, and
# Yosys' formal equivalence and synth_xilinx figures at W = 24 as well as
# W = 8, and the broad-phase accelerator with its scene in DRAM on two of
# CGAL's meshes in Verilator. About 30 minutes on 2 cores after a warm
# build.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export TRITRI_LONG=1 TRITRI_HARD_CASES=1 TRITRI_PAIRS=100000
cargo test --release --workspace --test rusthdl_pipeline --test shared_rare_cases --test emit_pipeline -- --nocapture

# The broad-phase accelerator with its scene in DRAM (the design that fits the ECP5-85),
# in Verilator against the memory model, on two of CGAL's meshes in
# contact: the pairs must be the exact answer on the grid, each once, with
# an ideal memory and one that stalls (examples/dram_broad_phase.rs), on
# its 64-bit port and on its 256-bit one. About 6 minutes.
bash scripts/fetch-meshes.sh
cargo build --release --workspace --examples
for bits in 64 256; do
    target/release/examples/dram_broad_phase --data-bits $bits build/meshes/camel.off build/meshes/elephant.off 1 0.3 0 0
    target/release/examples/dram_broad_phase --data-bits $bits build/meshes/armadillo.off build/meshes/camel.off 127 55 0 0
done

# How it grows: camel × elephant at 1, 4 and 16 times its triangles and
# at 1.25 M × 1.42 M, in the top's clock-exact model (docs/axi-port.md,
# "Scaling"). About a minute.
target/release/examples/dram_scaling build/meshes/camel.off build/meshes/elephant.off 1 0.3 0 0
