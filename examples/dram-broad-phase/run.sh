#!/usr/bin/env bash
# Writes a case of the broad-phase accelerator with its scene in DRAM
# (examples/dram_broad_phase.rs --write-case: the design that fits the ECP5-85, the
# built-in torus and sphere, or A B [SCALE_B TX TY TZ] given here) and runs
# its cocotb test against cocotbext-axi's AxiRam in Icarus; fails unless
# both tests pass (cocotb's make exits 0 when a test fails, so the results
# file is read). Not in Verilator, for the reason examples/axi-copy gives.
#
#   bash examples/dram-broad-phase/run.sh [A B [SCALE_B TX TY TZ]]   # after bash scripts/setup.sh
set -euo pipefail
cd "$(dirname "$0")"
root=$(cd ../.. && pwd)
venv=$root/build/venv
[ -x "$venv/bin/cocotb-config" ] || { echo "error: cocotb not found in $venv; run bash scripts/setup.sh first" >&2; exit 1; }
"$venv/bin/python" -c "import cocotbext.axi" 2>/dev/null || { echo "error: cocotbext-axi is not in $venv; run bash scripts/setup.sh first" >&2; exit 1; }
export PATH="$venv/bin:$PATH" PYTHONDONTWRITEBYTECODE=1
out=$root/build/examples/dram-broad-phase
rm -rf "$out/case"
mkdir -p "$out/case"
(cd "$root" && cargo build --release --quiet --workspace --bins --examples && target/release/examples/dram_broad_phase --write-case "$out/case" "$@")

for sim in icarus; do
  echo "dram-broad-phase: make SIM=$sim"
  results=$out/results_$sim.xml
  rm -f "$results"
  make --no-print-directory SIM=$sim CASE_DIR="$out/case" SIM_BUILD="$out/sim_build_$sim" COCOTB_RESULTS_FILE="$results" > "$out/$sim.log" 2>&1 \
    || { cat "$out/$sim.log" >&2; echo "error: make SIM=$sim failed (log above)" >&2; exit 1; }
  grep -E 'AxiRam top' "$out/$sim.log" | sed 's/^ *[0-9.]*ns INFO *cocotb[^ ]* */  /' || true
  python3 "$root/scripts/cocotb-results.py" "$results" 2 || { cat "$out/$sim.log" >&2; exit 1; }
done
