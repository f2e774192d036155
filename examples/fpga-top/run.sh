#!/usr/bin/env bash
# Generates the system examples/fpga-top is built around, then runs the top's
# FuseSoC targets: lint (Verilator -Wall), sim (Icarus, the self-checking
# tb/tb_fpga_top.sv) and synth (Yosys, Xilinx 7-series), and prints the
# resources. Fails if any of them fails or the test bench does not print PASS.
#
#   bash examples/fpga-top/run.sh          # after bash scripts/setup.sh
set -euo pipefail
cd "$(dirname "$0")"
root=$(cd ../.. && pwd)
out=$root/build/examples/fpga-top
fusesoc=$root/build/venv/bin/fusesoc
[ -x "$fusesoc" ] || { echo "error: $fusesoc not found; run bash scripts/setup.sh first" >&2; exit 1; }

# The configuration tritri_fpga_top.v and tritri_fpga_top.core name.
rm -rf "$out"
mkdir -p "$out"
# The whole workspace with its examples, as the test command builds it: a build
# of one package, or without the examples (their dev-dependencies), resolves
# other features and would compile the hardware crates again.
(cd "$root" && cargo build --release --quiet --workspace --bins --examples && target/release/tritri gen --system --width 16 --pipelines 1 --depth 64 --out "$out/system")

run() {
  local target=$1
  echo "fpga-top: fusesoc run --target $target"
  "$fusesoc" --cores-root "$out/system" --cores-root . run --build-root "$out/$target" --target "$target" \
    tritri:examples:fpga_top > "$out/$target.log" 2>&1 || { cat "$out/$target.log" >&2; echo "error: the $target target failed (log above)" >&2; exit 1; }
}

run lint
run sim
grep -E '^(pair|two batches)' "$out/sim.log"
grep -qx 'PASS' "$out/sim.log" || { cat "$out/sim.log" >&2; echo "error: the test bench did not print PASS" >&2; exit 1; }
echo "fpga-top: the test bench passed"

run synth
log=$(find "$out/synth" -name yosys.log | head -1)
# The resource table of the whole design (the last 'Number of cells' block).
awk '/Number of cells:/ { block = "" } /Number of cells:/, /^$/ { block = block $0 "\n" } END { printf "%s", block }' "$log"
