#!/usr/bin/env bash
# Runs the installed plugin headless: meshlabserver from the private prefix (prepare_prefix.sh)
# under Xvfb, on one case:
#   headless_test.sh nonmanifold PREFIX WORKDIR DATA_DIR
#       a mesh with a non-manifold edge: meshlabserver must exit non-zero, its log must give the
#       reason (the finding's code), and no output file may be written.
#   headless_test.sh same-as-cli PREFIX WORKDIR MESH SDFLOW COMPARE_MESHES
#       "Surface diffusion N steps" on MESH must give the surface `sdflow run` gives with the same
#       parameters (same vertices and triangles, coordinates equal to float precision), with the
#       automatic time step, with a constant τ and volume conservation, and with re-triangulation
#       (which must change the number of vertices); and, from the constant-τ case, with each other
#       mean curvature, the volume-gradient vertex areas and extrapolated steps (each of which must
#       change the surface).
#   headless_test.sh substrate-same-as-cli PREFIX WORKDIR SDFLOW COMPARE_MESHES
#       "Surface diffusion on a substrate N steps" on a 2 × 2 × 0.5 cuboid island (`sdflow shape
#       cuboid-island`) must give the surface `sdflow run --boundary substrate` gives with the same
#       parameters (θ_Y = 60°, η = 10, volume conserved, re-triangulation on), which must differ from
#       the input; the same island lifted off the plane must be refused with the loop named and no
#       output written.
#   headless_test.sh retriangulate-same-as-cli PREFIX WORKDIR SDFLOW COMPARE_MESHES
#       "Surface diffusion: re-triangulate" on two overlapping spheres and a small one apart (made by
#       `sdflow shape`) must give the surface `sdflow retriangulate` gives with the same parameters,
#       for three settings, each changing the number of vertices.
#   headless_test.sh nothing-left PREFIX WORKDIR MESH
#       "Surface diffusion: re-triangulate" on MESH with a minimum component size no component
#       reaches: meshlabserver must exit non-zero, its log must give the reason, and no output file
#       may be written.
#   headless_test.sh example PREFIX WORKDIR MESH
#       meshlab_plugin/examples/run_headless.sh with the shipped surface_diffusion.mlx on MESH: the
#       output must be written, differ from the input, and carry per-vertex normals and quality (H).
#   headless_test.sh bad-choice PREFIX WORKDIR MESH
#       "Surface diffusion N steps" on MESH with a mean curvature index past the last choice:
#       meshlabserver must exit non-zero, its log must name the choices, and no output file may be
#       written.
set -euo pipefail
case_name=$1 prefix=$2 work=$3

rm -rf "$work"
mkdir -p "$work"

fail() { echo "headless_test $case_name: FAILED: $*" >&2; exit 1; }

# shellcheck source=SCRIPTDIR/diffusion_filter_mlx.sh
source "$(dirname "${BASH_SOURCE[0]}")/diffusion_filter_mlx.sh"

# Writes a filter script for "Surface diffusion N steps": FILE, then the settings of
# diffusion_filter_mlx (diffusion_filter_mlx.sh).
write_diffusion_script() {
  local file=$1
  shift
  { printf '<!DOCTYPE FilterScript>\n<FilterScript>\n'; diffusion_filter_mlx "$@"; printf '</FilterScript>\n'; } > "$file"
}

# Writes a filter script for "Surface diffusion: re-triangulate" giving every parameter:
# FILE EDGE_LENGTH REMESH_ITERATIONS ALWAYS_REBUILD FILL_HOLES MIN_COMPONENT_FACES
write_retriangulation_script() {
  cat > "$1" <<MLX
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Surface diffusion: re-triangulate">
  <Param type="RichFloat" name="EdgeLength" value="$2"/>
  <Param type="RichInt" name="RemeshIterations" value="$3"/>
  <Param type="RichBool" name="AlwaysRebuild" value="$4"/>
  <Param type="RichBool" name="FillHoles" value="$5"/>
  <Param type="RichInt" name="MinComponentFaces" value="$6"/>
 </filter>
</FilterScript>
MLX
}

# The vertex count in the header of a PLY file.
vertex_count() { grep -a -m 1 '^element vertex' "$1" | cut -d' ' -f3; }

# Fails unless the PLY file FILE has a different number of vertices than $work/input.ply.
expect_changed() {
  [[ $(vertex_count "$1") != $(vertex_count "$work/input.ply") ]] \
    || fail "$1 has the input's $(vertex_count "$1") vertices: nothing was re-triangulated"
}

