#!/usr/bin/env bash
# Re-runs the validation of the 3-D flow against exact references and writes the tables of
# docs/validation.md (each section between its "<!-- tables: NAME -->" markers, when all its runs
# finished; --only NAME re-measures one section and leaves the others) from what it measured:
#   - the torus R = 3, r = 1.5 (R/r = 2; the paper's R = 6, r = 3 is the same shape, its times 16× these):
#     when its hole seals, at three resolutions, with the defaults and with --preset paper;
#   - the paper's dumbbell (samples/dumbbell.toml's shape): when its neck pinches off, likewise;
#   - capsules of radius 1 and length L (L/D from 5 to 12): how many bodies they break into, and when,
#     at three edge lengths with the defaults and at one with --preset paper;
#   - the axisymmetric reference (`sdflow axisymmetric`) for each, computed in 1-D;
#   - the sphere-mode rates and the remeshed tori's curvature errors, from the test suite's measurements.
# Each run's directory is kept under build/validation/ and reused when it finished, so a second call
# only redraws the tables; --force re-runs everything. Runs go two at a time (--jobs N to change).
# --tables-only redraws the tables from the runs on disk without starting any (unfinished ones show "–").
# --with "FLAGS" adds run flags to every run with the defaults (e.g. --with --retriangulate-local) and
# keeps those runs under build/validation-with/; the tables are then printed, not written to the doc.
#   scripts/validation.sh [--jobs N] [--force] [--tables-only] [--only modes|torus|dumbbell|capsules] [--sdflow PATH]
#                         [--with "FLAGS"]
set -euo pipefail
# Everything runs inside main(), which bash reads whole before it starts: editing this file while a
# validation runs cannot change what the running one does.
main() {
cd "$(dirname "$0")/.."

jobs=2 force=0 tables_only=0 only="" sdflow=build/release/cli/sdflow with=""
while (($#)); do
  case $1 in
    --jobs) jobs=$2; shift 2 ;;
    --force) force=1; shift ;;
    --tables-only) tables_only=1; shift ;;
    --only) only=$2; shift 2 ;;
    --sdflow) sdflow=$2; shift 2 ;;
    --with) with=$2; shift 2 ;;
    -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "validation.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
[[ -x $sdflow ]] || { echo "validation.sh: $sdflow not found: build first (scripts/test.sh builds build/release)" >&2; exit 2; }
sdflow=$(realpath "$sdflow")
# The flags are split into words, never evaluated: only option-like words are taken.
[[ $with =~ ^[A-Za-z0-9._=\ -]*$ ]] || { echo "validation.sh: --with takes run flags (letters, digits, . _ = -), got '$with'" >&2; exit 2; }
work=build/validation
[[ -z $with ]] || work=build/validation-with
mkdir -p "$work"
if [[ -n $with ]]; then
  # Runs made with other flags are not reused.
  [[ -f $work/flags && $(cat "$work/flags") == "$with" ]] || force=1
  echo "$with" > "$work/flags"
fi
work=$(realpath "$work")

torus_vertices=(5000 15000 30000)
dumbbell_vertices=(5000 10000 20000 40000)
capsule_ratios=(5 6 7 7.5 8 9 10 12)
capsule_edges=(0.2 0.15 0.11 0.08)
paper_capsule_edge=0.13

# --- the runs -----------------------------------------------------------------------------------
# One line per run: NAME MESH_COMMAND... ;; RUN_FLAGS...
plan=()
want() { [[ -z $only || $only == "$1" ]]; }
if want torus; then
  for n in "${torus_vertices[@]}"; do
    for scheme in default paper; do
      plan+=("torus_${n}_$scheme|shape torus --major 3 --minor 1.5 --vertices $n|--end-time 8 --stop-at-topology-change --preset $scheme")
    done
  done
fi
if want torus; then # the whole run: R = 6, r = 3 to the end of the paper's Table 1, t = 559, is t = 34.9 here
  plan+=("torus_15000_full|shape torus --major 3 --minor 1.5 --vertices 15000|--end-time 34.9375 --preset default")
fi
if want dumbbell; then
  for n in "${dumbbell_vertices[@]}"; do
    for scheme in default paper; do
      plan+=("dumbbell_${n}_$scheme|shape dumbbell --vertices $n --edges-per-radius 4|--end-time 0.6 --stop-at-topology-change --preset $scheme")
    done
  done
