#!/usr/bin/env bash
# What the refinement factor s costs (issue 30's target: a step within 1.3x of the unrefined
# step's cost at equal vertex count): runs the paper's dumbbell (R = 6, neck width 1) to its
# pinch-off with the defaults (s automatic, docs/method.md "Resolution") and with --refinement 1
# (edges per radius and displacement bound as given, as before s), at two vertex counts, and prints
# per run the pinch-off time, the steps, the mean vertex count over the steps, the whole run's CPU
# time (user + system, all threads; median over the repeats) and per step, a step's CPU time per
# 1000 vertices, and the ratios of the defaults to --refinement 1. CPU, not wall time: the figures
# stay readable on a busy machine.
#   bench/refinement_cost.sh [--sdflow PATH] [--runs N] [--vertices "N1 N2 ..."]
set -euo pipefail
cd "$(dirname "$0")/.."
sdflow=build/release/cli/sdflow runs=3 counts="10000 20000"
while (($#)); do
  case $1 in
    --sdflow) sdflow=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --vertices) counts=$2; shift 2 ;;
    *) echo "refinement_cost.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
sdflow=$(realpath "$sdflow")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for n in $counts; do
  "$sdflow" -q shape dumbbell --vertices "$n" -o "$work/dumbbell_$n.ply"
  for variant in defaults unrefined; do
    extra=()
    [[ $variant == unrefined ]] && extra=(--refinement 1)
    for ((r = 1; r <= runs; ++r)); do
      out=$work/${variant}_${n}_$r
      # GNU time's user + system of the whole process (start-up and files included).
      /usr/bin/time -f "%U %S" -o "$out.cpu" "$sdflow" -q run --input "$work/dumbbell_$n.ply" --t-end 0.5 \
        --stop-at-topology-change --snapshot-every 0 "${extra[@]}" --out "$out" > /dev/null
    done
  done
  python3 - "$work" "$n" "$runs" <<'EOF'
import csv, statistics, sys
work, n, runs = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def measure(variant):
    cpus, row = [], None
    for r in range(1, runs + 1):
        base = f"{work}/{variant}_{n}_{r}"
        user, system = map(float, open(base + ".cpu").read().split())
        cpus.append(user + system)
        rows = list(csv.DictReader(open(base + "/metrics.csv")))[1:]  # step 0 is the input
        s = float(next(l.split("=", 1)[1] for l in open(base + "/run.toml") if l.startswith("refinement")))
        row = (len(rows), float(rows[-1]["time"]), statistics.mean(int(x["vertices"]) for x in rows), s)
    steps, t, vertices, s = row
    cpu = statistics.median(cpus)
    return dict(steps=steps, t=t, vertices=vertices, s=s, cpu=cpu, per_step=cpu / steps,
                per_kvertex=1000 * cpu / steps / (vertices / 1000))
results = {v: measure(v) for v in ("defaults", "unrefined")}
print(f"dumbbell, {n} vertices ({runs} runs each, CPU medians):")
for variant, m in results.items():
    print(f"  {variant:9s} s = {m['s']:.2f}: pinch-off t = {m['t']:.6f}, {m['steps']} steps, "
          f"{m['vertices']:.0f} vertices on average, CPU {m['cpu']:.1f} s, {1000 * m['per_step']:.1f} ms a step, "
          f"{m['per_kvertex']:.2f} ms a step per 1000 vertices")
d, u = results["defaults"], results["unrefined"]
print(f"  defaults / --refinement 1: CPU {d['cpu'] / u['cpu']:.2f}, steps {d['steps'] / u['steps']:.2f}, "
      f"a step {d['per_step'] / u['per_step']:.2f}, a step per vertex {d['per_kvertex'] / u['per_kvertex']:.2f}")
EOF
done
