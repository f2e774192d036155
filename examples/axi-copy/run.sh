#!/usr/bin/env bash
# Emits the AXI copy unit (tritri gen --axi-copy) and runs its cocotb test
# against cocotbext-axi's AxiRam in Icarus; fails unless both tests pass
# (cocotb's make exits 0 when a test fails, so the results file is read).
# Not in Verilator: under Verilator 5.006 and cocotb 1.8.1 the unit never
# sees its inputs once AxiRam is attached (test_axi_copy.py); Verilator
# runs the unit against the project's memory model in
# crates/tritri-cosim/tests/axi_copy.rs.
#
#   bash examples/axi-copy/run.sh          # after bash scripts/setup.sh
set -euo pipefail
cd "$(dirname "$0")"
root=$(cd ../.. && pwd)
venv=$root/build/venv
[ -x "$venv/bin/cocotb-config" ] || { echo "error: cocotb not found in $venv; run bash scripts/setup.sh first" >&2; exit 1; }
"$venv/bin/python" -c "import cocotbext.axi" 2>/dev/null || { echo "error: cocotbext-axi is not in $venv; run bash scripts/setup.sh first" >&2; exit 1; }
export PATH="$venv/bin:$PATH" PYTHONDONTWRITEBYTECODE=1
out=$root/build/examples/axi-copy
mkdir -p "$out"
(cd "$root" && cargo build --release --quiet --workspace --bins --examples && target/release/tritri gen --axi-copy --out "$out/rtl" > /dev/null)

for sim in icarus; do
  echo "axi-copy: make SIM=$sim"
  results=$out/results_$sim.xml
  rm -f "$results"
  make --no-print-directory SIM=$sim RTL_DIR="$out/rtl" SIM_BUILD="$out/sim_build_$sim" COCOTB_RESULTS_FILE="$results" > "$out/$sim.log" 2>&1 \
    || { cat "$out/$sim.log" >&2; echo "error: make SIM=$sim failed (log above)" >&2; exit 1; }
  grep -E 'AxiRam copy' "$out/$sim.log" | sed 's/^ *[0-9.]*ns INFO *cocotb[^ ]* */  /' || true
  python3 "$root/scripts/cocotb-results.py" "$results" 2 || { cat "$out/$sim.log" >&2; exit 1; }
done
