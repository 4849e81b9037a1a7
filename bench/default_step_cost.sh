#!/usr/bin/env bash
# Cost of a re-triangulating run's step with sdflow's defaults against the paper's scheme
# (--preset paper) at the same vertex count: hyperfine times `sdflow run --retriangulate` for a
# fixed number of constant steps on tori of 15k and 60k vertices, alternating the two, and prints
# each median and their ratio. (The defaults add the cotangent H, which costs what eq. 9 does, and
# the curvature-adapted trigger, which computes κ on every step.)
#   bench/default_step_cost.sh [--sdflow PATH] [--runs N]
set -euo pipefail
cd "$(dirname "$0")/.."
sdflow=build/release/cli/sdflow runs=5
while (($#)); do
  case $1 in
    --sdflow) sdflow=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    *) echo "default_step_cost.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
command -v hyperfine > /dev/null || { echo "default_step_cost.sh: needs hyperfine (scripts/install-deps.sh --bench)" >&2; exit 2; }
sdflow=$(realpath "$sdflow")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for n in 15000 60000; do
  "$sdflow" -q shape torus --vertices "$n" -o "$work/torus_$n.ply"
  steps=$((n == 15000 ? 40 : 20))
  run="$sdflow -q run --input $work/torus_$n.ply --tau 0.01 --steps $steps --retriangulate --snapshot-every 0 --quiet"
  hyperfine -N -w 1 -r "$runs" --export-json "$work/$n.json" \
    --prepare "rm -rf $work/default $work/paper" \
    --command-name="defaults, $n vertices" "$run --out $work/default" \
    --command-name="--preset paper, $n vertices" "$run --out $work/paper --preset paper" > /dev/null
  python3 - "$work/$n.json" "$steps" <<'EOF'
import json, statistics, sys
results = json.load(open(sys.argv[1]))["results"]
steps = int(sys.argv[2])
medians = [statistics.median(r["times"]) for r in results]
for r, m in zip(results, medians):
    print(f"{r['command']}: median {m:.3f} s for {steps} steps ({1000 * m / steps:.1f} ms a step, start-up included)")
print(f"  ratio defaults / paper: {medians[0] / medians[1]:.2f}")
EOF
done
