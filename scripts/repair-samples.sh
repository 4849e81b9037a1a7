#!/usr/bin/env bash
# Runs `sdflow repair` on CGAL's sample meshes (Debian package libcgal-demo: its data.tar.gz) and
# prints one line per mesh that `sdflow stats` refuses: whether stats accepts the repaired file,
# and the repairs by code with their counts; then the totals README quotes.
#   scripts/repair-samples.sh [SDFLOW]      (default: build/release/cli/sdflow)
# Uses the installed package's data when present, else downloads the package (apt-get download)
# into a temporary directory without installing it. Meshes over 3 MB are skipped.
set -euo pipefail
if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
cd "$(dirname "$0")/.."
sdflow=$(realpath "${1:-build/release/cli/sdflow}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
data=/usr/share/doc/libcgal-dev/data.tar.gz
if [[ ! -f "$data" ]]; then
  (cd "$work" && apt-get download libcgal-demo > /dev/null 2>&1 && dpkg-deb -x libcgal-demo_*.deb package)
  data="$work/package/usr/share/doc/libcgal-dev/data.tar.gz"
fi
tar -xzf "$data" -C "$work" data/meshes
total=0 refused=0 repaired=0
for mesh in "$work"/data/meshes/*.{off,stl,ply}; do
  [[ $(stat -c %s "$mesh") -gt 3000000 ]] && continue
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
echo "$total meshes, $refused refused by stats, $repaired of them repaired into files stats accepts"
