#!/usr/bin/env bash
# Re-measures the axisymmetric reference solver's figures and writes them into docs/axisymmetric.md
# (between its "<!-- tables -->" markers): the sphere-mode rates (from the test suite), the torus's
# seal time under refinement in space and in time, the paper's dumbbell, capsule outcomes for L/D
# from 5 to 12 and the break-up threshold found by bisection. About ten minutes on 2 cores.
#   scripts/axisymmetric-reference.sh [--sdflow PATH]
set -euo pipefail
cd "$(dirname "$0")/.."

main() {
  local sdflow=build/release/cli/sdflow
  if [[ "${1:-}" == "--sdflow" ]]; then sdflow=$2; fi
  if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 0; fi
  [[ -x $sdflow ]] || { echo "axisymmetric-reference.sh: $sdflow not found: build first" >&2; exit 2; }
  local tests_binary
  tests_binary=$(dirname "$(dirname "$sdflow")")/tests/sdflow_tests

  json_value() { # KEY: the first number after "KEY" in JSON on stdin
    awk -v key="\"$1\"" 'index($0, key) { sub(/.*: */, ""); sub(/,$/, ""); print; exit }'
  }
  first_event() { "$sdflow" axisymmetric "$@" --json | json_value event_time; }
  timed() { # COMMAND...: prints "OUTPUT SECONDS"
    local start=$SECONDS out
    out=$("$@")
    echo "$out $((SECONDS - start))"
  }

  local tables
  tables=$(mktemp)
  {
    echo "#### Sphere modes (ε = ±0.01 averaged; spacing h, steps ≤ h/10 of the radius and of t_end)"
    echo
    echo "| h | l = 2 (exact 12) | l = 3 (exact 60) |"
    echo "|---|---|---|"
    local xml; xml=$(mktemp)
    "$tests_binary" --gtest_filter='AxisymmetricFlow.sphere_mode_rates_converge_to_12_and_60' --gtest_output="xml:$xml" > /dev/null
    for h in 0.1 0.05 0.025; do
      local r2 r3
      r2=$(grep -o "l2_h${h}_rate\" value=\"[^\"]*" "$xml" | sed 's/.*value="//')
      r3=$(grep -o "l3_h${h}_rate\" value=\"[^\"]*" "$xml" | sed 's/.*value="//')
      echo "| $h | $r2 ($(awk -v r="$r2" 'BEGIN { printf "%+.3f%%", 100 * (r - 12) / 12 }')) | $r3 ($(awk -v r="$r3" 'BEGIN { printf "%+.3f%%", 100 * (r - 60) / 60 }')) |"
    done
    rm -f "$xml"
    echo
    echo "#### Torus R = 3, r = 1.5: seal time t* (extrapolated in the step: 2 t*(δ/2) − t*(δ))"
    echo
    echo "| longest edge | edges per radius | δ = 0.01 | δ = 0.005 | δ = 0.0025 |"
    echo "|---|---|---|---|---|"
    for spacing in "0.09 8" "0.045 16" "0.0225 32"; do
      read -r h n <<< "$spacing"
      local row="| $h | $n |"
      for d in 0.01 0.005 0.0025; do
        row+=" $(first_event torus --major 3 --minor 1.5 --stop-at-first-event --max-edge "$h" --edges-per-radius "$n" --max-displacement "$d") |"
      done
      echo "$row"
    done
    echo
    echo "The paper's torus, R = 6, r = 3, seals at 16 times these times (the flow's scaling, t ∝ length⁴):"
    echo "\`sdflow axisymmetric torus --stop-at-first-event\` gives t* = $(first_event torus --stop-at-first-event)."
    echo
    echo "#### The paper's dumbbell (R = 6, neck width 1, centres 18 apart): pinch-off time"
    echo
    echo "| longest edge | edges per radius | t* | CPU |"
    echo "|---|---|---|---|"
    for spacing in "0.12 8" "0.06 16" "0.03 32"; do
      read -r h n <<< "$spacing"
      read -r t s < <(timed first_event dumbbell --stop-at-first-event --max-edge "$h" --edges-per-radius "$n")
      echo "| $h | $n | $t | $s s |"
    done
    echo
    echo "#### Capsules of radius 1, length L = 2 · (L/D): bodies at t = 50 and break-up times"
    echo
    echo "| L/D | bodies | first break-up t* | where (z) | CPU |"
    echo "|---|---|---|---|---|"
    for ratio in 5 6 7 7.5 8 9 10 12; do
      local start=$SECONDS out
      out=$("$sdflow" axisymmetric capsule --length-ratio "$ratio" --json)
      local bodies time z
      bodies=$(json_value bodies <<< "$out")
      time=$(json_value event_time <<< "$out")
      z=$(grep -o '"z" *: *[-0-9.e+]*' <<< "$out" | head -n 1 | sed 's/.*: *//' || true)
      echo "| $ratio | $bodies | ${time:-none} | ${z:-–} | $((SECONDS - start)) s |"
    done
    echo
    # Bisection of the threshold between the last ratio that stays whole and the first that breaks.
    local low=7 high=7.5
    for _ in 1 2 3; do
      local mid; mid=$(awk -v a="$low" -v b="$high" 'BEGIN { printf "%.4g", (a + b) / 2 }')
      if [[ $("$sdflow" axisymmetric capsule --length-ratio "$mid" --json | json_value bodies) -gt 1 ]]; then
        high=$mid
      else
        low=$mid
      fi
    done
    echo "Break-up threshold by bisection: a capsule with L/D = $low stays one body, one with L/D = $high breaks"
    echo "(Nichols 1976: about 7.2)."
    echo
    echo "#### Independent checks: the initial curves' bodies"
    echo
    echo "The curve each reference starts from (its default node count) against the exact measures of the"
    echo "3-D shape it stands for (tests/axisymmetric/test_initial_curves.cpp, which asserts 10⁻⁶ at 200 000 nodes)."
    echo
    echo "| shape | curve volume | shape volume | difference | curve area | shape area | difference |"
    echo "|---|---|---|---|---|---|---|"
    xml=$(mktemp)
    "$tests_binary" --gtest_filter='InitialCurves.*' --gtest_output="xml:$xml" > /dev/null
    property() { grep -o "\"$1\" value=\"[^\"]*" "$xml" | sed 's/.*value="//'; }
    relative() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%+.1e", (a - b) / b }'; }
    for shape in dumbbell torus capsule_5 capsule_7.5 capsule_8 capsule_9 capsule_10 capsule_12; do
      local cv sv ca sa
      cv=$(property "${shape}_curve_volume") sv=$(property "${shape}_shape_volume")
      ca=$(property "${shape}_curve_area") sa=$(property "${shape}_shape_area")
      echo "| ${shape//_/ L\/D = } | $cv | $sv | $(relative "$cv" "$sv") | $ca | $sa | $(relative "$ca" "$sa") |"
    done
    rm -f "$xml"
    echo
    echo "#### Independent checks: event times from another discretisation"
    echo
    echo "\`scripts/independent_reference.py\` solves the same flow for the generating curve written as a"
    echo "function on a fixed graded grid (the dumbbell's radius over its axis, the torus's tube in polar"
    echo "coordinates about its centre circle) by finite differences and SciPy's BDF: no code in common with"
    echo "the solver above. t* is extrapolated from the last approach to the axis (r⁴ linear in t)."
    echo
    echo "| shape | grid nodes | t* | this solver's finest (above) | difference |"
    echo "|---|---|---|---|---|"
    local finest_dumbbell finest_torus python
    python=$(command -v /usr/bin/python3 || command -v python3) # Debian's, with numpy and SciPy
    finest_dumbbell=$(first_event dumbbell --stop-at-first-event --max-edge 0.03 --edges-per-radius 32)
    finest_torus=$(first_event torus --major 3 --minor 1.5 --stop-at-first-event --max-edge 0.0225 --edges-per-radius 32 --max-displacement 0.0025)
    for nodes in 400 800 1600; do
      for shape in dumbbell torus; do
        local t ref
        t=$("$python" scripts/independent_reference.py "$shape" --nodes "$nodes" | json_value extrapolated_time)
        if [[ $shape == dumbbell ]]; then ref=$finest_dumbbell; else ref=$finest_torus; fi
        echo "| $shape | $nodes | $t | $ref | $(awk -v a="$t" -v b="$ref" 'BEGIN { printf "%+.4f%%", 100 * (b - a) / a }') |"
      done
    done
  } > "$tables"
  local doc=docs/axisymmetric.md
  awk -v tables="$tables" '
    /<!-- tables -->/ { print; while ((getline line < tables) > 0) print line; skip = 1; next }
    /<!-- end of tables -->/ { skip = 0 }
    !skip { print }' "$doc" > "$doc.tmp" && mv "$doc.tmp" "$doc"
  cat "$tables"
  rm -f "$tables"
}
main "$@"
