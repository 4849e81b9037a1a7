#!/usr/bin/env bash
# Runs surface_diffusion.mlx (beside this script) on a mesh with MeshLab's meshlabserver, without a
# display (xvfb-run), keeping per-vertex normals (N) and quality (the mean curvature H) in the output:
#   meshlab_plugin/examples/run_headless.sh IN.ply OUT.ply [SCRIPT.mlx]
# Needs the plugin installed (README, "MeshLab plugin") and the Debian packages meshlab and xvfb.
# meshlabserver exits with 0 even when it cannot save: the output file is checked here.
set -euo pipefail
[[ $# -ge 2 ]] || { sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
in=$1 out=$2 script=${3:-$(dirname "$0")/surface_diffusion.mlx}
meshlabserver=${MESHLABSERVER:-meshlabserver}
rm -f "$out"
xvfb-run -a "$meshlabserver" -i "$in" -o "$out" -m vn vq -s "$script"
[[ -s $out ]] || { echo "run_headless.sh: meshlabserver wrote no $out" >&2; exit 1; }
echo "run_headless.sh: wrote $out"
