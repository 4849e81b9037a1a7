#!/usr/bin/env bash
# The table of docs/scaling.md, "What a re-triangulating step costs": steps 1..STEPS of the three
# spheres on a plane (samples/spheres_on_plane.toml on the paper's resolution, the 94 380 vertices of
# samples/meshes/spheres_on_plane_95657.ply; one BLAS thread) run RUNS times with each
# build, the builds alternating, and scripts/step-cost.sh's wall-time figures of every run; prints
# a markdown table of their medians per build, and whether every run's metrics.csv equals the
# reference run's first steps (REFERENCE_RUN/metrics.csv, default runs/spheres_on_plane-95657) bit for bit. A build is LABEL=SDFLOW, an
# sdflow executable, optionally followed by run flags in the same argument
# ("local=build/release/cli/sdflow --retriangulate-local").
#   scripts/step-cost-table.sh [--runs N] [--steps N] [--work DIR] LABEL=SDFLOW[ FLAGS] ...
set -euo pipefail
cd "$(dirname "$0")/.."
runs=2 steps=400 work=build/step-cost
builds=()
while (($#)); do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --steps) steps=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    -h|--help) awk 'NR > 1 && /^#/ {sub(/^# ?/, ""); print; next} NR > 1 {exit}' "$0"; exit 0 ;;
    *=*) builds+=("$1"); shift ;;
    *) echo "step-cost-table.sh: '$1' is neither an option nor LABEL=SDFLOW (see --help)" >&2; exit 2 ;;
  esac
done
((${#builds[@]})) || { echo "step-cost-table.sh: give at least one LABEL=SDFLOW" >&2; exit 2; }
[[ $runs =~ ^[1-9][0-9]*$ && $steps =~ ^[1-9][0-9]*$ ]] || { echo "step-cost-table.sh: --runs and --steps take positive integers" >&2; exit 2; }
mkdir -p "$work"
mesh=samples/meshes/spheres_on_plane_95657.ply
[[ -f $mesh ]] || { echo "step-cost-table.sh: $mesh is missing: samples/make_meshes.sh build/release/cli/sdflow makes it" >&2; exit 2; }
reference=${REFERENCE_RUN:-runs/spheres_on_plane-95657}/metrics.csv
for ((i = 1; i <= runs; ++i)); do
  for k in "${!builds[@]}"; do
    label=${builds[k]%%=*}
    read -r -a command <<< "${builds[k]#*=}" # the executable, then its flags: words, never evaluated
    [[ $label =~ ^[A-Za-z0-9_.-]+$ ]] || { echo "step-cost-table.sh: label '$label' must be letters, digits, . _ -" >&2; exit 2; }
    out=$work/$label-$i
    rm -rf "$out"
    echo "run $i of $runs: $label" >&2
    OPENBLAS_NUM_THREADS=1 "${command[0]}" -q run samples/spheres_on_plane.toml --input "$mesh" --steps "$steps" --out "$out" \
      "${command[@]:1}" > "$out.log" 2>&1 || { echo "step-cost-table.sh: $label run $i failed (see $out.log)" >&2; exit 1; }
    scripts/step-cost.sh --json "$out" 1 "$steps" > "$out.json"
    lines=$((steps + 2))
    if [[ ! -f $reference ]]; then echo "no reference" > "$out.same"
    elif cmp -s "$out/metrics.csv" <(head -n "$lines" "$reference"); then echo same > "$out.same"; else echo different > "$out.same"; fi
  done
done
labels=()
for b in "${builds[@]}"; do labels+=("${b%%=*}"); done
python3 - "$work" "$runs" "${labels[@]}" <<'EOF'
import json, statistics, sys
work, runs, labels = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
data = {l: [json.load(open(f"{work}/{l}-{i}.json")) for i in range(1, runs + 1)] for l in labels}
verdicts = {l: {open(f"{work}/{l}-{i}.same").read().strip() for i in range(1, runs + 1)} for l in labels}
same = {l: "no reference run" if v == {"no reference"} else "yes" if v == {"same"} else "**no**" for l, v in verdicts.items()}
med = lambda l, key: statistics.median(d[key] for d in data[l])
rows = [("steps, wall", "total", "{:.1f} s"), ("mean step", "mean", "{:.3f} s"),
        ("plain step (median)", "plain_median", "{:.3f} s"),
        ("ratio to the plain steps' median (target ≤ 1.3)", "ratio", "{:.2f}"),
        ("ratio to the plain steps' mean", "ratio_to_plain_mean", "{:.2f}"),
        ("the plain steps' own mean over their median", "plain_own", "{:.2f}"),
        ("re-triangulations", "retriangulated", "{:.0f}"),
        ("a re-triangulating step", "retriangulating_step", "{:.2f} s")]
print(f"| wall time, median of {runs} | " + " | ".join(labels) + " |")
print("|---|" + "---|" * len(labels))
for name, key, form in rows:
    print(f"| {name} | " + " | ".join(form.format(med(l, key)) for l in labels) + " |")
print("| metrics.csv as the reference run's | " + " | ".join(same[l] for l in labels) + " |")
for l in labels:
    parts = {}
    for d in data[l]:
        for c, t in d["parts"]:
            parts.setdefault(c, []).append(t)
    top = sorted(((statistics.median(v), c) for c, v in parts.items()), reverse=True)
    print(f"\n{l}: a re-triangulating step, wall (median of the runs' means): "
          + ", ".join(f"{c} {t:.3f} s" for t, c in top if t >= 0.01))
EOF
