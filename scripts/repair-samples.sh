#!/usr/bin/env bash
# Runs `sdflow repair` on the sample meshes of two Debian packages and prints one line per mesh
# that `sdflow stats` refuses: whether stats accepts the repaired file, and the repairs by code with
# their counts; then the totals README quotes, per package:
#   - CGAL's sample data (libcgal-demo: its data.tar.gz; scans, CAD models, test cases);
#   - geomview's example objects (geomview: /usr/share/geomview; hand-written polyhedra, OOGL files).
#   scripts/repair-samples.sh [SDFLOW]      (default: build/release/cli/sdflow)
# Uses a package's installed files when present, else downloads the package (apt-get download)
# into a temporary directory without installing it. Meshes over 3 MB are skipped.
set -euo pipefail
if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
cd "$(dirname "$0")/.."
sdflow=$(realpath "${1:-build/release/cli/sdflow}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# package_path PACKAGE PATH
source scripts/lib/debian-package.sh # the working directory is the repository's root

# Repairs every mesh given that stats refuses, one line each, then the totals for LABEL.
repair_all() {
  local label=$1; shift
  local total=0 refused=0 repaired=0 mesh out repairs
  for mesh in "$@"; do
    [[ -f "$mesh" && $(stat -c %s "$mesh") -le 3000000 ]] || continue
    total=$((total + 1))
    "$sdflow" -q stats --no-tetgen "$mesh" > /dev/null 2>&1 && continue
    refused=$((refused + 1))
    out="$work/repaired.off"
    rm -f "$out"
    repairs=$("$sdflow" -q repair --json "$mesh" -o "$out" 2> /dev/null | tr -d '\n ' |
              grep -o '"code":"[a-z-]*","count":[0-9]*' | sed 's/"code":"//; s/","count":/=/' | tr '\n' ' ' || true)
    if [[ -f "$out" ]] && "$sdflow" -q stats --no-tetgen "$out" > /dev/null 2>&1; then
      repaired=$((repaired + 1))
      echo "$(basename "$mesh"): repaired, stats accepts it: $repairs"
    else
      echo "$(basename "$mesh"): not repaired: $("$sdflow" -q repair "$mesh" -o "$out" 2>&1 | head -1)"
    fi
  done
  echo "$label: $total meshes, $refused refused by stats, $repaired of them repaired into files stats accepts"
}

cgal=$(package_path libcgal-demo /usr/share/doc/libcgal-dev/data.tar.gz)
tar -xzf "$cgal" -C "$work" data/meshes
repair_all "CGAL (libcgal-demo)" "$work"/data/meshes/*.{off,stl,ply}

geomview=$(package_path geomview /usr/share/geomview)
mapfile -t objects < <(find "$geomview" -name '*.off' | sort)
repair_all "geomview" "${objects[@]}"
