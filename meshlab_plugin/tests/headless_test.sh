#!/usr/bin/env bash
# Runs the installed plugin headless: meshlabserver from the private prefix (prepare_prefix.sh)
# under Xvfb, on one case:
#   headless_test.sh nonmanifold PREFIX WORKDIR DATA_DIR
#       a mesh with a non-manifold edge: meshlabserver must exit non-zero, its log must give the
#       reason (the finding's code), and no output file may be written.
#   headless_test.sh same-as-cli PREFIX WORKDIR MESH SDFLOW COMPARE_MESHES
#       "Surface diffusion N steps" on MESH must give the surface `sdflow run` gives with the same
#       parameters (same vertices and triangles, coordinates equal to float precision), with the
#       automatic time step, and with a constant τ and volume conservation.
set -euo pipefail
case_name=$1 prefix=$2 work=$3

rm -rf "$work"
mkdir -p "$work"

fail() { echo "headless_test $case_name: FAILED: $*" >&2; exit 1; }

# Writes a filter script for "Surface diffusion N steps" giving every parameter (meshlabserver
# asserts on a missing one): FILE STEPS AUTOMATIC_TAU TAU BETA CONSERVE_VOLUME FIXED_BOUNDARY
write_diffusion_script() {
  cat > "$1" <<MLX
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Surface diffusion N steps">
  <Param type="RichInt" name="Steps" value="$2"/>
  <Param type="RichBool" name="AutomaticTau" value="$3"/>
  <Param type="RichFloat" name="Tau" value="$4"/>
  <Param type="RichFloat" name="Beta" value="$5"/>
  <Param type="RichBool" name="ConserveVolume" value="$6"/>
  <Param type="RichBool" name="FixedBoundary" value="$7"/>
 </filter>
</FilterScript>
MLX
}

# meshlabserver ARGS... under Xvfb; sets `status` to its exit code and keeps its console output.
run_meshlabserver() {
  status=0
  timeout 240 xvfb-run -a "$prefix/bin/meshlabserver" "$@" > "$work/console.txt" 2>&1 || status=$?
}

# Runs the filter with SETTINGS (those of write_diffusion_script after the file name) on
# $work/input.ply, and `sdflow run` with FLAGS..., then compares the two final surfaces.
#   compare_with_cli NAME "SETTINGS" FLAGS...
compare_with_cli() {
  local name=$1 settings=$2; shift 2
  local steps
  steps=$(cut -d' ' -f1 <<< "$settings")
  # shellcheck disable=SC2086 # the settings are words on purpose
  write_diffusion_script "$work/$name.mlx" $settings
  run_meshlabserver -l "$work/$name.log" -i "$work/input.ply" -o "$work/$name.meshlab.ply" -s "$work/$name.mlx"
  [[ $status -eq 0 && -s "$work/$name.meshlab.ply" ]] || fail "$name: meshlabserver failed ($status): $(cat "$work/$name.log")"
  "$sdflow" --quiet run --input "$work/input.ply" --out "$work/$name.run" --steps "$steps" "$@" > /dev/null \
    || fail "$name: sdflow run failed"
  local final
  final=$(ls "$work/$name.run"/snapshots/step_*.ply | tail -n 1)
  [[ $(basename "$final") == "$(printf 'step_%06d.ply' "$steps")" ]] || fail "$name: sdflow run stopped at $final"
  "$compare" "$final" "$work/$name.meshlab.ply" || fail "$name: the plugin's surface differs from sdflow run's"
}

case "$case_name" in
nonmanifold)
  data=$4
  write_diffusion_script "$work/diffusion.mlx" 3 true 0.001 0.5 false false
  run_meshlabserver -l "$work/log.txt" -i "$data/fins.ply" -o "$work/out.ply" -s "$work/diffusion.mlx"
  [[ $status -ne 0 ]] || fail "meshlabserver exited with 0 on a non-manifold mesh"
  grep -q "non-manifold-edge" "$work/log.txt" || fail "the log does not name the problem: $(cat "$work/log.txt")"
  [[ ! -e "$work/out.ply" ]] || fail "an output file was written"
  echo "headless_test nonmanifold: exit code $status, reason logged, no output written"
  ;;
same-as-cli)
  mesh=$4 sdflow=$5 compare=$6
  # MeshLab holds coordinates as floats: both sides start from its float copy of the mesh.
  run_meshlabserver -i "$mesh" -o "$work/input.ply"
  [[ $status -eq 0 && -s "$work/input.ply" ]] || fail "meshlabserver could not convert $mesh"
  compare_with_cli adaptive "12 true 0.001 0.5 false false" --adaptive --beta 0.5
  compare_with_cli constant "8 false 0.05 0.5 true false" --tau 0.05 --beta 0.5 --conserve-volume
  echo "headless_test same-as-cli: the plugin's surfaces equal sdflow run's"
  ;;
*)
  fail "unknown case (nonmanifold, same-as-cli)"
  ;;
esac
