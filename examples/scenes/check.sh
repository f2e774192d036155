#!/usr/bin/env bash
# Runs every scene of scenes.txt through `tritri sim` and fails unless, for
# each: the pairs equal the committed expected/NAME.pairs, the engine equals
# the exact model on the quantized coordinates, and the quantized answer
# equals the exact answer on the original f64 coordinates (0 missing,
# 0 extra) -- so expected/NAME.pairs is the exact model's answer.
#
#   bash examples/scenes/check.sh            # the scenes that need nothing outside the repository
#   bash examples/scenes/check.sh --shared   # the scenes that read ../shared/testdata
#   bash examples/scenes/check.sh --update   # rewrite expected/*.pairs (then review the diff)
set -euo pipefail
cd "$(dirname "$0")/../.."
want=own
update=0
for arg in "$@"; do
  case $arg in
    --shared) want=shared ;;
    --update) update=1 ;;
    *) echo "error: unknown option $arg (--shared, --update)" >&2; exit 2 ;;
  esac
done
# The whole workspace with its examples, as the test command builds it: a build
# of one package, or without the examples (their dev-dependencies), resolves
# other features and would compile the hardware crates again.
cargo build --release --quiet --workspace --bins --examples
tritri=target/release/tritri
out=build/examples/scenes
mkdir -p "$out"

ran=0
while IFS='|' read -r name args needs; do
  name=$(echo "$name" | xargs)
  needs=$(echo "$needs" | xargs)
  case $name in ''|'#'*) continue ;; esac
  if [ "$want" = shared ] && [ "$needs" != shared ]; then continue; fi
  if [ "$want" = own ] && [ "$needs" = shared ]; then continue; fi
  # The README shows each command as it is run here (with --verbose added
  # for the lines this script reads).
  grep -qF -- "-- sim $(echo "$args" | xargs) --out" examples/scenes/README.md \
    || { echo "error: examples/scenes/README.md does not show the command of scene $name" >&2; exit 1; }
  report=$out/$name.txt
  # shellcheck disable=SC2086
  $tritri sim $args --verbose --out "$out/$name.pairs" > "$report"
  grep -E '^(scene|exact pairs: [0-9]+ \(|walk|DRAM)' "$report" | sed "s/^/$name: /"
  grep -q '^check: engine against the exact model on the quantized coordinates .*: equal$' "$report" \
    || { echo "error: $name: the engine differs from the exact model ($report)" >&2; exit 1; }
  grep -q 'quantization error on the [0-9]*-bit grid: 0 missing, 0 extra; exact pairs: 0 missing, 0 extra$' "$report" \
    || { echo "error: $name: the quantized answer differs from the exact answer on the original coordinates ($report)" >&2; exit 1; }
  if [ "$update" = 1 ]; then
    cp "$out/$name.pairs" "examples/scenes/expected/$name.pairs"
  fi
  diff -u "examples/scenes/expected/$name.pairs" "$out/$name.pairs" \
    || { echo "error: $name: the pairs differ from examples/scenes/expected/$name.pairs" >&2; exit 1; }
  ran=$((ran + 1))
done < examples/scenes/scenes.txt
[ "$ran" -gt 0 ] || { echo "error: no scene ran" >&2; exit 1; }
echo "scenes: $ran checked"
