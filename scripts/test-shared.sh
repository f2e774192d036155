#!/usr/bin/env bash
# Tests that read the external cases in ../shared/testdata (see its README).
set -euo pipefail
cd "$(dirname "$0")/.."
test -d ../shared/testdata || { echo "error: ../shared/testdata not found next to this checkout" >&2; exit 1; }
cargo test --release --workspace --features tritri-geom/shared-testdata --test shared_testdata -- --nocapture
# The published C code's fidelity check against the peer cases' recorded wrong-ordering counts.
cargo test --release -p tritri-geom --features shared-testdata --lib published_float -- --nocapture