fi
if want capsules; then
  for ratio in "${capsule_ratios[@]}"; do
    half=$(awk -v x="$ratio" 'BEGIN { print x - 1 }') # half-length of the axis segment, radius 1
    box=$(awk -v x="$ratio" 'BEGIN { printf "%g,-1.5,-1.5,%g,1.5,1.5", -x - 0.5, x + 0.5 }')
    expr="sqrt(max(abs(x)-$half,0)^2+y^2+z^2)-1"
    for h in "${capsule_edges[@]}"; do
      plan+=("capsule_${ratio}_${h}_default|shape --expr $expr --box $box --edge-length $h|--end-time 50 --preset default")
    done
    plan+=("capsule_${ratio}_${paper_capsule_edge}_paper|shape --expr $expr --box $box --edge-length $paper_capsule_edge|--end-time 50 --preset paper")
  done
fi

if [[ -n $with ]]; then
  for k in "${!plan[@]}"; do
    [[ ${plan[k]} == *"--preset default"* ]] && plan[k]="${plan[k]} $with"
  done
fi

run_one() { # NAME|MESH ARGS|RUN ARGS
  local name=${1%%|*} rest=${1#*|}
  local mesh_args=${rest%%|*} run_args=${rest#*|}
  local dir=$work/$name
  [[ -n $name ]] || return 0
  # A run that finished, or failed (deterministically, with the same binary), is not run again
  # unless --force.
  if [[ $force == 0 && ( -f $dir/done || -f $dir/failed ) ]]; then return 0; fi
  rm -rf "$dir"
  mkdir -p "$dir"
  # shellcheck disable=SC2086 # the argument lists are ours, split on purpose
  "$sdflow" -q $mesh_args -o "$dir/start.ply" > "$dir/shape.log" 2>&1
  local start=$SECONDS
  # shellcheck disable=SC2086
  if "$sdflow" -q run --input "$dir/start.ply" --out "$dir/run" --retriangulate --snapshot-every 0 --quiet \
      $run_args > "$dir/run.log" 2>&1; then
    echo $((SECONDS - start)) > "$dir/seconds"
    touch "$dir/done"
  else
    echo $((SECONDS - start)) > "$dir/seconds"
    grep -m1 "error:" "$dir/run.log" > "$dir/failed" || echo "stopped without an error line" > "$dir/failed"
    echo "validation.sh: $name failed (see $dir/run.log)" >&2
  fi
}
export -f run_one
export sdflow work force
if ((${#plan[@]} > 0 && !tables_only)); then
  printf '%s\n' "${plan[@]}" | xargs -d '\n' -P "$jobs" -I{} bash -c 'run_one "$1"' _ {}
fi

# --- what the runs measured ---------------------------------------------------------------------
# Only finished runs count: an unfinished one (killed, or still running) shows "–". A failed run
# (its sdflow stopped with an error) counts as finished: its table cell says where it stopped.
finished() { [[ -f $work/$1/done || -f $work/$1/failed ]]; }
metrics() { finished "$1" && echo "$work/$1/run/metrics.csv" || echo "$work/$1/unfinished"; }
# Time of the first row after which the genus fell (a hole sealed) or the component count rose.
event_time() { # NAME genus|components
  local file; file=$(metrics "$1")
  [[ -f $file ]] || { echo "–"; return; }
  local failed=0; [[ -f $work/$1/failed ]] && failed=1
  awk -F, -v what="$2" -v failed="$failed" 'NR == 2 { g = $7; c = $6 } NR > 2 && ((what == "genus" && $7 < g) || (what == "components" && $6 > c)) { printf "%.6g", $2; found = 1; exit } { last = $2 } END { if (!found) { if (failed) printf "failed before it, at %.6g", last; else printf "none" } }' "$file"
}
final_components() {
  local f; f=$(metrics "$1")
  if [[ -f $work/$1/failed ]]; then echo "stopped"; elif [[ -f $f ]]; then tail -n 1 "$f" | cut -d, -f6; else echo "–"; fi
}
vertices() { local f; f=$(metrics "$1"); [[ -f $f ]] && sed -n 2p "$f" | cut -d, -f4 || echo "–"; }
volume_drift() { # relative change from the first row to the last, in %
  local f; f=$(metrics "$1")
  [[ -f $f ]] || { echo "–"; return; }
  awk -F, 'NR == 2 { v0 = $9 } END { printf "%+.3f%%", 100 * ($9 - v0) / v0 }' "$f"
}
seconds() { [[ -f $work/$1/seconds ]] && echo "$(cat "$work/$1/seconds") s" || echo "–"; }
# Richardson extrapolation of three values at resolutions h1 > h2 > h3 with h ∝ n^(-1/2) (vertex counts) or
# given edge lengths, assuming a power law in h: prints the extrapolated value and the observed order
# (an observed order below 1 means the three are not yet in the asymptotic range: the finest value is
# printed instead).
extrapolate() { # h1 v1 h2 v2 h3 v3
  awk -v h1="$1" -v a="$2" -v h2="$3" -v b="$4" -v h3="$5" -v c="$6" '
    function gap(p) { return (h1^p - h2^p) / (h2^p - h3^p) - (a - b) / (b - c) }
    BEGIN {
      if (a !~ /^[0-9.]+$/ || b !~ /^[0-9.]+$/ || c !~ /^[0-9.]+$/) { print "–"; exit }
      if ((a - b) * (b - c) <= 0) { printf "%.4g (not monotone)", c; exit }
      lo = 0.25; hi = 4; flo = gap(lo)
      if (flo * gap(hi) > 0) { printf "%.4g (order outside [0.25, 4])", c; exit }
      for (i = 0; i < 60; ++i) { p = (lo + hi) / 2; f = gap(p); if (f * flo > 0) { lo = p; flo = f } else hi = p }
      if (p < 1) { printf "%.4g (order %.2g: not asymptotic, finest value)", c, p; exit }
      printf "%.4g (order %.2g)", c - (b - c) / (h2^p - h3^p) * h3^p, p
    }'
}
reference() { # axisymmetric ARGS...: "BODIES T*" of the 1-D reference (T* of the first event), or "– –"
  { "$sdflow" axisymmetric "$@" --json 2>/dev/null || true; } |
    awk 'match($0, /"event_time" *: *[-0-9.eE+]+/) { s = substr($0, RSTART, RLENGTH); sub(/.*: */, "", s); t = s }
         match($0, /"bodies" *: *[0-9]+/) { s = substr($0, RSTART, RLENGTH); sub(/.*: */, "", s); b = s }
         END { printf "%s %s\n", (b == "" ? "–" : b), (t == "" ? (b == "" ? "–" : "none") : sprintf("%.5g", t)) }'
}
relative_error() { # VALUE REFERENCE
  awk -v x="$1" -v r="$2" 'BEGIN { if (r + 0 > 0 && x + 0 > 0) printf "%+.1f%%", 100 * (x - r) / r; else printf "–" }'
}
# The table of one shape's event times at each vertex count, defaults and paper beside the reference.
event_table() { # NAME genus|components REFERENCE VERTEX_COUNTS...
  local name=$1 what=$2 ref=$3 d=() p=() n a b
  shift 3
  echo "| vertices | default | error | order | --preset paper | error | volume drift (default) | wall time default / paper |"
  echo "|---|---|---|---|---|---|---|---|"
  local previous_h="" previous_a=""
  for n in "$@"; do
    a=$(event_time "${name}_${n}_default" "$what") b=$(event_time "${name}_${n}_paper" "$what")
    d+=("$(h_of "$n")" "$a") p+=("$(h_of "$n")" "$b")
    echo "| $(vertices "${name}_${n}_default") | $a | $(relative_error "$a" "$ref") | $(observed_order "$previous_h" "$previous_a" "$(h_of "$n")" "$a" "$ref") | $b | $(relative_error "$b" "$ref") | $(volume_drift "${name}_${n}_default") | $(seconds "${name}_${n}_default") / $(seconds "${name}_${n}_paper") |"
    previous_h=$(h_of "$n") previous_a=$a
  done
  # From the three finest resolutions: the coarser ones are the farthest from the asymptotic range.
  echo "| extrapolated | $(extrapolate "${d[@]: -6}") | | | $(extrapolate "${p[@]: -6}") | | | |"
  echo
}
# The observed order of the error against the reference between two resolutions, log(e1/e2) / log(h1/h2).
observed_order() { # H1 V1 H2 V2 REFERENCE
  awk -v h1="$1" -v a="$2" -v h2="$3" -v b="$4" -v r="$5" 'BEGIN {
    if (h1 == "" || a !~ /^[0-9.]+$/ || b !~ /^[0-9.]+$/ || r + 0 <= 0 || a == r || b == r) { printf "–"; exit }
    q = (a - r) / (b - r)
    if (q <= 0) printf "–"; else printf "%.2g", log(q) / log(h1 / h2) }'
}
h_of() { awk -v n="$1" 'BEGIN { printf "%.6g", 1 / sqrt(n) }'; } # resolution from a vertex count

# Test properties (gtest's XML output) of the measurements the test suite makes anyway.
tests_binary=$(dirname "$(dirname "$sdflow")")/tests/sdflow_tests
properties() { # FILTER: prints NAME VALUE lines
  local xml; xml=$(mktemp)
  "$tests_binary" --gtest_filter="$1" --gtest_output="xml:$xml" > /dev/null 2>&1 || true
  grep -o 'property name="[^"]*" value="[^"]*"' "$xml" | sed 's/property name="\([^"]*\)" value="\([^"]*\)"/\1 \2/'
  rm -f "$xml"
}

# Each section's table goes to its own file, then between its markers in the doc.
tables_dir=$(mktemp -d)
{
  if want modes && [[ -x $tests_binary ]]; then
    echo "#### Sphere modes (3-D flow, defaults, extrapolated steps, ±ε averaged, ε = 0.01)"
    echo
    echo "| vertices | l = 2: rate (exact 12) | error | l = 3: rate (exact 60) | error |"
    echo "|---|---|---|---|---|"
    props=$(properties 'FlowStep.sphere_mode_rates_12_and_60_converge_with_the_defaults')
    for n in 162 642 2562; do
      r2=$(awk -v k="l2_vertices_${n}_rate" '$1 == k { print $2 }' <<< "$props")
      r3=$(awk -v k="l3_vertices_${n}_rate" '$1 == k { print $2 }' <<< "$props")
      echo "| $n | $r2 | $(awk -v r="$r2" 'BEGIN { printf "%+.2f%%", 100 * (r - 12) / 12 }') | $r3 | $(awk -v r="$r3" 'BEGIN { printf "%+.2f%%", 100 * (r - 60) / 60 }') |"
    done
    echo
    echo "#### Mean curvature on remeshed tori R = 3, r = 1.5: largest band-averaged error of H"
    echo
    echo "| edge length | vertices | eq. (9) | cotangent (the default) |"
    echo "|---|---|---|---|"
    props=$(properties 'CotangentCurvature.its_error_averages_out_on_remeshed_tori_where_eq9_is_biased')
    # property names: edge_H_vertices_N_{eq9,cotangent}_band_bias
    awk '{ split($1, k, "_"); key = k[2] " " k[4]; if ($1 ~ /eq9/) e9[key] = $2; else ct[key] = $2 }
         END { for (key in e9) { split(key, hv, " "); printf "| %s | %s | %s | %s |\n", hv[1], hv[2], e9[key], ct[key] } }' <<< "$props" |
      sort -t'|' -k2,2gr
    echo
  fi
} > "$tables_dir/modes"
{
  if want torus; then
    ref=$(reference torus --major 3 --minor 1.5 --stop-at-first-event | cut -d' ' -f2)
    echo "#### Torus R = 3, r = 1.5: time at which the hole seals"
    echo
    echo "1-D reference (\`sdflow axisymmetric torus --major 3 --minor 1.5\`): **$ref** (the paper's R = 6, r = 3: 16× that)."
    echo "The paper reports 83.2 for R = 6, r = 3, that is $(awk 'BEGIN { printf "%.4g", 83.2 / 16 }') here."
    echo
    event_table torus genus "$ref" "${torus_vertices[@]}"
    echo "The whole run with the defaults (15k vertices, to t = 34.94, the end of the paper's Table 1 scaled by"
    echo "1/16): genus $(awk -F, 'NR == 2 { print $7 }' "$(metrics torus_15000_full)" 2>/dev/null) → $(tail -n 1 "$(metrics torus_15000_full)" 2>/dev/null | cut -d, -f7),"
    echo "volume drift $(volume_drift torus_15000_full) without \`--conserve-volume\`, $(tail -n 1 "$(metrics torus_15000_full)" 2>/dev/null | cut -d, -f1) steps, $(seconds torus_15000_full)."
    echo
  fi
} > "$tables_dir/torus"
{
  if want dumbbell; then
    ref=$(reference dumbbell --stop-at-first-event | cut -d' ' -f2)
    echo "#### The paper's dumbbell (R = 6, neck width 1, centres 18 apart): time at which the neck pinches off"
    echo
    echo "1-D reference (\`sdflow axisymmetric dumbbell\`): **$ref**."
    echo
    event_table dumbbell components "$ref" "${dumbbell_vertices[@]}"
  fi
} > "$tables_dir/dumbbell"
{
  if want capsules; then
    echo "#### Capsules of radius 1 (D = 2), length L: bodies at the end (t = 50) and time of the first break-up"
    echo
    header="| L/D | 1-D reference |"
    rule="|---|---|"
    for h in "${capsule_edges[@]}"; do header+=" default, edge $h |"; rule+="---|"; done
    header+=" order, finest two | default, extrapolated t | --preset paper, edge $paper_capsule_edge | wall time (default, finest) |"; rule+="---|---|---|---|"
    echo "$header"
    echo "$rule"
    for ratio in "${capsule_ratios[@]}"; do
      read -r ref_bodies ref_t < <(reference capsule --length-ratio "$ratio")
      row="| $ratio | $ref_bodies, t = $ref_t |"
      local points=()
      for h in "${capsule_edges[@]}"; do
        local t; t=$(event_time "capsule_${ratio}_${h}_default" components)
        row+=" $(final_components "capsule_${ratio}_${h}_default"), t = $t |"
        points+=("$h" "$t")
      done
      row+=" $(observed_order "${points[@]: -4:1}" "${points[@]: -3:1}" "${points[@]: -2:1}" "${points[@]: -1}" "$ref_t") |"
      row+=" $(extrapolate "${points[@]: -6}") |"
      row+=" $(final_components "capsule_${ratio}_${paper_capsule_edge}_paper"), t = $(event_time "capsule_${ratio}_${paper_capsule_edge}_paper" components) |"
      row+=" $(seconds "capsule_${ratio}_${capsule_edges[-1]}_default") |"
      echo "$row"
    done
    echo
  fi
} > "$tables_dir/capsules"

# A section measured by this call replaces the text between its markers, "<!-- tables: NAME -->" and
# "<!-- end of tables: NAME -->"; the other sections and the prose around them stay as they are.
doc=docs/validation.md
# A section is written only when every one of its runs finished: a table in the doc comes from one
# complete measurement, never from a mix of new runs and dashes.
unfinished() { # PREFIX: how many of the plan's runs named PREFIX* have not finished
  local entry count=0
  for entry in "${plan[@]}"; do
    [[ ${entry%%|*} == "$1"* ]] && ! finished "${entry%%|*}" && count=$((count + 1))
  done
  echo "$count"
}
declare -A run_prefix=([modes]=none [torus]=torus_ [dumbbell]=dumbbell_ [capsules]=capsule_)
for section in modes torus dumbbell capsules; do
  [[ -s $tables_dir/$section ]] || continue
  missing=$(unfinished "${run_prefix[$section]}")
  if ((missing > 0)); then
    echo "validation.sh: the $section tables are not written to $doc: $missing of its runs did not finish"
  elif [[ -z $with && -f $doc ]] && grep -q "<!-- tables: $section -->" "$doc"; then
    awk -v tables="$tables_dir/$section" -v begin="<!-- tables: $section -->" -v end="<!-- end of tables: $section -->" '
      $0 == begin { print; while ((getline line < tables) > 0) print line; skip = 1; next }
      $0 == end { skip = 0 }
      !skip { print }' "$doc" > "$doc.tmp" && mv "$doc.tmp" "$doc"
    echo "validation.sh: the $section tables written to $doc"
  fi
  cat "$tables_dir/$section"
done
rm -rf "$tables_dir"
}
main "$@"
