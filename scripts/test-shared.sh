#!/usr/bin/env bash
# Tests that read the external cases in ../shared/testdata (see its README).
set -euo pipefail
cd "$(dirname "$0")/.."
test -d ../shared/testdata || { echo "error: ../shared/testdata not found next to this checkout" >&2; exit 1; }
cargo test --release --workspace --features tritri-geom/shared-testdata,tritri-cosim/shared-testdata --test shared_testdata -- --nocapture

# The example scenes that read ../shared/testdata (examples/scenes/README.md).
bash examples/scenes/check.sh --shared
