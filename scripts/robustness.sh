#!/usr/bin/env bash
# Runs sdflow on surfaces it did not make: every closed surface of CGAL's sample data (libcgal-demo)
# and of geomview's example objects (fetched as scripts/repair-samples.sh does), each after
# `sdflow repair` (which leaves a valid file as it is), through `sdflow run --end-time T` with
# T = (0.02 D)^4 for the bounding-box diagonal D, under a wall budget each, and writes
# docs/robustness.md: file, vertices, exit code, steps, wall time, topology events with what set
# each off, volume drift (debris included), and the counts. Runs go one at a time under nice.
#   scripts/robustness.sh [--quick] [--budget S] [--max-vertices N] [--only REGEX] [--out FILE] [SDFLOW]
#     --quick          a few small files of each kind (CI: well under a minute); writes no document
#                      unless --out, and fails on an early or too-wide topology change as well
#     --budget S       wall seconds per run (default 120; with --quick 600, a guard against a hang
#                      only: how fast the runs are is measured by the full corpus and bench/, never
#                      asserted)
#     --max-vertices N closed surfaces up to N vertices (default 60000)
#     --only REGEX     only the files whose name matches (a subset; the document says so)
#     --compact        also run samples/compact_27.toml (its metrics are read from its own run)
#     --with "FLAGS"   add these run flags to every run (e.g. --with --conserve-volume: a trial of
#                      a setting against the defaults); the document says so
# Exit status: 0 when every run reached T with exit 0 or was refused before step 1 with exit 2,
# 1 otherwise (the document lists which).
set -euo pipefail
usage() { sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'; }
quick=0 budget="" max_vertices=60000 only="" out="" compact=0 with=""
while [[ $# -gt 0 ]]; do
  case $1 in
    -h|--help) usage; exit 0 ;;
    --quick) quick=1 ;;
    --budget) budget=$2; shift ;;
    --max-vertices) max_vertices=$2; shift ;;
    --only) only=$2; shift ;;
    --out) out=$2; shift ;;
    --compact) compact=1 ;;
    --with) with=$2; shift ;;
    -*) usage >&2; exit 2 ;;
    *) break ;;
  esac
  shift
done
[[ -n $budget ]] || budget=$([[ $quick -eq 1 ]] && echo 600 || echo 120)
[[ $budget =~ ^[0-9]+$ && $max_vertices =~ ^[0-9]+$ ]] || { echo "robustness.sh: --budget and --max-vertices take whole numbers" >&2; exit 2; }
cd "$(dirname "$0")/.."
sdflow=$(realpath "${1:-build/release/cli/sdflow}")
[[ -x $sdflow ]] || { echo "robustness.sh: build sdflow first ($sdflow)" >&2; exit 2; }
[[ $quick -eq 1 || -n $out ]] || out=docs/robustness.md
read -ra with_flags <<< "$with" # words of --with, passed as arguments, never through a shell
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# package_path PACKAGE PATH
source scripts/lib/debian-package.sh # the working directory is the repository's root

