#!/usr/bin/env bash
# Meshes the initial surfaces of the paper's experiments into samples/meshes/ with `sdflow shape`
# (deterministic: the same files on every machine), skipping those already there.
#   samples/make_meshes.sh SDFLOW_BINARY
set -euo pipefail
sdflow=$(realpath "$1")
cd "$(dirname "$0")/meshes"
make_mesh() { # file, then the arguments of sdflow shape
  local file=$1; shift
  [[ -f $file ]] || "$sdflow" shape "$@" -o "$file"
}
make_mesh torus_15250.ply torus --vertices 15250
make_mesh dumbbell.ply dumbbell --edge-length 0.5 --edges-per-radius 4 # the neck resolved from the start
make_mesh sintering_51311.ply sintering --vertices 51311
make_mesh spheres_on_plane_95657.ply spheres-on-plane --vertices 95657
