#!/usr/bin/env bash
# Runs the cocotb test of the emitted pipeline (rtl-out/w24) in Icarus and in
# Verilator, and fails unless all three tests pass in both (cocotb's make
# exits 0 when a test fails, so the results file is read).
#
#   bash examples/cocotb/run.sh          # after bash scripts/setup.sh
set -euo pipefail
cd "$(dirname "$0")"
root=$(cd ../.. && pwd)
venv=$root/build/venv
[ -x "$venv/bin/cocotb-config" ] || { echo "error: cocotb not found in $venv; run bash scripts/setup.sh first" >&2; exit 1; }
export PATH="$venv/bin:$PATH" PYTHONDONTWRITEBYTECODE=1
out=$root/build/examples/cocotb
mkdir -p "$out"

for sim in icarus verilator; do
  echo "cocotb: make SIM=$sim"
  results=$out/results_$sim.xml
  rm -f "$results"
  make --no-print-directory SIM=$sim SIM_BUILD="$out/sim_build_$sim" COCOTB_RESULTS_FILE="$results" > "$out/$sim.log" 2>&1 \
    || { cat "$out/$sim.log" >&2; echo "error: make SIM=$sim failed (log above)" >&2; exit 1; }
  grep -E 'verdicts equal' "$out/$sim.log" | sed 's/^ *[0-9.]*ns INFO *cocotb[^ ]* */  /' || true
  python3 "$root/scripts/cocotb-results.py" "$results" 3 || { cat "$out/$sim.log" >&2; exit 1; }
done
