#!/usr/bin/env bash
# The octree broad phase against the thesis's flat system on real meshes in
# contact (issue 13): per scene, both broad phases through the model engine,
# their pairs compared, and one table row in Markdown.
#
#   bash scripts/fetch-meshes.sh          # once: CGAL's meshes into build/meshes
#   bash scripts/broad-phase-scenes.sh [--subdivide K] [other tritri sim options]
#
# Times: software is the exact box sweep measured by `tritri sim` on this
# machine (one thread); hardware is the system's cycle model at 100 MHz
# (no post-route clock yet); "first in to last out" adds the binning unit's
# cycles (its cycle-exact model, which its Verilog equals in co-simulation;
# memories sized for the scene) and the owner filter's, not overlapped with
# the narrow phase.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/public-scenes.sh
source scripts/public-scenes.sh

field() { grep -m1 "$1" "$2" | sed -E "s/.*$3.*/\1/"; }
echo "| scene | N1 x N2 | box-overlap pairs | flat: pairs tested | octree: pairs tested | / box-overlap | leaves, depth | intersecting | = flat | vs exact f64 | flat time | octree narrow phase | binning cycles | binning memory | owner filter: hits / dropped / cycles | first in to last out | software | ratio (narrow) | ratio (first in to last out) |"
echo "|---|---|---:|---:|---:|---:|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for entry in "${scenes[@]}"; do
  name=${entry%%|*}
  read -r -a args <<<"${entry#*|}"
  $tritri sim --scene "${args[@]:0:2}" "${args[@]:2}" "$@" --verbose --broad-phase flat --out "$work/flat.txt" >"$work/flat.log"
  $tritri sim --scene "${args[@]:0:2}" "${args[@]:2}" "$@" --verbose --broad-phase octree --out "$work/octree.txt" >"$work/octree.log"
  same=$(cmp -s "$work/flat.txt" "$work/octree.txt" && echo yes || echo NO)
  grep -q "engine = exact model on the quantized coordinates.*equal" "$work/octree.log" || same="NO (model)"
  n1=$(grep -m1 "^scene:" "$work/octree.log" | sed -E 's/.*A = [^(]*\(([0-9]+) triangles.*/\1/')
  n2=$(grep -m1 "^scene:" "$work/octree.log" | sed -E 's/.*B = [^(]*\(([0-9]+) triangles.*/\1/')
  box=$(field "^work:" "$work/octree.log" 'box-overlap pairs \(([0-9]+)\)')
  flat_tested=$(field "^pairs tested:" "$work/flat.log" 'pairs tested: ([0-9]+) .*')
  tested=$(field "^pairs tested:" "$work/octree.log" 'pairs tested: ([0-9]+) .*')
  per_box=$(field "^work:" "$work/octree.log" '= ([0-9.]+) x the box-overlap.*')
  leaves=$(field "^broad phase:" "$work/octree.log" ' ([0-9]+) leaves with both objects.*')
  depth=$(field "^broad phase:" "$work/octree.log" 'depth ([0-9]+),.*')
  hits=$(field "^intersecting pairs on the grid:" "$work/octree.log" 'intersecting pairs on the grid: ([0-9]+)')
  quant=$(field "^quantization error" "$work/octree.log" ': ([0-9]+ pairs missing, [0-9]+ extra).*')
  flat_time=$(field "^cycles:" "$work/flat.log" 'time at [^:]*: (.*)')
  octree_time=$(field "^cycles:" "$work/octree.log" 'time at [^:]*: (.*)')
  software=$(field "^speed:" "$work/octree.log" 'one thread, triangles in memory\) ([0-9.]+ [a-z]+);.*')
  ratio=$(field "^speed:" "$work/octree.log" ': ([0-9.]+) x; first.*')
  binning=$(field "^binning unit" "$work/octree.log" ': ([0-9]+) cycles;.*')
  memory=$(field "^binning unit" "$work/octree.log" 'memories ([0-9.]+ Mbit).*')
  owner=$(grep -m1 "^owner filter" "$work/octree.log" | sed -E 's/.*: ([0-9]+) hits from the leaves, ([0-9]+) duplicates dropped, [0-9]+ pairs through; ([0-9]+) cycles.*/\1 \/ \2 \/ \3/')
  whole=$(field "^first triangle in to last pair out:" "$work/octree.log" '\), ([0-9.]+ [a-z]+) at .*')
  whole_ratio=$(field "^speed:" "$work/octree.log" ': ([0-9.]+) x$')
  echo "| $name | $n1 x $n2 | $box | $flat_tested | $tested | $per_box | $leaves, $depth | $hits | $same | $quant | $flat_time | $octree_time | $binning | $memory | $owner | $whole | $software | $ratio | $whole_ratio |"
done
