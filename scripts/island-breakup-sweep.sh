#!/usr/bin/env bash
# Long islands on a substrate breaking into several (issue 36, item 5): for each aspect ratio L/W
# and edge length, a ridge `sdflow shape cuboid-island --a L --b 1 --c 0.5 --radius 0.45` (W = 1; the
# rounding radius near W/2 makes its cross-section and its ends almost round) flows with
# boundary = "substrate", Young's angle θ_Y and contact-line mobility η to END_TIME; the table gives
# the islands at the end (components of the last row of metrics.csv), the time of the first break-up
# (the first row whose component count rose) and, for a run that stopped early, where and why. It goes
# between "<!-- tables: island-breakup -->" and "<!-- end of tables: island-breakup -->" in
# docs/validation.md (for η ≠ 1 between the markers named island-breakup-eta-η), with a line per
# edge length saying between which ratios the count changes.
# Runs are kept under build/island-breakup/ and reused when finished (--force re-runs them).
#   scripts/island-breakup-sweep.sh [--sdflow PATH] [--ratios "4 6 8 10 12"] [--edges "0.14 0.1 0.07"]
#                                   [--angle 90] [--mobility 1] [--end-time 2] [--force] [--print]
set -euo pipefail
main() {
cd "$(dirname "$0")/.."
sdflow=${SDFLOW:-build/release/cli/sdflow}
ratios=(4 6 8 10 12) edges=(0.14 0.1 0.07) angle=90 mobility=1 end_time=2 force=0 print=0
while (($#)); do
  case $1 in
    --sdflow) sdflow=$2; shift 2 ;;
    --ratios) read -r -a ratios <<< "$2"; shift 2 ;;
    --edges) read -r -a edges <<< "$2"; shift 2 ;;
    --angle) angle=$2; shift 2 ;;
    --mobility) mobility=$2; shift 2 ;;
    --end-time) end_time=$2; shift 2 ;;
    --force) force=1; shift ;;
    --print) print=1; shift ;;
    -h|--help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "island-breakup-sweep.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
number='^[0-9]+([.][0-9]+)?$'
for x in "${ratios[@]}" "${edges[@]}" "$angle" "$mobility" "$end_time"; do
  [[ $x =~ $number ]] || { echo "island-breakup-sweep.sh: '$x' is not a plain number" >&2; exit 2; }
done
[[ -x $sdflow ]] || { echo "island-breakup-sweep.sh: $sdflow not found (build it, or give --sdflow / SDFLOW)" >&2; exit 2; }
sdflow=$(realpath "$sdflow")
work=build/island-breakup
mkdir -p "$work"

run_one() { # RATIO EDGE
  local dir=$work/ratio_$1_edge_$2_angle_${angle}_eta_${mobility}_t_$end_time
  if [[ $force == 0 && -f $dir/seconds ]]; then echo "$dir"; return; fi
  rm -rf "$dir"
  mkdir -p "$dir"
  "$sdflow" -q shape cuboid-island --a "$1" --b 1 --c 0.5 --radius 0.45 --edge-length "$2" -o "$dir/start.ply" > "$dir/shape.log" 2>&1
  local start=$SECONDS status=0
  "$sdflow" -q run --input "$dir/start.ply" --out "$dir/run" --boundary substrate --contact-angle "$angle" \
    --contact-line-mobility "$mobility" --conserve-volume --end-time "$end_time" --snapshot-every 0 --quiet \
    > "$dir/run.log" 2>&1 || status=$?
  echo "$status" > "$dir/status"
  echo $((SECONDS - start)) > "$dir/seconds"
  echo "island-breakup-sweep.sh: L/W = $1, edge $2: exit $status after $((SECONDS - start)) s" >&2
  echo "$dir"
}