# Fails unless the surfaces of the filter's runs NAME and OTHER differ (beyond float precision).
expect_different() {
  local status=0
  "$compare" "$work/$1.meshlab.ply" "$work/$2.meshlab.ply" > /dev/null 2>&1 || status=$?
  [[ $status -eq 1 ]] || fail "$2: the same surface as $1 (compare_meshes exit $status): the option did not reach the run"
}

# Writes the OFF files A and B (as sdflow writes them: "OFF", "V F 0", points, triangles) as one
# file OUT holding both surfaces.
join_off() {
  local a=$1 b=$2 out=$3 va fa vb fb
  read -r va fa _ < <(sed -n 2p "$a")
  read -r vb fb _ < <(sed -n 2p "$b")
  {
    printf 'OFF\n%d %d 0\n' $((va + vb)) $((fa + fb))
    sed -n "3,$((2 + va))p" "$a"
    sed -n "3,$((2 + vb))p" "$b"
    sed -n "$((3 + va)),$((2 + va + fa))p" "$a"
    sed -n "$((3 + vb)),$((2 + vb + fb))p" "$b" | awk -v offset="$va" '{ print 3, $2 + offset, $3 + offset, $4 + offset }'
  } > "$out"
}

# meshlabserver ARGS... under Xvfb; sets `status` to its exit code and keeps its console output.
# No wall-clock limit of its own: a hang is ctest's to stop (TIMEOUT in CMakeLists.txt).
run_meshlabserver() {
  status=0
  xvfb-run -a "$prefix/bin/meshlabserver" "$@" > "$work/console.txt" 2>&1 || status=$?
}

