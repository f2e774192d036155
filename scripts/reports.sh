#!/usr/bin/env bash
# The speed-against-error reports of issue 15, each opened in headless
# Chromium for a screenshot: the Shen sets, the hard-case suite and two
# real scenes, into build/reports/<name>/ (gitignored).
#
#   bash scripts/fetch-meshes.sh     # once: CGAL's meshes into build/meshes
#   bash scripts/reports.sh          # about a minute; needs chromium (apt-get install chromium)
#
# The screenshots are build/reports/<name>.png; docs/report/ keeps a crop
# of two of them: shen.png the page's top 1400 x 1300 pixels, and
# camel-elephant-scene.png the camel-elephant page's Scene section (rows
# 1760 to 2575 on 2026-11-30: its heading to the end of its table).
set -euo pipefail
cd "$(dirname "$0")/.."
m=build/meshes
t=../shared/testdata
[ -s "$m/camel.off" ] || { echo "error: $m/camel.off missing; run: bash scripts/fetch-meshes.sh" >&2; exit 1; }
[ -s "$t/shen_intersected.txt" ] || { echo "error: $t/shen_intersected.txt missing (the shared test data)" >&2; exit 1; }
command -v chromium >/dev/null || { echo "error: chromium not found; install it with: apt-get install chromium" >&2; exit 1; }
# The whole workspace with its examples, as the test command builds it: a build
# of one package, or without the examples (their dev-dependencies), resolves
# other features and would compile the hardware crates again.
cargo build --release -q --workspace --bins --examples
tritri=target/release/tritri
out=build/reports
mkdir -p "$out"

$tritri report "$t/shen_intersected.txt" "$t/shen_separated.txt" --out "$out/shen"
$tritri report @hard --out "$out/hard"
$tritri report --scene "$m/bunny.off" "$m/armadillo.off" --scale-b 0.008 --pose-b 0.6,0,0 --out "$out/bunny-armadillo"
$tritri report --scene "$m/camel.off" "$m/elephant.off" --pose-b 0.3,0,0 --out "$out/camel-elephant"
for name in shen hard bunny-armadillo camel-elephant; do
  chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1400,2600 \
    --screenshot="$PWD/$out/$name.png" "file://$PWD/$out/$name/report.html" >/dev/null 2>&1
  echo "screenshot: $out/$name.png"
done
