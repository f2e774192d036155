#!/usr/bin/env bash
# The public scenes of docs/broad-phase.md on the accelerator that fits the
# ECP5-85 (`tritri sim`'s default design: the scene in DRAM behind an AXI4
# port), end to end against the software in the same run: one markdown row
# per scene, from `tritri sim --json`. A scene the design cannot take (its
# owner filter holds 8,192 triangles of an object in the common box) gets a
# row with the reason.
#
#   bash scripts/dram-scenes.sh [other tritri sim options, e.g. --engine verilator]
#
# Times: the top's clocks at its post-route clock with the ECP5-5G Versa's
# 1.6 GB/s DDR3; the host's preparation and the software measured once on
# this machine (they vary by a third from run to run here).
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/public-scenes.sh
source scripts/public-scenes.sh

echo "| scene | in the common box | exact pairs (decided again) | top: clocks | DRAM read / written | x the memory's bound | top at the post-route clock | host | link in + out | end to end | software, 1 thread (2) | top / software | end to end / software |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for entry in "${scenes[@]}"; do
  name=${entry%%|*}
  read -r -a args <<<"${entry#*|}"
  if ! "$tritri" sim --scene "${args[@]:0:2}" "${args[@]:2}" "$@" --json "$work/run.json" >"$work/out.txt" 2>"$work/err.txt"; then
    echo "| $name | $(sed -e 's/^error: //' -e 's/|/\\|/g' "$work/err.txt" | head -1) |"
    continue
  fi
  python3 - "$name" "$work/run.json" <<'EOF'
import json, sys
name, path = sys.argv[1], sys.argv[2]
v = json.load(open(path))
s, d, t = v["scene"], v["dram"], v["seconds"]
ms = lambda x: f"{x * 1e3:.3f} ms"
acc = v["accelerator"]
print(f"| {name} | {s['kept_a']:,} + {s['kept_b']:,} | {len(v['pairs'])} ({len(v['uncertain'])}) | {v['clocks']:,} "
      f"| {d['bytes_read'] // 1024:,} / {d['bytes_written'] // 1024:,} KiB | {v['clocks'] / d['memory_bound_clocks']:.2f} "
      f"| {ms(t['accelerator'])} at {acc['clock_mhz']} MHz | {ms(t['host'])} | {ms(t['link_in'] + t['link_back'])} "
      f"| {ms(t['end_to_end'])} | {ms(t['software'])} ({ms(t['software_two_threads'])}) "
      f"| {t['software'] / t['accelerator']:.2f} x | {t['software'] / t['end_to_end']:.2f} x |")
EOF
done
