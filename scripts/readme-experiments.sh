#!/usr/bin/env bash
# Writes README's table of the paper's experiments (between "<!-- experiments -->" and
# "<!-- end of experiments -->") from the sample runs on disk: runs/NAME (sdflow's defaults) and
# runs/NAME-paper (--preset paper), as samples/reproduce.sh [--paper] leaves them. Each measured
# cell is read from that run's metrics.csv and events.log; a run that is not on disk says so. With
# NAMEs, only those experiments' rows are measured again; the others stay as README has them.
#   samples/reproduce.sh torus && samples/reproduce.sh --paper torus && scripts/readme-experiments.sh
#   scripts/readme-experiments.sh spheres_on_plane     only its row
set -euo pipefail
cd "$(dirname "$0")/.."

# One line per experiment: NAME|paper section|what happens|the paper's figures. The volume is the
# material volume (docs/method.md): for the plane's open surface, closed by a cap over its rim.
experiments=(
  "sphere_accuracy|§4.4|unit sphere, 2562 vertices, τ = 5·10⁻⁵, 50 steps|D1, D2 fall (Table 4)"
  "ellipsoid_relax|§4.5|5/4/3 ellipsoid relaxes toward a sphere (adaptive τ)|H_dev falls, area falls, volume kept"
  "ellipsoid_quarter_beta|§4.5, Fig. 25|β = 1/4, τ = 0.5|H_dev grows: unstable"
  "ellipsoid_explicit|§4.5, Fig. 24|β = 0, τ = 0.5|unstable at once"
  "dumbbell|§3.2.2, Fig. 6|the neck pinches off; two bodies relax toward spheres|pinch-off (time not given)"
  "torus|§4.1, Figs. 8–9|the hole seals (genus 1 → 0), then a sphere, under Table 1|seal at t = 83.2; area −30%, volume 1%, H_dev 1%"
  "sintering|§4.2, Figs. 11–16|eight spheres (genus 5) under Table 2 to its end: the windows close, the void separates|volume 0.6%"
  "spheres_on_plane|§4.3, Figs. 17–22, App. B|three spheres on a plane (with boundary, genus 3) under Table 3 to t = 774.6|the holes seal; a bubble separates and merges back (t = 187.3)"
)

# The measured cell of one run: how it ended, its steps and time, each topology change, the area,
# volume and curvature deviation at the end relative to the start, and D1/D2 (§4.4) for a run that
# starts on its reference sphere.
measure() { # RUN_DIR
  local run=$1
  [[ -f $run/metrics.csv ]] || { echo "not run"; return; }
  local stopped=""
  if grep -q ': stopped: re-triangulation' "$run/events.log" 2>/dev/null; then
    stopped="stops (a re-triangulation failed) after"
  elif grep -q ': stopped: ' "$run/events.log" 2>/dev/null; then
    stopped="stops (numerical failure) after"
  elif tail -n 3 "$run/events.log" 2>/dev/null | grep -q ': interrupted: '; then
    stopped="interrupted (to go on: sdflow run --resume DIR) after"
  fi
  awk -F, -v stopped="$stopped" '
    NR == 2 { a0 = $8; v0 = $9; c = $6; g = $7; h0 = $11; on_sphere = ($12 + 0 < 1e-3) }
    NR > 2 {
      if ($7 != g || $6 != c) {
        changes = changes sprintf("%s%s t = %.4g", (changes == "" ? "" : "; "),
                                  ($7 < g ? "genus " g " → " $7 : ($6 > c ? c " → " $6 " bodies" : ($6 < c ? c " → " $6 " bodies" : "genus " g " → " $7))), $2)
        c = $6; g = $7
      }
    }
    NR > 1 { last = $0; if ($15 ~ /fallback/) fallbacks++ }
    END {
      split(last, f, ",")
      printf "%s%s steps to t = %.4g", (stopped == "" ? "" : stopped " "), f[1], f[2]
      if (changes != "") printf " (%s)", changes
      printf ": area %+.2f%%, ", 100 * (f[8] / a0 - 1)
      printf "volume %+.3f%%, ", (v0 != 0 ? 100 * (f[9] / v0 - 1) : 0)
      printf "H_dev %.3g%% → %.3g%%", h0, f[11]
      if (on_sphere) printf ", D1 %.2g, D2 %.2g", f[12], f[13] # only for a run that starts on the reference sphere
      if (fallbacks) printf "; %d table step(s) failed, covered by adaptive steps", fallbacks
    }' "$run/metrics.csv"
}

readme=README.md
grep -q '<!-- experiments -->' "$readme" || { echo "readme-experiments: no <!-- experiments --> marker in $readme" >&2; exit 1; }
only=" $* "
for name in "$@"; do
  printf '%s\n' "${experiments[@]}" | grep -q "^$name|" || { echo "readme-experiments: no experiment $name" >&2; exit 2; }
done

table=$(mktemp)
trap 'rm -f "$table"' EXIT
{
  echo "| scenario | paper | what happens | the paper | measured, defaults | measured, \`--preset paper\` |"
  echo "|---|---|---|---|---|---|"
  for line in "${experiments[@]}"; do
    IFS='|' read -r name section what paper <<< "$line"
    if [[ $# -gt 0 && $only != *" $name "* ]]; then
      awk '/<!-- experiments -->/ { inside = 1; next } /<!-- end of experiments -->/ { inside = 0 } inside' "$readme" |
        grep -m 1 -F "| \`$name\` |" || echo "| \`$name\` | $section | $what | $paper | not run | not run |"
      continue
    fi
    echo "| \`$name\` | $section | $what | $paper | $(measure "runs/$name") | $(measure "runs/$name-paper") |"
  done
} > "$table"

awk -v table="$table" '
  /<!-- experiments -->/ { print; while ((getline line < table) > 0) print line; skip = 1; next }
  /<!-- end of experiments -->/ { skip = 0 }
  !skip { print }' "$readme" > "$readme.tmp" && mv "$readme.tmp" "$readme"
cat "$table"
