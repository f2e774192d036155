#!/usr/bin/env bash
# Fetches public meshes for `tritri sim` into build/meshes/ (gitignored; never commit them).
#
#   build/meshes/bunny.off      the Stanford bunny (37,706 vertices, 75,408 triangles),
#                               from CGAL's example data in Debian's libcgal-demo
#                               (data/meshes/bunny00.off)
#   build/meshes/armadillo.off  the Stanford armadillo (26,002 vertices, 52,000 triangles),
#                               same source
#   build/meshes/camel.off      a camel (19,536 triangles), same source
#   build/meshes/elephant.off   an elephant (5,558 triangles), same source
#   build/meshes/teapot.bpt     the Utah teapot's 32 Bezier patches, copied from
#                               ../shared/testdata when it is there (tessellate with
#                               `tritri sim --tessellation N`)
#
# The Debian package is downloaded (not installed) and unpacked in a temporary
# directory, so docs-excluding dpkg configurations do not matter.
#
# Example:
#   bash scripts/fetch-meshes.sh
#   tritri sim --scene build/meshes/bunny.off build/meshes/bunny.off --pose-b 0.02,0.01,0,0,30,0
set -euo pipefail
cd "$(dirname "$0")/.."
out=build/meshes
mkdir -p "$out"

if [ ! -s "$out/bunny.off" ] || [ ! -s "$out/armadillo.off" ] || [ ! -s "$out/camel.off" ] || [ ! -s "$out/elephant.off" ]; then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  if ! (cd "$work" && apt-get download libcgal-demo >/dev/null 2>&1); then
    $SUDO apt-get update -qq
    (cd "$work" && apt-get download libcgal-demo >/dev/null)
  fi
  dpkg -x "$work"/libcgal-demo_*.deb "$work/pkg"
  data=$(find "$work/pkg" -name data.tar.gz -path '*cgal*' | head -1)
  [ -n "$data" ] || { echo "error: libcgal-demo has no data.tar.gz" >&2; exit 1; }
  tar -xzf "$data" -C "$work" data/meshes/bunny00.off data/meshes/armadillo.off data/meshes/camel.off data/meshes/elephant.off
  cp "$work/data/meshes/bunny00.off" "$out/bunny.off"
  for mesh in armadillo camel elephant; do
    cp "$work/data/meshes/$mesh.off" "$out/$mesh.off"
  done
fi

if [ -f ../shared/testdata/teapot.bpt ]; then
  install -m 644 ../shared/testdata/teapot.bpt "$out/teapot.bpt"
fi

ls -l "$out"
