#!/usr/bin/env bash
# What re-triangulation adds to the steps of a run (issue 17's stage-1 target): from the run's
# timings.csv, the mean wall and CPU time per step over steps FIRST..LAST, against the median of
# those steps of the same stretch that did not re-triangulate (the plain steps on the same mesh),
# and their ratio; then that ratio for the plain steps alone (what re-triangulating at no extra
# cost would give), the ratio to the plain steps' mean (refactorisations included, as a plain
# run's time per step counts them) and where a re-triangulating step's time goes. A step
# re-triangulated when any pipeline stage or the volume restoration took time. With --json, the
# same figures (wall time) as one JSON object (scripts/step-cost-table.sh reads it).
#   scripts/step-cost.sh [--json] RUN_DIR [FIRST [LAST]]   e.g. scripts/step-cost.sh runs/spheres_on_plane 1 400
set -euo pipefail
json=0
[[ ${1:-} == --json ]] && { json=1; shift; }
if [[ $# -lt 1 || $1 == -h || $1 == --help ]]; then
  awk 'NR > 1 && /^#/ {sub(/^# ?/, ""); print; next} NR > 1 {exit}' "$0"
  exit $(($# < 1 ? 2 : 0))
fi
run=$1 first=${2:-1} last=${3:-400}
[[ -f $run/timings.csv ]] || { echo "step-cost.sh: $run/timings.csv not found" >&2; exit 2; }
[[ $first =~ ^[0-9]+$ && $last =~ ^[0-9]+$ ]] || { echo "step-cost.sh: FIRST and LAST must be step numbers" >&2; exit 2; }
python3 - "$run/timings.csv" "$first" "$last" "$json" <<'EOF'
import csv, json, statistics, sys
path, first, last, as_json = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4] == "1"
stages = ("merge", "remesh", "intersections", "normals", "reconstruction", "holes", "components", "volume_restoration", "retriangulation_other")
rows = [r for r in csv.DictReader(open(path)) if first <= int(r["step"]) <= last]
if not rows:
    sys.exit(f"step-cost.sh: no steps {first}..{last} in {path}")
plain = [r for r in rows if all(float(r.get(s) or 0) == 0 for s in stages)]  # runs before retriangulation_other lack it
retri = [r for r in rows if r not in plain]
mean = lambda key, rs: sum(float(r[key]) for r in rs) / len(rs)
median = lambda key, rs: statistics.median(float(r[key]) for r in rs)
columns = [c for c in rows[0] if c not in ("step", "total", "cpu")]
parts = sorted(((mean(c, retri), c) for c in columns), reverse=True) if retri else []
if as_json:
    m, p, pm = mean("total", rows), median("total", plain), mean("total", plain)
    print(json.dumps({"steps": len(rows), "retriangulated": len(retri), "total": m * len(rows), "mean": m,
                      "plain_median": p, "ratio": m / p, "ratio_to_plain_mean": m / pm, "plain_own": pm / p,
                      "retriangulating_step": mean("total", retri) if retri else 0,
                      "parts": [[c, t] for t, c in parts if t >= 0.0005]}))
    sys.exit(0)
print(f"steps {first}..{last}: {len(rows)} steps, {len(retri)} re-triangulated")
for key, label in (("total", "wall"), ("cpu", "CPU")):
    m, p = mean(key, rows), median(key, plain)
    print(f"{label}: mean {m:.3g} s a step; plain steps (median) {p:.3g} s; ratio {m / p:.2f}; "
          f"the plain steps' own mean over their median {mean(key, plain) / p:.2f} (the ratio if "
          f"re-triangulating cost nothing more than a plain step); ratio to the plain steps' mean "
          f"{m / mean(key, plain):.2f}")
if retri:
    print(f"a re-triangulating step: {mean('cpu', retri):.3g} s CPU, {mean('total', retri):.3g} s wall: "
          + ", ".join(f"{c} {t:.3f}" for t, c in parts if t >= 0.0005) + " (wall, mean)")
EOF