# The cell of one run: islands at the end, first break-up, and how a run that stopped early ended.
cell() { # DIR
  local dir=$1 metrics=$1/run/metrics.csv
  [[ -f $metrics ]] || { echo "no run ($(head -c 120 "$dir/run.log" 2>/dev/null | tr '\n|' '  '))"; return; }
  awk -F, -v status="$(cat "$dir/status")" -v end="$end_time" '
    NR == 2 { c = $6 }
    NR > 2 && $6 > c && !t { t = $2 }
    NR > 1 { last_c = $6; last_t = $2 }
    END {
      printf "%d", last_c
      if (t) printf ", first break-up at t = %.4g", t
      if (status != 0) printf ", stopped at t = %.4g (exit %d)", last_t, status
      else if (last_t < end * (1 - 1e-12)) printf ", ended at t = %.4g", last_t
    }' "$metrics"
}
vertices() { sed -n 2p "$1/run/metrics.csv" 2>/dev/null | cut -d, -f4 || echo "–"; }
final_count() { # DIR: the component count at the end, or "stopped" for a run that stopped early
  local status; status=$(cat "$1/status")
  [[ $status == 0 && -f $1/run/metrics.csv ]] && tail -n 1 "$1/run/metrics.csv" | cut -d, -f6 || echo stopped
}

table=$(mktemp)
trap 'rm -f "$table"' EXIT
declare -A dirs
for e in "${edges[@]}"; do
  for r in "${ratios[@]}"; do
    dirs[$r,$e]=$(run_one "$r" "$e")
  done
done
{
  echo "#### Islands 1 × 0.5 × L (rounding radius 0.45) on z = 0, θ_Y = $angle°, η = $mobility: islands at t = $end_time"
  echo
  header="| L/W |" rule="|---|"
  for e in "${edges[@]}"; do header+=" edge $e: islands; vertices at the start |"; rule+="---|"; done
  echo "$header wall time, finest |"
  echo "$rule---|"
  for r in "${ratios[@]}"; do
    row="| $r |"
    for e in "${edges[@]}"; do row+=" $(cell "${dirs[$r,$e]}"); $(vertices "${dirs[$r,$e]}") |"; done
    echo "$row $(cat "${dirs[$r,${edges[-1]}]}/seconds") s |"
  done
  echo
  # Where the count changes, per edge length: between consecutive ratios whose runs both reached the end.
  for e in "${edges[@]}"; do
    local changes="" previous="" previous_count=""
    for r in "${ratios[@]}"; do
      local count; count=$(final_count "${dirs[$r,$e]}")
      if [[ -n $previous && $count != stopped && $previous_count != stopped && $count != "$previous_count" ]]; then
        changes+="${changes:+, }$previous_count → $count between L/W = $previous and $r"
      fi
      previous=$r previous_count=$count
    done
    local stopped=0
    for r in "${ratios[@]}"; do [[ $(final_count "${dirs[$r,$e]}") == stopped ]] && stopped=$((stopped + 1)); done
    echo "- edge $e: ${changes:-no change of the count between ratios whose runs reached the end}; $stopped of ${#ratios[@]} runs stopped before t = $end_time."
  done
  echo
} > "$table"
cat "$table"
((print)) && return 0
doc=docs/validation.md
# One table per mobility: η = 1 between the markers "island-breakup", another η between "island-breakup-eta-η".
name=island-breakup
[[ $mobility == 1 ]] || name+="-eta-$mobility"
begin="<!-- tables: $name -->" end="<!-- end of tables: $name -->"
grep -qxF "$begin" "$doc" || { echo "island-breakup-sweep.sh: no $begin marker in $doc" >&2; exit 1; }
awk -v tables="$table" -v begin="$begin" -v end="$end" '
  $0 == begin { print; while ((getline line < tables) > 0) print line; skip = 1; next }
  $0 == end { skip = 0 }
  !skip { print }' "$doc" > "$doc.tmp" && mv "$doc.tmp" "$doc"
echo "island-breakup-sweep.sh: the table written to $doc" >&2
}
main "$@"
