#!/usr/bin/env bash
# Cost of a step on a substrate against a closed surface's step of the same size (issue 36's
# target: at most 1.3x): hyperfine times a fixed number of constant steps of an island standing
# on z = 0 (`shape cuboid-island`, boundary = substrate, contact angle 60 degrees) and of a sphere
# of about as many vertices, alternating the two, and prints per step the whole run's median wall
# time and mean CPU time (user + system, hyperfine's means; start-up included), a step's own median
# CPU time from one more run's timings.csv, and their ratios (on a busy machine, read the CPU
# figures). Two modes:
#   plain: --factorisation every_step --no-retriangulate, the step alone (operators, assembly,
#          factorisation, solve, acceptance, and the contact line's part for the island);
#   full:  the defaults (reused factorisations, the look at the surface after each step and its
#          re-triangulations): what a run pays.
# Last, the figures as a Markdown table; with --docs it replaces docs/validation.md's table between
# "<!-- tables: substrate-cost -->" and "<!-- end of tables: substrate-cost -->".
#   bench/substrate_step_cost.sh [--sdflow PATH] [--runs N] [--steps N] [--docs]
set -euo pipefail
cd "$(dirname "$0")/.."
sdflow=build/release/cli/sdflow runs=5 steps=15 docs=0
while (($#)); do
  case $1 in
    --sdflow) sdflow=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --steps) steps=$2; shift 2 ;;
    --docs) docs=1; shift ;;
    *) echo "substrate_step_cost.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
command -v hyperfine > /dev/null || { echo "substrate_step_cost.sh: needs hyperfine (scripts/install-deps.sh --bench)" >&2; exit 2; }
sdflow=$(realpath "$sdflow")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
vertices() { "$sdflow" stats "$1" 2>&1 | sed -n 's/^ *\([0-9]*\) vertices,.*/\1/p' | head -1; }
for edge in 0.03 0.015; do
  island=$work/island_$edge.ply sphere=$work/sphere_$edge.ply
  "$sdflow" -q shape cuboid-island --a 2 --b 1 --c 0.5 --radius 0.2 --edge-length "$edge" -o "$island" > /dev/null
  n_island=$(vertices "$island")
  "$sdflow" -q shape sphere --vertices "$n_island" -o "$sphere" > /dev/null
  n_sphere=$(vertices "$sphere")
  for mode in plain full; do
    extra=""
    [[ $mode == plain ]] && extra="--factorisation every_step --no-retriangulate"
    # τ = 1e-7: far below both meshes' stability bound, so that every step is accepted at once.
    run="$sdflow -q run --tau 1e-7 --steps $steps --snapshot-every 0 $extra"
    hyperfine -N -w 1 -r "$runs" --export-json "$work/$mode.json" \
      --prepare "rm -rf $work/a $work/b" \
      --command-name="island on a substrate, $n_island vertices" \
      "$run --input $island --boundary substrate --contact-angle 60 --out $work/a" \
      --command-name="closed sphere, $n_sphere vertices" "$run --input $sphere --out $work/b" > /dev/null
    # Once more each, for their timings.csv (hyperfine's preparation removes both before every run).
    rm -rf "$work/a" "$work/b"
    $run --input "$island" --boundary substrate --contact-angle 60 --out "$work/a"
    $run --input "$sphere" --out "$work/b"
    python3 - "$work/$mode.json" "$steps" "$n_island" "$n_sphere" "$mode" "$work/a/timings.csv" "$work/b/timings.csv" "$work/rows.md" <<'EOF'
import csv, json, statistics, sys
results = json.load(open(sys.argv[1]))["results"]
steps, counts, mode = int(sys.argv[2]), (int(sys.argv[3]), int(sys.argv[4])), sys.argv[5]
wall = [statistics.median(r["times"]) for r in results]
cpu = [r["user"] + r["system"] for r in results]
# Each step's own time from one more run's timings.csv (the run's start-up left out): median CPU.
step_cpu = [statistics.median(float(row["cpu"]) for row in csv.DictReader(open(path))) for path in sys.argv[6:8]]
print(f"{mode}:")
for r, w, c, sc in zip(results, wall, cpu, step_cpu):
    print(f"  {r['command']}: whole run {1000 * w / steps:.1f} ms a step wall, {1000 * c / steps:.1f} ms CPU "
          f"(start-up included); a step alone {1000 * sc:.1f} ms CPU (median)")
per_vertex = lambda t: (t[0] / counts[0]) / (t[1] / counts[1])
print(f"  island / sphere, whole run: wall {wall[0] / wall[1]:.2f}, CPU {cpu[0] / cpu[1]:.2f}; a step alone: CPU "
      f"{step_cpu[0] / step_cpu[1]:.2f}, per vertex {per_vertex(step_cpu):.2f}")
spaced = lambda n: f"{n:,}".replace(",", " ")
with open(sys.argv[8], "a") as rows:
    rows.write(f"| {spaced(counts[0])}, {spaced(counts[1])} | {mode} | {1000 * step_cpu[0]:.1f} / "
               f"{1000 * step_cpu[1]:.1f} ms | {step_cpu[0] / step_cpu[1]:.2f} | {cpu[0] / cpu[1]:.2f} |\n")
EOF
  done
done
table=$(printf '%s\n%s\n' "| vertices (island, sphere) | mode | a step alone, CPU (island / sphere) | ratio | whole run, CPU ratio |" \
  "|---|---|---|---|---|"; cat "$work/rows.md")
echo "$table"
if ((docs)); then
  scripts/lib/replace-doc-table.py docs/validation.md substrate-cost <<< "$table"
fi
