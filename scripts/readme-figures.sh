#!/usr/bin/env bash
# Draws README's figures from finished sample runs (samples/reproduce.sh NAME first): for each run in
# runs/NAME, its plots (sdflow plot) and four snapshots with sdflow render, coloured by H:
#   docs/images/NAME_start.png         the initial surface
#   docs/images/NAME_before_event.png  the last snapshot before the first topology change (if any)
#   docs/images/NAME_after_event.png   the first snapshot after it (if any)
#   docs/images/NAME_middle.png        the snapshot nearest half the run's final time
#   docs/images/NAME_end.png           the last snapshot (sdflow render can draw)
# and docs/images/NAME_area_volume.png, NAME_curvature_deviation.png.
#   scripts/readme-figures.sh torus dumbbell sintering spheres_on_plane
set -euo pipefail
cd "$(dirname "$0")/.."
sdflow=${SDFLOW:-$PWD/build/release/cli/sdflow}
[[ -x $sdflow ]] || { echo "readme-figures: build sdflow first ($sdflow)" >&2; exit 1; }
[[ $# -gt 0 ]] || { echo "usage: $0 RUN_NAME..." >&2; exit 2; }

for name in "$@"; do
  run=runs/$name
  [[ -f $run/metrics.csv ]] || { echo "readme-figures: $run/metrics.csv is missing" >&2; exit 1; }
  # Snapshot steps on disk, and the step of the first topology change (components or genus) in
  # metrics.csv; a surgery that keeps the topology (a crossing of the initial mesh) is not the event.
  mapfile -t steps < <(ls "$run/snapshots" | sed -n 's/^step_0*\([0-9][0-9]*\)\.ply$/\1/p' | sort -n -u)
  event=$(awk -F, 'NR == 2 { c = $6; g = $7 } NR > 2 && ($6 != c || $7 != g) { print $1; exit }' "$run/metrics.csv")
  time_of() { awk -F, -v s="$1" 'NR > 1 && $1 == s { printf "%.4g", $2; exit }' "$run/metrics.csv"; }
  draw() { # step, picture name
    local file
    file=$(printf '%s/snapshots/step_%06d.ply' "$run" "$1")
    "$sdflow" render "$file" -o "docs/images/${name}_$2.png" --size 480,360 --title "$name, t = $(time_of "$1")"
  }
  draw "${steps[0]}" start
  # A run that stopped may have written the degenerate triangle that stopped it into its last
  # snapshot, which sdflow render refuses: the end is then the last snapshot it draws.
  for ((k = ${#steps[@]} - 1; k >= 0; --k)); do
    draw "${steps[k]}" end && break
    echo "readme-figures: $name: snapshot ${steps[k]} not drawn, the end is an earlier one" >&2
  done
  # The snapshot whose time is nearest half the final time.
  middle=$(for s in "${steps[@]}"; do echo "$s $(time_of "$s")"; done |
           awk -v half="$(awk -F, 'END { print $2 / 2 }' "$run/metrics.csv")" \
               '{ d = $2 - half; if (d < 0) d = -d; if (best == "" || d < bd) { best = $1; bd = d } } END { print best }')
  draw "$middle" middle
  if [[ -n $event ]]; then
    before=${steps[0]} after=""
    for s in "${steps[@]}"; do
      if (( s < event )); then before=$s; elif [[ -z $after ]]; then after=$s; fi
    done
    draw "$before" before_event
    [[ -n $after ]] && draw "$after" after_event
  fi
  "$sdflow" plot "$run" > /dev/null   # into $run/plots
  for plot in area_volume curvature_deviation; do
    cp "$run/plots/$plot.png" "docs/images/${name}_$plot.png"
  done
  echo "readme-figures: $name (first topology change at step ${event:-none})"
done
