#!/usr/bin/env bash
# Step time and peak memory of the plain flow and of a re-triangulating run against the vertex
# count (docs/scaling.md, issue 17): the paper's torus (R = 6, r = 3) meshed to each size, a few
# constant-τ steps (τ = h⁴ for the mean edge h), BLAS threads by sdflow's policy (docs/design.md
# §10). The step time is the median over the steps after the first (timings.csv's total, and its
# cpu column, which stays meaningful on a machine other work loads), the factorisation the largest
# in the run (the first step's), the solve the median after the first; peak memory is the
# process's maximum resident set (GNU time). Writes build/scaling/results.csv and prints the
# markdown table with growth exponents between consecutive sizes. A run of some sizes or kinds
# replaces those rows of results.csv and keeps the others (a size that fits in memory only for
# the plain flow is run with --kinds plain).
#   scripts/scaling.sh [--sdflow PATH] [--sizes "100000 400000 1600000"] [--kinds "plain retriangulating"]
#                      [--steps N] [--tables-only]
set -euo pipefail
cd "$(dirname "$0")/.."

sdflow=build/release/cli/sdflow
sizes="100000 400000 1600000"
kinds="plain retriangulating"
steps=5
tables_only=0
while (($#)); do
  case $1 in
    --sdflow) sdflow=$2; shift 2 ;;
    --sizes) sizes=$2; shift 2 ;;
    --kinds) kinds=$2; shift 2 ;;
    --steps) steps=$2; shift 2 ;;
    --tables-only) tables_only=1; shift ;;
    -h|--help) awk 'NR > 1 && /^#/ {sub(/^# ?/, ""); print; next} NR > 1 {exit}' "$0"; exit 0 ;;
    *) echo "scaling.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
work=build/scaling
mkdir -p "$work"
results=$work/results.csv

# median of the numbers on stdin
median() { sort -g | awk '{a[NR] = $1} END {if (NR == 0) print "nan"; else if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

# median over steps of the timings.csv column named $2 (seconds per step), skipping the first step
column_median() {
  awk -F, -v name="$2" 'NR == 1 {for (i = 1; i <= NF; ++i) if ($i == name) c = i; next} NR > 2 && c {print $c}' "$1" | median
}

# largest value of the timings.csv column named $2 (the first step's factorisation)
column_max() {
  awk -F, -v name="$2" 'NR == 1 {for (i = 1; i <= NF; ++i) if ($i == name) c = i; next} c {print $c}' "$1" | sort -g | tail -1
}

run_one() { # size, kind (plain|retriangulating)
  local n=$1 kind=$2 mesh=$work/torus_$1.ply dir=$work/${2}_$1
  [[ -f $mesh ]] || "$sdflow" -q shape torus --vertices "$n" -o "$mesh" --force
  local h tau
  h=$("$sdflow" stats "$mesh" --json --no-tetgen | python3 -c 'import json, sys; print(json.load(sys.stdin)["quality"]["edge_length"]["mean"])')
  tau=$(python3 -c "print(f'{$h ** 4:.6g}')")
  local flags=(--no-retriangulate)
  [[ $kind == retriangulating ]] && flags=(--retriangulate --retriangulate-always)
  rm -rf "$dir"
  /usr/bin/time -f '%M %e %U %S' -o "$dir.time" \
    "$sdflow" -q run --input "$mesh" --out "$dir" --steps "$steps" --tau "$tau" --snapshot-every 0 \
    --checkpoint-every 1000000 --force "${flags[@]}" > /dev/null
  local rss wall user sys vertices
  read -r rss wall user sys < "$dir.time"
  vertices=$("$sdflow" stats "$mesh" --json --no-tetgen | python3 -c 'import json, sys; print(json.load(sys.stdin)["vertices"])')
  echo "$n,$kind,$vertices,$(column_median "$dir/timings.csv" total),$(column_median "$dir/timings.csv" cpu),$(column_max "$dir/timings.csv" factorisation),$(column_median "$dir/timings.csv" solve),$rss,$wall,$user,$sys" >> "$results"
}

if ((!tables_only)); then
  header="size,kind,vertices,step_s,step_cpu_s,factorisation_s,solve_s,peak_rss_kib,wall_s,user_s,sys_s"
  # keep the rows of the sizes and kinds not re-run now
  kept=$(mktemp)
  trap 'rm -f "$kept"' EXIT
  if [[ -f $results ]]; then
    awk -F, -v sizes=" $sizes " -v kinds=" $kinds " \
      'NR > 1 && !(index(sizes, " " $1 " ") && index(kinds, " " $2 " "))' "$results" > "$kept"
  fi
  echo "$header" > "$results"
  cat "$kept" >> "$results"
  for n in $sizes; do
    for kind in $kinds; do
      [[ $kind == plain || $kind == retriangulating ]] ||
        { echo "scaling.sh: unknown kind '$kind' (plain or retriangulating)" >&2; exit 2; }
      echo "scaling.sh: $kind flow on a torus of $n vertices ($steps steps)" >&2
      run_one "$n" "$kind"
    done
  done
fi

python3 - "$results" <<'EOF'
import csv, math, sys
rows = sorted(csv.DictReader(open(sys.argv[1])), key=lambda r: int(r["size"]))
print("| flow | vertices | step, wall (median) | step, CPU (median) | factorisation, wall (largest) | solve, wall (median) | peak memory | exponent of step CPU | exponent of memory |")
print("|---|---|---|---|---|---|---|---|---|")
for kind in ("plain", "retriangulating"):
    previous = None
    for r in (r for r in rows if r["kind"] == kind):
        v, step, mem = float(r["vertices"]), float(r["step_cpu_s"]), float(r["peak_rss_kib"]) / 2**20
        if previous:
            pv, ps, pm = previous
            e_step = f"{math.log(step / ps) / math.log(v / pv):.2f}"
            e_mem = f"{math.log(mem / pm) / math.log(v / pv):.2f}"
        else:
            e_step = e_mem = "–"
        print(f"| {kind} | {int(v):,} | {float(r['step_s']):.3g} s | {step:.3g} s | {float(r['factorisation_s']):.3g} s | "
              f"{float(r['solve_s']):.3g} s | {mem:.2f} GiB | {e_step} | {e_mem} |")
        previous = (v, step, mem)
EOF
