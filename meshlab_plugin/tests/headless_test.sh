#!/usr/bin/env bash
# Runs the installed plugin headless: meshlabserver from the private prefix (prepare_prefix.sh)
# under Xvfb, on one case:
#   headless_test.sh nonmanifold PREFIX WORKDIR DATA_DIR
#       a mesh with a non-manifold edge: meshlabserver must exit non-zero, its log must give the
#       reason (the finding's code), and no output file may be written.
set -euo pipefail
case_name=$1 prefix=$2 work=$3 data=$4

rm -rf "$work"
mkdir -p "$work"

fail() { echo "headless_test $case_name: FAILED: $*" >&2; exit 1; }

#! Writes a filter script for "Surface diffusion N steps" giving every parameter (meshlabserver
#! asserts on a missing one): FILE STEPS AUTOMATIC_TAU TAU BETA CONSERVE_VOLUME FIXED_BOUNDARY
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

#! meshlabserver ARGS... under Xvfb; sets `status` to its exit code and keeps its console output.
run_meshlabserver() {
  status=0
  timeout 240 xvfb-run -a "$prefix/bin/meshlabserver" "$@" > "$work/console.txt" 2>&1 || status=$?
}

case "$case_name" in
nonmanifold)
  write_diffusion_script "$work/diffusion.mlx" 3 true 0.001 0.5 false false
  run_meshlabserver -l "$work/log.txt" -i "$data/fins.ply" -o "$work/out.ply" -s "$work/diffusion.mlx"
  [[ $status -ne 0 ]] || fail "meshlabserver exited with 0 on a non-manifold mesh"
  grep -q "non-manifold-edge" "$work/log.txt" || fail "the log does not name the problem: $(cat "$work/log.txt")"
  [[ ! -e "$work/out.ply" ]] || fail "an output file was written"
  echo "headless_test nonmanifold: exit code $status, reason logged, no output written"
  ;;
*)
  fail "unknown case (nonmanifold)"
  ;;
esac
