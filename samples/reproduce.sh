#!/usr/bin/env bash
# Reproduces the paper's experiments from the scenarios in samples/: builds sdflow, meshes the
# initial surfaces (samples/make_meshes.sh), runs each scenario into runs/NAME, plots it, and prints
# one line per run: steps, final time, area and volume change, final curvature deviation, the
# topology (components/genus, first -> last) and the re-triangulation events. Progress on stderr:
# which scenario of how many, then each run's own progress (sdflow run's bar or a line every 10 s).
#   samples/reproduce.sh                    every experiment with sdflow's defaults (hours on 2 cores)
#   samples/reproduce.sh torus dumbbell     only these scenarios
#   samples/reproduce.sh --paper [NAME...]  the same with the paper's scheme (--preset paper), into
#                                           runs/NAME-paper: to compare with the paper's tables
set -euo pipefail
cd "$(dirname "$0")/.."
preset=() suffix=""
if [[ "${1:-}" == "--paper" ]]; then
  preset=(--preset paper) suffix=-paper
  shift
fi
if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build/release -j "$(nproc)" --target sdflow
sdflow=$PWD/build/release/cli/sdflow
samples/make_meshes.sh "$sdflow"

names=("$@")
[[ ${#names[@]} -gt 0 ]] || names=(sphere_accuracy ellipsoid_relax ellipsoid_quarter_beta ellipsoid_explicit torus
                                   dumbbell sintering spheres_on_plane compact_27 compact_100
                                   wulff_ellipsoid cubic_faceting anisotropic_dumbbell
                                   island_on_substrate island_breakup film_with_hole film_rim_breakup
                                   winterbottom_island)
index=0
for name in "${names[@]}"; do
  index=$((index + 1))
  echo "reproduce.sh: [$index/${#names[@]}] $name" >&2
  out=runs/$name$suffix
  rm -rf "$out"
  status=0
  "$sdflow" run "samples/$name.toml" --out "$out" "${preset[@]}" || status=$?
  [[ $status -eq 0 || $status -eq 3 ]] || exit "$status"   # 3: stopped as unstable (the explicit scheme)
  "$sdflow" plot "$out" > /dev/null
  awk -F, -v name="$name" -v status="$status" '
    NR == 2 { a0 = $8; v0 = $9; topo0 = $6 "/" $7 }
    NR > 1 { last = $0; split($15, ev, "+"); for (i in ev) if (ev[i] != "") n[ev[i]]++ }
    END {
      split(last, f, ",")
      events = ""
      for (e in n) events = events e " " n[e] " "
      printf "%-24s %s steps, t = %.4g, area %+.2f%%, volume (debris included) %+.3f%%, H_dev %.2f%%, components/genus %s -> %s/%s%s%s\n",
             name, f[1], f[2], 100 * (f[8] / a0 - 1), (v0 != 0 ? 100 * ((f[9] + f[14]) / v0 - 1) : 0), f[11], topo0, f[6], f[7],
             (events == "" ? "" : ", events: " events), (status == 3 ? " (stopped as unstable)" : "")
    }' "$out/metrics.csv"
done
