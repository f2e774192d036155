#!/usr/bin/env bash
# The project's test command (README): every test that needs nothing outside this repository.
set -euo pipefail
cd "$(dirname "$0")/.."
for tool in iverilog verilator yosys; do
  command -v "$tool" >/dev/null 2>&1 || { echo "error: $tool not found; install it with: apt-get install iverilog verilator yosys" >&2; exit 1; }
done
cargo test --release --workspace

# The examples (examples/README.md): each checks what it shows and fails
# otherwise. Built with the workspace's features, as the tests were.
cargo build --release --workspace --examples
for example in classify_pairs scene_pairs emit_and_synthesize; do
  echo "example: $example"
  target/release/examples/$example
done
