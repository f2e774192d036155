#!/usr/bin/env bash
# Tests that read the external cases in ../shared/testdata (see its README).
set -euo pipefail
cd "$(dirname "$0")/.."
test -d ../shared/testdata || { echo "error: ../shared/testdata not found next to this checkout" >&2; exit 1; }
# Real meshes for the voxelization oracle test (CGAL's, from Debian's libcgal-demo).
bash scripts/fetch-meshes.sh
# These targets are `test = false` (the plain `cargo test` leaves them out),
# so naming them here builds nothing the test command did not build already.
cargo test --release --workspace --test shared_testdata --test voxelize_meshes --test broad_phase_meshes -- --nocapture

# examples/fpga-top's cocotb test on a real mesh pair (the camel and the
# elephant of docs/broad-phase.md, about two minutes of Icarus); the test
# command ran its lint and synthesis already.
bash examples/fpga-top/run.sh --no-synth build/meshes/camel.off build/meshes/elephant.off 1 0.3 0 0

# The example scenes that read ../shared/testdata (examples/scenes/README.md).
bash examples/scenes/check.sh --shared
