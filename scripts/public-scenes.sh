# Sourced by scripts/broad-phase-scenes.sh and scripts/dram-scenes.sh: the
# public scenes of docs/broad-phase.md (CGAL's meshes, posed in contact),
# the release build both run, and a work directory removed on exit.
# Defines `scenes` ("name|tritri sim arguments"), `tritri` and `work`.
m=build/meshes
[ -s "$m/camel.off" ] || { echo "error: $m/camel.off missing; run: bash scripts/fetch-meshes.sh" >&2; exit 1; }
# The whole workspace with its examples, as the test command builds it: a build
# of one package, or without the examples (their dev-dependencies), resolves
# other features and would compile the hardware crates again.
cargo build --release -q --workspace --bins --examples
tritri=target/release/tritri
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

scenes=(
  "bunny x armadillo|$m/bunny.off $m/armadillo.off --scale-b 0.008 --pose-b 0.6,0,0"
  "armadillo x camel|$m/armadillo.off $m/camel.off --scale-b 127 --pose-b 55,0,0"
  "camel x elephant|$m/camel.off $m/elephant.off --pose-b 0.3,0,0"
  "teapot (16) x bunny|$m/teapot.bpt $m/bunny.off --tessellation 16 --scale-b 3 --pose-b 3,0,1.5"
  "bunny x bunny (README)|$m/bunny.off $m/bunny.off --pose-b 0.02,0.01,0,0,30,0"
)
