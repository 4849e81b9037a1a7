#!/usr/bin/env bash
# Cost of an anisotropic step against an isotropic step of the same size (issue 35's target: at
# most 1.3x). From an ellipsoid (1.2, 1, 0.8) meshed at about N vertices, each energy takes steps
# without re-triangulation, and a step's own CPU time is read from timings.csv (the mean over the
# steps after the first, so that refactorisations count; the least over interleaved repetitions,
# the figure other jobs disturbed least). Energies: isotropic; ellipsoidal g = (1, 2, 3); the cubic-like sum of three (1, 1, 4)
# terms turned by 90 degrees about x and about y. Modes:
#   plain:    a factorisation every step, tau = 1e-5: the step alone (operators with mu, assembly,
#             factorisation, solve), the same linear algebra for every energy;
#   reuse:    the default solver (a factor reused as CG preconditioner until refactorising pays),
#             tau = 1e-5: the same tau, so an energy whose flow moves the surface faster per step
#             refactorises more often;
#   adaptive: the default adaptive tau, steps of the same size in the sense of the rule (the normal
#             displacement bound), what a run pays per step.
# Prints a Markdown table (factorisations per run in brackets); with --docs it replaces
# docs/validation.md's table between "<!-- tables: anisotropic-cost -->" and its end marker.
#   bench/anisotropic_step_cost.sh [--sdflow PATH] [--rounds N] [--docs]
set -euo pipefail
cd "$(dirname "$0")/.."
sdflow=build/release/cli/sdflow rounds=3 docs=0
while (($#)); do
  case $1 in
    --sdflow) sdflow=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --docs) docs=1; shift ;;
    *) echo "anisotropic_step_cost.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
sdflow=$(realpath "$sdflow")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
energies=(isotropic ellipsoidal sum)
energy_flags() {
  case $1 in
    isotropic) ;;
    ellipsoidal) echo "--energy ellipsoidal --energy-g 1,2,3" ;;
    sum) echo "--energy sum --energy-g 1,1,4,0,0,0,1,1,4,90,0,0,1,1,4,0,90,0" ;;
  esac
}
mode_flags() {
  case $1 in
    plain) echo "--tau 1e-5 --steps 40 --factorisation every_step" ;;
    reuse) echo "--tau 1e-5 --steps 100" ;;
    adaptive) echo "--steps 100" ;;
  esac
}
for n in 640 2500 10000; do
  start=$work/ellipsoid_$n.ply
  "$sdflow" -q shape ellipsoid --a 1.2 --b 1 --c 0.8 --vertices "$n" -o "$start" > /dev/null
  for mode in plain reuse adaptive; do
    for ((round = 0; round < rounds; ++round)); do
      for energy in "${energies[@]}"; do
        out=$work/${n}_${mode}_${energy}_$round
        # shellcheck disable=SC2046 # the flags are words
        "$sdflow" -q run --input "$start" --out "$out" --no-retriangulate --snapshot-every 0 \
          $(mode_flags "$mode") $(energy_flags "$energy") > "$out.log"
      done
    done
  done
done
table=$(python3 - "$work" "$rounds" <<'EOF'
import csv, glob, os, statistics, sys
work, rounds = sys.argv[1], int(sys.argv[2])
energies = ("isotropic", "ellipsoidal", "sum")
def step_cpu(run):
    rows = list(csv.DictReader(open(os.path.join(run, "timings.csv"))))[1:]
    return statistics.mean(float(r["cpu"]) for r in rows)
def factorisations(run):
    text = open(run + ".log").read() if os.path.exists(run + ".log") else ""
    # the run's summary line: "..., N factorisations"
    words = text.replace(",", " ").split()
    return words[words.index("factorisations") - 1] if "factorisations" in words else "?"
lines = ["| vertices | mode | isotropic step, CPU | ellipsoidal (ratio) | sum of 3 terms (ratio) |",
         "|---|---|---|---|---|"]
for n in (640, 2500, 10000):
    for mode in ("plain", "reuse", "adaptive"):
        best, count = {}, {}
        for energy in energies:
            runs = [f"{work}/{n}_{mode}_{energy}_{r}" for r in range(rounds)]
            best[energy] = min(step_cpu(r) for r in runs)
            count[energy] = factorisations(runs[0])
        iso = best["isotropic"]
        cells = [f"{1000 * iso:.2f} ms ({count['isotropic']})"] + [
            f"{1000 * best[e]:.2f} ms ({count[e]}): {best[e] / iso:.2f}" for e in energies[1:]]
        lines.append(f"| {n} | {mode} | " + " | ".join(cells) + " |")
print("\n".join(lines))
EOF
)
echo "$table"
if ((docs)); then
  scripts/lib/replace-doc-table.py docs/validation.md anisotropic-cost <<< "$table"
fi
