#!/usr/bin/env bash
# Generates the accelerator examples/fpga-top is built around and a scene
# for it, then runs the top's FuseSoC targets: lint (Verilator -Wall), sim
# (Icarus, the cocotb test tb/test_fpga_top.py against cocotbext-axi's
# AxiLiteMaster, AxiRam and AxiStreamSink) and synth (Yosys synth_ecp5,
# about 7 minutes; --no-synth leaves it out) with its resources. Fails if
# any of them fails or a cocotb test fails.
#
#   bash examples/fpga-top/run.sh [--no-synth] [A B [SCALE_B TX TY TZ]]   # after bash scripts/setup.sh
#
# The scene is the built-in torus and sphere, or meshes A and B (B scaled
# and moved) as examples/dram_broad_phase.rs takes them.
set -euo pipefail
cd "$(dirname "$0")"
here=$(pwd)
root=$(cd ../.. && pwd)
venv=$root/build/venv
synth=1
if [ "${1:-}" = "--no-synth" ]; then synth=0; shift; fi
for tool in fusesoc cocotb-config; do
  [ -x "$venv/bin/$tool" ] || { echo "error: $venv/bin/$tool not found; run bash scripts/setup.sh first" >&2; exit 1; }
done
"$venv/bin/python" -c "import cocotbext.axi" 2>/dev/null || { echo "error: cocotbext-axi is not in $venv; run bash scripts/setup.sh first" >&2; exit 1; }
out=$root/build/examples/fpga-top
rm -rf "$out"
mkdir -p "$out"

# The accelerator tritri_fpga_top.core depends on (its rtl/ directory holds
# the generated core), the scene memory the host writes and the answers.
# The whole workspace with its examples, as the test command builds it: a
# build of one package, or without the examples (their dev-dependencies),
# resolves other features and would compile the hardware crates again.
(cd "$root" && cargo build --release --quiet --workspace --bins --examples \
  && target/release/examples/dram_broad_phase --data-bits 256 --write-case "$out/case" "$@")

run() {
  local target=$1
  echo "fpga-top: fusesoc run --target $target"
  "$venv/bin/fusesoc" --cores-root "$out/case/rtl" --cores-root "$here" run --build-root "$out/$target" \
    --target "$target" tritri:examples:fpga_top > "$out/$target.log" 2>&1 \
    || { cat "$out/$target.log" >&2; echo "error: the $target target failed (log above)" >&2; exit 1; }
}

run lint

# cocotb in the vvp that FuseSoC's Icarus flow runs: its VPI library by
# name (the core's vvp_options), found on this path; the test by MODULE.
# Not TOPLEVEL: the flow's Makefile has a variable of that name, which make
# would export to vvp (cocotb takes the design's one root).
results=$out/results.xml
(
  export PATH="$venv/bin:$PATH" PYTHONDONTWRITEBYTECODE=1
  export IVERILOG_VPI_MODULE_PATH=$(cocotb-config --lib-dir)
  export LIBPYTHON_LOC=$(cocotb-config --libpython) PYGPI_PYTHON_BIN=$(cocotb-config --python-bin)
  export MODULE=test_fpga_top TOPLEVEL_LANG=verilog
  export PYTHONPATH="$here/tb" CASE_DIR="$out/case" COCOTB_RESULTS_FILE="$results"
  run sim
)
grep -E 'INFO.*fpga-top' "$out/sim.log" | sed 's/^ *[0-9.]*ns INFO *cocotb[^ ]* */  /' || true
python3 "$root/scripts/cocotb-results.py" "$results" 2 || { cat "$out/sim.log" >&2; exit 1; }

if [ "$synth" = 1 ]; then
  run synth
  log=$(find "$out/synth" -name yosys.log | head -1)
  # The resource table of the whole design (the last 'Number of cells' block).
  awk '/Number of cells:/ { block = "" } /Number of cells:/, /^$/ { block = block $0 "\n" } END { printf "%s", block }' "$log"
fi
