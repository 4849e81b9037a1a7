#!/usr/bin/env bash
# Meshes the initial surfaces of the paper's experiments into samples/meshes/ with `sdflow shape`
# (deterministic: the same files on every machine), skipping those already there. Progress on
# stderr: which mesh of how many, then sdflow shape's own (the largest takes about half a minute).
#   samples/make_meshes.sh SDFLOW_BINARY
set -euo pipefail
usage() { sed -n '2,5p' "$0" | sed 's/^# \{0,1\}//'; }
if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  usage
  exit 0
fi
[[ $# -eq 1 ]] || { usage >&2; exit 2; }
sdflow=$(realpath "$1")
cd "$(dirname "$0")/meshes"
count=12 index=0
make_mesh() { # file, then the arguments of sdflow shape
  local file=$1; shift
  index=$((index + 1))
  if [[ -f $file ]]; then
    echo "make_meshes.sh: [$index/$count] $file is there" >&2
  else
    echo "make_meshes.sh: [$index/$count] $file: sdflow shape $*" >&2
    "$sdflow" shape "$@" -o "$file"
  fi
}
make_mesh torus_15250.ply torus --vertices 15250
make_mesh dumbbell.ply dumbbell --edge-length 0.5 --edges-per-radius 4 # the neck resolved from the start
make_mesh sintering_51311.ply sintering --vertices 51311
make_mesh spheres_on_plane_25000.ply spheres-on-plane --vertices 25000   # the sample's
make_mesh spheres_on_plane_95657.ply spheres-on-plane --vertices 95657   # the paper's resolution, for --input
make_mesh compact_27.ply packing --nx 3 --ny 3 --nz 3 --spacing 1.8 --edge-length 0.12
make_mesh cuboid_island.ply cuboid-island --a 2 --b 1 --c 0.5 --radius 0.2 --edge-length 0.06
make_mesh island_breakup.ply cuboid-island --a 8 --b 1 --c 0.5 --radius 0.45 --edge-length 0.1
make_mesh film_with_hole.ply film-with-hole --side 6 --thickness 0.5 --hole 1 --radius 0.2 --edge-length 0.1
make_mesh film_rim_breakup.ply film-with-hole --side 6 --thickness 0.5 --hole 2.5 --radius 0.2 --edge-length 0.1
make_mesh round_island.ply cuboid-island --a 1 --b 1 --c 0.5 --radius 0.45 --edge-length 0.035
make_mesh compact_100.ply packing --count 100 --seed 1 --spacing 1.8 --min-distance 2.4 --edge-length 0.15