cgal=$(package_path libcgal-demo /usr/share/doc/libcgal-dev/data.tar.gz)
[[ -f $cgal ]] || { echo "robustness.sh: could not fetch CGAL's sample data (apt-get download libcgal-demo)" >&2; exit 2; }
tar -xzf "$cgal" -C "$work" data/meshes
geomview=$(package_path geomview /usr/share/geomview)
[[ -d $geomview ]] || { echo "robustness.sh: could not fetch geomview's examples (apt-get download geomview)" >&2; exit 2; }
# ls fails on the extensions the data set lacks; under errexit that ended the list before geomview's.
mapfile -t files < <( (ls "$work"/data/meshes/*.{off,stl,ply,obj} 2> /dev/null || true) | sort; find "$geomview" -name '*.off' | sort)
if [[ $quick -eq 1 ]]; then
  # Small closed surfaces of different kinds: polyhedra (one of 8 vertices that the run refines, one
  # of 20 too small for the neighbourhoods the re-triangulation uses), a smooth sphere, CAD parts
  # with sharp edges and walls thinner than an edge, a torus, a scan that `repair` mends, and one
  # whose handle opens in the flow (a topology change whose trigger size is checked).
  only='^(octahedron|beam|hole|sphere|dragknob|part|mpi|3torus|blobby-shuffled|cow)\.off$'
fi

results=$work/results.tsv
: > "$results"
index=0
for file in "${files[@]}"; do
  name=$(basename "$file")
  [[ -z $only ]] || [[ $name =~ $only ]] || continue
  index=$((index + 1))
  source=cgal
  [[ $file == "$geomview"* ]] && source=geomview
  prepared=$work/prepared.off run=$work/run
  rm -rf "$prepared" "$run"
  # Repair what stats refuses (a valid file passes through unchanged), then keep closed surfaces.
  if ! "$sdflow" -q repair --ascii "$file" -o "$prepared" > /dev/null 2> "$work/repair.err"; then
    continue # not a surface sdflow can read or repair (README: repair-samples.sh lists them)
  fi
  "$sdflow" -q stats --no-tetgen --json "$prepared" > "$work/stats.json" 2> /dev/null || continue
  read -r vertices loops < <(python3 -c '
import json, sys
s = json.load(open(sys.argv[1]))
print(s["vertices"], s["boundary_loops"])' "$work/stats.json")
  [[ $loops -eq 0 && $vertices -le $max_vertices ]] || continue
  repaired=no
  "$sdflow" -q stats --no-tetgen "$file" > /dev/null 2>&1 || repaired=yes
  # A surface that crosses itself is refused by `run` (which side is inside is not defined); as its
  # message says, `repair --remove-self-intersections` cuts the crossings out and closes it again.
  # Where that fails too, the run gets the file as it is and refuses it.
  crossings=$("$sdflow" -q intersections --json "$prepared" 2> /dev/null |
              python3 -c 'import json, sys; print(json.load(sys.stdin)["intersecting_pairs"])' 2> /dev/null || echo 0)
  if [[ $crossings -gt 0 ]] &&
     "$sdflow" -q repair --ascii --remove-self-intersections "$prepared" -o "$work/uncrossed.off" > /dev/null 2>&1; then
    mv "$work/uncrossed.off" "$prepared"
    repaired="crossings undone ($crossings pairs)"
    vertices=$(awk 'NR == 2 { print $1; exit }' "$prepared")
  fi
  # T = (0.02 D)^4 from the bounding box of the OFF file's vertices.
  end_time=$(awk 'NR == 1 { next } NR == 2 { n = $1; next } n > 0 { if (!seen) { lo1 = hi1 = $1; lo2 = hi2 = $2; lo3 = hi3 = $3; seen = 1 }
                   if ($1 < lo1) lo1 = $1; if ($1 > hi1) hi1 = $1; if ($2 < lo2) lo2 = $2; if ($2 > hi2) hi2 = $2
                   if ($3 < lo3) lo3 = $3; if ($3 > hi3) hi3 = $3; n-- }
                  END { d = sqrt((hi1 - lo1)^2 + (hi2 - lo2)^2 + (hi3 - lo3)^2); printf "%.6g", (0.02 * d)^4 }' "$prepared")
  echo "robustness.sh: [$index] $name ($vertices vertices, T = $end_time)" >&2
  start=$(date +%s%N)
  status=0
  # SIGINT at the budget (the run stops at its next step with a checkpoint), SIGKILL 30 s later if
  # a single step holds it longer.
  nice timeout -k 30 -s INT "$budget" "$sdflow" -q run --input "$prepared" -o "$run" --end-time "$end_time" \
    "${with_flags[@]}" > "$work/run.out" 2>&1 || status=$?
  wall=$(( ($(date +%s%N) - start) / 1000000 ))
  message=$(grep -v '^\s*$' "$work/run.out" | tail -1 | cut -c1-160 || true)
  python3 - "$run" "$name" "$source" "$vertices" "$repaired" "$status" "$wall" "$end_time" "$message" >> "$results" <<'EOF'
import csv, os, re, sys
run, name, source, vertices, repaired, status, wall, end_time, message = sys.argv[1:]
status, end_time = int(status), float(end_time)
rows, events, edge = [], [], ""
metrics = os.path.join(run, "metrics.csv")
if os.path.exists(metrics):
    with open(metrics) as f:
        rows = list(csv.DictReader(f))
if os.path.exists(os.path.join(run, "run.toml")):
    m = re.search(r"^\s*edge_length\s*=\s*([0-9.eE+-]+)", open(os.path.join(run, "run.toml")).read(), re.M)
    edge = m.group(1) if m else ""
log = open(os.path.join(run, "events.log")).read().splitlines() if os.path.exists(os.path.join(run, "events.log")) else []
def detail(step):
    # The events.log line of that step that changed the surface: what set it off, and its sizes.
    for line in log:
        if line.startswith(f"step {step} ") and ("components" in line or "genus" in line or "surgery" in line
                                                 or "intersecting" in line):
            text = line.split(":", 1)[1].strip() if ":" in line else line
            # The size that set the change off, measured at the start of the step that crossed.
            size = re.search(r"narrowest neck or gap within 2 ℓ of them \S+ = (\S+) ℓ", line)
            return (f"trigger {size.group(1)} ℓ; " if size else "") + text[:150]
    return ""
first_change = ""
for a, b in zip(rows, rows[1:]):
    if a["components"] != b["components"] or a["genus"] != b["genus"]:
        what = []
        if a["components"] != b["components"]:
            what.append(f"bodies {a['components']}→{b['components']}")
        if a["genus"] != b["genus"]:
            what.append(f"genus {a['genus']}→{b['genus']}")
        events.append(f"t = {float(b['time']):.3g}: {', '.join(what)} ({detail(b['step'])})")
        first_change = first_change or b["time"]
steps = rows[-1]["step"] if rows else "0"
t_end = float(rows[-1]["time"]) if rows else 0.0
drift = ""
if rows:
    v0 = float(rows[0]["volume"])
    v1 = float(rows[-1]["volume"]) + float(rows[-1].get("debris_volume", 0) or 0)
    drift = f"{(v1 - v0) / v0:+.2e}" if v0 else ""
reached = status == 0 and t_end >= end_time * (1 - 1e-9)
refused = status == 2 and (not rows or steps == "0")
early = ""
if first_change and edge:
    bound = (float(edge) / 4) ** 4
    early = "yes" if float(first_change) < bound else "no"
outcome = "reached T" if reached else ("refused before step 1" if refused else
          ("wall budget" if status == 124 else
           "killed: one step outlasted the budget by 30 s" if status == 137 else f"exit {status}"))
print("\t".join([name, source, vertices, repaired, str(status), outcome, steps, f"{t_end:.3g}", f"{end_time:.3g}",
                 f"{float(wall) / 1000:.1f}", edge, drift, early, " · ".join(events) or "none",
                 message.replace("\t", " ").replace("|", "/") if not reached else ""]))
EOF
done

if [[ $compact -eq 1 ]]; then
  echo "robustness.sh: compact_27 (samples/compact_27.toml)" >&2
  samples/make_meshes.sh "$sdflow" > /dev/null
  run=$work/compact_27 status=0 start=$(date +%s%N)
  nice "$sdflow" -q run samples/compact_27.toml --out "$run" "${with_flags[@]}" > "$work/run.out" 2>&1 || status=$?
  wall=$(( ($(date +%s%N) - start) / 1000000 ))
  vertices=$(awk -F, 'NR == 2 { print $4 }' "$run/metrics.csv")
  end_time=$(awk -F, 'END { print $2 }' "$run/metrics.csv")
  python3 - "$run/metrics.csv" "$status" "$wall" "$vertices" "$end_time" >> "$results" <<'EOF'
import csv, sys
metrics, status, wall, vertices, end_time = sys.argv[1:]
rows = list(csv.DictReader(open(metrics)))
v0 = float(rows[0]["volume"]); v1 = float(rows[-1]["volume"]) + float(rows[-1]["debris_volume"])
changes = sum(1 for a, b in zip(rows, rows[1:]) if a["components"] != b["components"] or a["genus"] != b["genus"])
genus = max(int(r["genus"]) for r in rows)
print("\t".join(["compact_27 (sample)", "sdflow", vertices, "no", status, "reached T" if status == "0" else f"exit {status}",
                 rows[-1]["step"], f"{float(rows[-1]['time']):.3g}", f"{float(end_time):.3g}", f"{float(wall) / 1000:.1f}", "",
                 f"{(v1 - v0) / v0:+.2e}", "", f"{changes} topology changes, genus at most {genus}", ""]))
EOF
fi

python3 - "$results" "$budget" "$max_vertices" "$only" "$quick" "$out" "$("$sdflow" --version 2>/dev/null | head -1)" "$with" <<'EOF'
import re, sys
results, budget, max_vertices, only, quick, out, version, with_flags = sys.argv[1:]
rows = [line.rstrip("\n").split("\t") for line in open(results) if line.strip()]
reached = sum(1 for r in rows if r[5] == "reached T")
refused = sum(1 for r in rows if r[5] == "refused before step 1")
budget_out = sum(1 for r in rows if r[5] == "wall budget")
failed = [r for r in rows if r[5] not in ("reached T", "refused before step 1")]
early = sum(1 for r in rows if r[12] == "yes")
triggers = [float(t) for r in rows for t in re.findall(r"trigger (\S+) ℓ", r[13])]
wide = sum(1 for t in triggers if t > 0.25)
summary = (f"{len(rows)} closed surfaces: {reached} reached T with exit 0 ({100 * reached / max(len(rows), 1):.0f}%), "
           f"{refused} refused before step 1 with exit 2, {budget_out} stopped by the wall budget, "
           f"{len(failed) - budget_out} failed otherwise; {early} changed topology before t = (ℓ/4)⁴; "
           f"{wide} of {len(triggers)} topology changes logged with a neck or gap wider than ¼ ℓ.")
if quick == "1" and not out:
    for r in rows:
        print(f"{r[0]}: {r[5]}, exit {r[4]}, {r[6]} steps to t = {r[7]} of {r[8]}, {r[9]} s, volume drift {r[11]}")
    print(summary)
    sys.exit(0 if not failed and early == 0 and wide == 0 else 1)
lines = [
    "# Robustness on surfaces sdflow did not make",
    "",
    "Generated by `scripts/robustness.sh` (" + ("the quick subset" if quick == "1" else
        (f"the files matching `{only}`: a subset" if only else
         ("every closed surface" if max_vertices == "60000" else
          f"a subset: the closed surfaces up to {max_vertices} vertices, not all up to 60000"))) +
    f"; wall budget {budget} s a run, surfaces up to {max_vertices} vertices; {version}). "
    "Every closed surface of CGAL's sample data (`libcgal-demo`, `data/meshes`) and of geomview's example "
    "objects, after `sdflow repair` where `stats` refuses the file and `sdflow repair "
    "--remove-self-intersections` where it crosses itself (`run` refuses such a surface), runs " +
    (f"with the defaults and `{with_flags}` (`sdflow run --input FILE --end-time T {with_flags}`)" if with_flags else
     "with the defaults (`sdflow run --input FILE --end-time T`)") + " to T = (0.02 D)⁴, D the bounding-box diagonal: far enough for "
    "the flow to smooth what is finer than a fiftieth of the object, not for its large-scale change. "
    "Files with boundary, point sets and files sdflow cannot read are not in the corpus "
    "(`scripts/repair-samples.sh` lists the unreadable ones). The runs go one at a time under `nice` on the "
    "shared 2-core machine: wall times are indicative.",
    "",
    "**" + summary + "**",
    "",
    "Columns: vertices of the (repaired) surface; repaired: `stats` refused the file and `repair` fixed it, or "
    "the file crossed itself and `repair --remove-self-intersections` undid the crossings; exit "
    "code (124: stopped by the wall budget); steps and the time reached against T; wall seconds; ℓ, the run's "
    "re-triangulation edge length; volume drift (volume + debris dropped, end against start); early: a topology "
    "change before t = (ℓ/4)⁴, the flow's displacement over a quarter of an edge; the topology events, each with "
    "its trigger (the narrowest neck or gap within 2 ℓ of the crossing that set it off, in ℓ, measured on the "
    "surface at the start of the step that crossed; it does not by itself tell a fold from a pinch, "
    "docs/retriangulation.md) and its events.log line; for runs that did not reach T, the last line they printed.",
    "",
    "| file | source | vertices | repaired | exit | outcome | steps | t reached | T | wall s | ℓ | volume drift | early | topology events | last message |",
    "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
]
for r in rows:
    lines.append("| " + " | ".join(c.replace("|", "/") for c in r) + " |")
open(out, "w").write("\n".join(lines) + "\n")
print(summary)
sys.exit(0 if not failed else 1)
EOF
