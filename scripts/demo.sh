#!/usr/bin/env bash
# The main job (README): installs what it needs first (scripts/setup.sh,
# idempotent: a second run installs nothing), then `tritri demo`: the
# pipeline's and the system's Verilog, and the built-in scene through the
# bit-exact model and through the emitted system in Verilator.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# The whole workspace with its examples, as the test command builds it: a build
# of one package, or without the examples (their dev-dependencies), resolves
# other features and would compile the hardware crates again.
cargo build --release --quiet --workspace --bins --examples
target/release/tritri demo "$@"
