#!/usr/bin/env bash
# What re-triangulation adds to the steps of a run (issue 17's stage-1 target): from the run's
# timings.csv, the mean wall and CPU time per step over steps FIRST..LAST, against the median of
# those steps of the same stretch that did not re-triangulate (the plain steps on the same mesh),
# and their ratio; then that ratio for the plain steps alone (what re-triangulating at no extra
# cost would give) and where a re-triangulating step's time goes. A step re-triangulated when any
# pipeline stage or the volume restoration took time.
#   scripts/step-cost.sh RUN_DIR [FIRST [LAST]]     e.g. scripts/step-cost.sh runs/spheres_on_plane 1 400
set -euo pipefail
if [[ $# -lt 1 || $1 == -h || $1 == --help ]]; then
  awk 'NR > 1 && /^#/ {sub(/^# ?/, ""); print; next} NR > 1 {exit}' "$0"
  exit $(($# < 1 ? 2 : 0))
fi
run=$1 first=${2:-1} last=${3:-400}
[[ -f $run/timings.csv ]] || { echo "step-cost.sh: $run/timings.csv not found" >&2; exit 2; }
[[ $first =~ ^[0-9]+$ && $last =~ ^[0-9]+$ ]] || { echo "step-cost.sh: FIRST and LAST must be step numbers" >&2; exit 2; }
python3 - "$run/timings.csv" "$first" "$last" <<'EOF'
import csv, statistics, sys
path, first, last = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
stages = ("merge", "remesh", "intersections", "normals", "reconstruction", "holes", "components", "volume_restoration")
rows = [r for r in csv.DictReader(open(path)) if first <= int(r["step"]) <= last]
if not rows:
    sys.exit(f"step-cost.sh: no steps {first}..{last} in {path}")
plain = [r for r in rows if all(float(r[s]) == 0 for s in stages)]
mean = lambda key, rs: sum(float(r[key]) for r in rs) / len(rs)
median = lambda key, rs: statistics.median(float(r[key]) for r in rs)
print(f"steps {first}..{last}: {len(rows)} steps, {len(rows) - len(plain)} re-triangulated")
for key, label in (("total", "wall"), ("cpu", "CPU")):
    m, p = mean(key, rows), median(key, plain)
    print(f"{label}: mean {m:.3g} s a step; plain steps (median) {p:.3g} s; ratio {m / p:.2f}; "
          f"the plain steps' own mean over their median {mean(key, plain) / p:.2f} (the ratio if "
          f"re-triangulating cost nothing more than a plain step)")
retri = [r for r in rows if r not in plain]
if retri:
    columns = [c for c in rows[0] if c not in ("step", "total", "cpu")]
    parts = sorted(((mean(c, retri), c) for c in columns), reverse=True)
    print(f"a re-triangulating step: {mean('cpu', retri):.3g} s CPU, {mean('total', retri):.3g} s wall: "
          + ", ".join(f"{c} {t:.3f}" for t, c in parts if t >= 0.0005) + " (wall, mean)")
EOF