# Runs the filter with SETTINGS (those of write_diffusion_script after the file name) on
# $work/input.ply, and `sdflow run` with FLAGS..., then compares the two final surfaces; after
# `-- anisotropic ENERGY G FORMULA`, the anisotropic filter with those (anisotropic_filter_mlx);
# after `-- substrate Z ANGLE MOBILITY ENERGY G FORMULA`, the substrate filter (substrate_filter_mlx).
#   compare_with_cli NAME "SETTINGS" FLAGS... [-- anisotropic ENERGY G FORMULA | -- substrate ...]
compare_with_cli() {
  local name=$1 settings=$2; shift 2
  local steps flags=() filter=diffusion extra=()
  steps=$(cut -d' ' -f1 <<< "$settings")
  # FLAGS... -- FILTER SETTINGS...: the anisotropic or substrate filter with those settings.
  while [[ $# -gt 0 && $1 != -- ]]; do flags+=("$1"); shift; done
  [[ $# -eq 0 ]] || { filter=$2; shift 2; extra=("$@"); }
  {
    printf '<!DOCTYPE FilterScript>\n<FilterScript>\n'
    # shellcheck disable=SC2086 # the settings are words on purpose
    "${filter}_filter_mlx" "${extra[@]}" $settings
    printf '</FilterScript>\n'
  } > "$work/$name.mlx"
  run_meshlabserver -l "$work/$name.log" -i "$work/input.ply" -o "$work/$name.meshlab.ply" -s "$work/$name.mlx"
  [[ $status -eq 0 && -s "$work/$name.meshlab.ply" ]] || fail "$name: meshlabserver failed ($status): $(cat "$work/$name.log")"
  "$sdflow" --quiet run --input "$work/input.ply" --out "$work/$name.run" --steps "$steps" "${flags[@]}" > /dev/null \
    || fail "$name: sdflow run failed"
  local final
  final=$(ls "$work/$name.run"/snapshots/step_*.ply | tail -n 1)
  [[ $(basename "$final") == "$(printf 'step_%06d.ply' "$steps")" ]] || fail "$name: sdflow run stopped at $final"
  "$compare" "$final" "$work/$name.meshlab.ply" || fail "$name: the plugin's surface differs from sdflow run's"
}

case "$case_name" in
nonmanifold)
  data=$4
  write_diffusion_script "$work/diffusion.mlx" 3 true 0.001 0.5 false false false 0.1 0 0 false
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
  # Re-triangulation is on by default on both sides; the cases without it say so on both.
  compare_with_cli adaptive "12 true 0.001 0.5 false false false 0.1 0 0 false" --adaptive --beta 0.5 \
    --no-retriangulate
  compare_with_cli constant "8 false 0.05 0.5 true false false 0.1 0 0 false" --tau 0.05 --beta 0.5 --conserve-volume \
    --no-retriangulate
  # Half the mean edge length (0.61): the first step's surface has edges longer than 2ℓ.
  compare_with_cli retriangulated "4 true 0.001 0.5 false false true 0.3 0 0 false" --adaptive --beta 0.5 \
    --edge-length 0.3
  expect_changed "$work/retriangulated.meshlab.ply"
  # The constant case with one scheme option changed.
  compare_with_cli normal_integral "8 false 0.05 0.5 true false false 0.1 1 0 false" --tau 0.05 --beta 0.5 \
    --conserve-volume --curvature normal_integral --no-retriangulate
  compare_with_cli angle_sum "8 false 0.05 0.5 true false false 0.1 2 0 false" --tau 0.05 --beta 0.5 \
    --conserve-volume --curvature normal_integral_angle_sum --no-retriangulate
  compare_with_cli volume_gradient "8 false 0.05 0.5 true false false 0.1 0 1 false" --tau 0.05 --beta 0.5 \
    --conserve-volume --mass volume_gradient --no-retriangulate
  compare_with_cli extrapolated "8 false 0.05 0.5 true false false 0.1 0 0 true" --tau 0.05 --beta 0.5 \
    --conserve-volume --extrapolate --no-retriangulate
  for name in normal_integral angle_sum volume_gradient extrapolated; do
    expect_different constant "$name"
  done
  # The anisotropic filter: an ellipsoidal γ, and the same γ written as a formula.
  compare_with_cli ellipsoidal "8 false 0.05 0.5 true false false 0.1 0 0 false" --tau 0.05 --beta 0.5 \
    --conserve-volume --no-retriangulate --energy ellipsoidal --energy-g 1,1,4 -- anisotropic 1 "1, 1, 4" "1"
  compare_with_cli formula "8 false 0.05 0.5 true false false 0.1 0 0 false" --tau 0.05 --beta 0.5 \
    --conserve-volume --no-retriangulate --energy formula --energy-formula "1 + 0.05 * (nx^4 + ny^4 + nz^4)" \
    -- anisotropic 3 "1" "1 + 0.05 * (nx^4 + ny^4 + nz^4)"
  expect_different constant ellipsoidal
  echo "headless_test same-as-cli: the plugin's surfaces equal sdflow run's"
  ;;
substrate-same-as-cli)
  sdflow=$4 compare=$5
  "$sdflow" --quiet shape cuboid-island --a 2 --b 2 --c 0.5 --edge-length 0.2 -o "$work/island.ply" > /dev/null \
    || fail "sdflow shape failed"
  run_meshlabserver -i "$work/island.ply" -o "$work/input.ply"
  [[ $status -eq 0 && -s "$work/input.ply" ]] || fail "meshlabserver could not convert the island"
  compare_with_cli island "6 true 0.001 0.5 true false true 0.2 0 0 false" --adaptive --beta 0.5 --conserve-volume \
    --edge-length 0.2 --boundary substrate --substrate-z 0 --contact-angle 60 --contact-line-mobility 10 \
    -- substrate 0 60 10 0 "1, 1, 4" "1"
  "$compare" "$work/input.ply" "$work/island.meshlab.ply" > /dev/null 2>&1 && fail "the island did not change"
  # The plane 0.1 above the island's rim: refused before any step, naming the loop.
  { printf '<!DOCTYPE FilterScript>\n<FilterScript>\n'
    substrate_filter_mlx 0.1 60 10 0 "1, 1, 4" "1" 3 true 0.001 0.5 true false true 0.2 0 0 false
    printf '</FilterScript>\n'; } > "$work/lifted.mlx"
  run_meshlabserver -l "$work/lifted.log" -i "$work/input.ply" -o "$work/lifted.ply" -s "$work/lifted.mlx"
  [[ $status -ne 0 ]] || fail "meshlabserver exited with 0 with the rim off the substrate"
  grep -q "boundary loop 0 .* is not on the plane" "$work/lifted.log" \
    || fail "the log does not name the loop: $(cat "$work/lifted.log")"
  [[ ! -e "$work/lifted.ply" ]] || fail "an output file was written"
  echo "headless_test substrate-same-as-cli: the plugin's island equals sdflow run's; a rim off the plane is refused"
  ;;
retriangulate-same-as-cli)
  sdflow=$4 compare=$5
  "$sdflow" --quiet shape sphere --cx -0.6 --edge-length 0.25 -o "$work/left.off" > /dev/null || fail "sdflow shape failed"
  "$sdflow" --quiet shape sphere --cx 0.6 --edge-length 0.25 -o "$work/right.off" > /dev/null || fail "sdflow shape failed"
  "$sdflow" --quiet shape sphere --radius 0.4 --cy 3 --edge-length 0.25 -o "$work/small.off" > /dev/null \
    || fail "sdflow shape failed"
  join_off "$work/left.off" "$work/right.off" "$work/two.off"
  join_off "$work/two.off" "$work/small.off" "$work/spheres.off"
  run_meshlabserver -i "$work/spheres.off" -o "$work/input.ply"
  [[ $status -eq 0 && -s "$work/input.ply" ]] || fail "meshlabserver could not convert the spheres"
  # joined: the overlapping spheres become one; debris: the small sphere (58 triangles) is dropped as
  # smaller than 100; rebuilt: the surface is rebuilt from its points.
  #   NAME EDGE_LENGTH REMESH_ITERATIONS ALWAYS_REBUILD FILL_HOLES MIN_COMPONENT_FACES/the same as flags
  for settings in "joined 0.2 3 false true 16/--edge-length 0.2 --iterations 3 --min-component-faces 16" \
    "debris 0.3 2 false true 100/--edge-length 0.3 --iterations 2 --min-component-faces 100" \
    "rebuilt 0.3 2 true false 16/--edge-length 0.3 --iterations 2 --always-rebuild --no-fill-holes --min-component-faces 16"; do
    read -r name length iterations always fill faces <<< "${settings%%/*}"
    write_retriangulation_script "$work/$name.mlx" "$length" "$iterations" "$always" "$fill" "$faces"
    run_meshlabserver -l "$work/$name.log" -i "$work/input.ply" -o "$work/$name.meshlab.ply" -s "$work/$name.mlx"
    [[ $status -eq 0 && -s "$work/$name.meshlab.ply" ]] || fail "$name: meshlabserver failed ($status): $(cat "$work/$name.log")"
    # shellcheck disable=SC2086 # the flags are words on purpose
    "$sdflow" retriangulate "$work/input.ply" -o "$work/$name.cli.ply" ${settings#*/} > /dev/null \
      || fail "$name: sdflow retriangulate failed"
    "$compare" "$work/$name.cli.ply" "$work/$name.meshlab.ply" \
      || fail "$name: the plugin's surface differs from sdflow retriangulate's"
    expect_changed "$work/$name.meshlab.ply"
  done
  echo "headless_test retriangulate-same-as-cli: the plugin's surfaces equal sdflow retriangulate's"
  ;;
nothing-left)
  mesh=$4
  write_retriangulation_script "$work/retriangulate.mlx" 0 3 false true 1000000
  run_meshlabserver -l "$work/log.txt" -i "$mesh" -o "$work/out.ply" -s "$work/retriangulate.mlx"
  [[ $status -ne 0 ]] || fail "meshlabserver exited with 0 although no component is large enough"
  grep -q "nothing is left" "$work/log.txt" || fail "the log does not give the reason: $(cat "$work/log.txt")"
  [[ ! -e "$work/out.ply" ]] || fail "an output file was written"
  echo "headless_test nothing-left: exit code $status, reason logged, no output written"
  ;;
example)
  mesh=$4
  run_meshlabserver -i "$mesh" -o "$work/input.ply"
  [[ $status -eq 0 && -s "$work/input.ply" ]] || fail "meshlabserver could not convert $mesh"
  example=$(dirname "${BASH_SOURCE[0]}")/../examples
  MESHLABSERVER="$prefix/bin/meshlabserver" "$example/run_headless.sh" "$work/input.ply" \
    "$work/out.ply" > "$work/console.txt" 2>&1 || fail "run_headless.sh failed: $(cat "$work/console.txt")"
  ! cmp -s "$work/input.ply" "$work/out.ply" || fail "the output is the input: the filter did not run"
  for property in "property float nx" "property float quality"; do
    grep -a -q -m 1 "^$property" "$work/out.ply" || fail "the output has no '$property' (-m vn vq)"
  done
  echo "headless_test example: the shipped script ran; normals and quality kept"
  ;;
bad-choice)
  mesh=$4
  write_diffusion_script "$work/diffusion.mlx" 3 true 0.001 0.5 false false false 0.1 3 0 false
  run_meshlabserver -l "$work/log.txt" -i "$mesh" -o "$work/out.ply" -s "$work/diffusion.mlx"
  [[ $status -ne 0 ]] || fail "meshlabserver exited with 0 on a mean curvature index past the last choice"
  grep -qF "Curvature must be 0 (cotangent), 1 (normal_integral) or 2 (normal_integral_angle_sum), got 3" \
    "$work/log.txt" || fail "the log does not name the choices: $(cat "$work/log.txt")"
  [[ ! -e "$work/out.ply" ]] || fail "an output file was written"
  echo "headless_test bad-choice: exit code $status, choices logged, no output written"
  ;;
*)
  fail "unknown case (nonmanifold, same-as-cli, substrate-same-as-cli, retriangulate-same-as-cli, nothing-left, example, bad-choice)"
  ;;
esac
