#!/usr/bin/env bash
# Runs sample scenarios with two sdflow binaries and compares what they record, byte for byte:
# each run's exit code, metrics.csv, events.log and its snapshots (.ply). For refactorings that
# must not change a single result ("bit-identical").
#   scripts/compare-runs.sh OLD_SDFLOW NEW_SDFLOW [SAMPLE...]
# SAMPLE is a scenario of samples/ (default: every one). The two large ones stop early: sintering
# after 30 steps, spheres_on_plane after 15 (override with STEPS_<name>=N, e.g. STEPS_torus=100;
# 0 = the scenario's own end). Wall times are not compared: timings.csv, and events.log's
# "time by stage" line.
# Meshes come from samples/make_meshes.sh, run with OLD_SDFLOW when missing. Exit 0 when every
# sample matches, 1 otherwise.
set -euo pipefail
if [[ $# -lt 2 || "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'
  [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]] && exit 0 || exit 2
fi
old=$(realpath "$1") new=$(realpath "$2")
shift 2
cd "$(dirname "$0")/.."
names=("$@")
if [[ ${#names[@]} -eq 0 ]]; then
  for file in samples/*.toml; do names+=("$(basename "$file" .toml)"); done
fi
declare -A default_steps=([sintering]=30 [spheres_on_plane]=15)
untimed() { grep -v ': time by stage: ' "$1" 2> /dev/null || true; }
samples/make_meshes.sh "$old"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
for name in "${names[@]}"; do
  [[ -f samples/$name.toml ]] || { echo "compare-runs: no scenario samples/$name.toml" >&2; exit 2; }
  var=STEPS_$name
  steps=${!var:-${default_steps[$name]:-0}}
  limit=()
  [[ $steps -gt 0 ]] && limit=(--steps "$steps")
  declare -A status=()
  for side in old new; do
    binary=$old
    [[ $side == new ]] && binary=$new
    status[$side]=0
    "$binary" run "samples/$name.toml" --out "$work/$side/$name" "${limit[@]}" --quiet \
      > "$work/$name.$side.out" 2>&1 || status[$side]=$?
  done
  differences=()
  [[ ${status[old]} == "${status[new]}" ]] || differences+=("exit code ${status[old]} -> ${status[new]}")
  cmp -s "$work/old/$name/metrics.csv" "$work/new/$name/metrics.csv" || differences+=(metrics.csv)
  # events.log less its wall-time line ("time by stage: ... s in all; ...").
  cmp -s <(untimed "$work/old/$name/events.log") <(untimed "$work/new/$name/events.log") || differences+=(events.log)
  # The snapshots written by both, and any written by one only.
  snapshots=$( (cd "$work/old/$name" 2>/dev/null && ls snapshots/*.ply; cd "$work/new/$name" 2>/dev/null && ls snapshots/*.ply) | sort -u)
  count=0
  for file in $snapshots; do
    count=$((count + 1))
    cmp -s "$work/old/$name/$file" "$work/new/$name/$file" || differences+=("$file")
  done
  last=$(tail -n 1 "$work/new/$name/metrics.csv" 2>/dev/null | cut -d, -f1)
  summary="${last:-no} steps${limit:+ (limited)}, exit ${status[new]}, $count snapshots"
  if [[ ${#differences[@]} -eq 0 ]]; then
    printf '%-24s identical: %s\n' "$name" "$summary"
  else
    printf '%-24s DIFFERENT (%s): %s\n' "$name" "$summary" "${differences[*]}"
    failed=1
  fi
  unset status
done
exit $failed
