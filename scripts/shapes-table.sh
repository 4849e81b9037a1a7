#!/usr/bin/env bash
# Meshes each built-in shape at the paper's resolution (`sdflow shape NAME --vertices N --json`) and
# writes the quality tables from what it measured: README.md's (between "<!-- shapes -->" and
# "<!-- end of shapes -->") and docs/shapes.md's (between "<!-- shape quality -->" and
# "<!-- end of shape quality -->"). CPU is the command's user + system time (/usr/bin/time).
#   scripts/shapes-table.sh [SDFLOW]      (default: build/release/cli/sdflow)
set -euo pipefail
if [[ "${1:-}" == "-h" || "${1:-}" == "--help" ]]; then
  sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
cd "$(dirname "$0")/.."
sdflow=$(realpath "${1:-build/release/cli/sdflow}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# NAME|VERTICES|the paper's label (docs)|README's label ('-': docs only)
shapes=(
  "sphere|3550|sphere (§4.4: 3550)|sphere"
  "ellipsoid|3500|ellipsoid 5,4,3 (§4.5: ~3500)|ellipsoid 5, 4, 3"
  "torus|15250|torus 6,3 (§4.1: 15250)|torus 6, 3"
  "dumbbell|20000|dumbbell (20000)|dumbbell"
  "sintering|51311|sintering (§4.2: 51311)|sintering cluster"
  "spheres-on-plane|95657|three spheres on a plane (§4.3: 95657)|three spheres on a plane"
  "torus|100000|torus, 100k vertices (benchmarks)|-"
)
for entry in "${shapes[@]}"; do
  IFS='|' read -r name vertices docs_label readme_label <<< "$entry"
  echo "shape $name --vertices $vertices" >&2
  /usr/bin/time -f '%U %S' -o "$work/time" "$sdflow" -q shape "$name" --vertices "$vertices" -o "$work/mesh.ply" \
    --json > "$work/shape.json"
  python3 - "$work/shape.json" "$work/time" "$docs_label" "$readme_label" >> "$work/rows" <<'PY'
import json, sys
shape = json.load(open(sys.argv[1]))
user, system = map(float, open(sys.argv[2]).read().split()[-2:])
angles = shape["min_angle_deg"]
genus = sum(c["genus"] for c in shape["components"])
loops = sum(c["boundary_loops"] for c in shape["components"])
cpu = f"{user + system:.2g} s" if user + system < 10 else f"{user + system:.0f} s"
thousands = f"{shape['vertices']:,}".replace(",", " ")
docs = (f"| {sys.argv[3]} | {shape['vertices']} | {shape['edge_length']:.3g} | {genus} / {loops} | {angles['min']:.1f} | "
        f"{angles['p01']:.1f} | {angles['p05']:.1f} | {angles['median']:.1f} | {cpu} |")
readme = (f"| {sys.argv[4]} | {thousands} | {genus} / {loops} | {angles['min']:.1f}° | {angles['p05']:.1f}° | {cpu} |"
          if sys.argv[4] != "-" else "")
print(json.dumps({"docs": docs, "readme": readme}))
PY
done

python3 - "$work/rows" <<'PY'
import json, re, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
def replace(path, begin, end, table):
    text = open(path).read()
    pattern = re.compile(re.escape(begin) + ".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        sys.exit(f"shapes-table.sh: {path} has no {begin} ... {end} markers")
    open(path, "w").write(pattern.sub(lambda m: begin + "\n" + table + "\n" + end, text))
readme = ["| shape (`sdflow shape NAME --vertices N`) | vertices | genus / loops | min angle | 5th pct of min angle | CPU |",
          "|---|---|---|---|---|---|"] + [r["readme"] for r in rows if r["readme"]]
docs = ["| shape | vertices | ℓ | genus / loops | min | 1% | 5% | median | CPU |",
        "|---|---|---|---|---|---|---|---|---|"] + [r["docs"] for r in rows]
replace("README.md", "<!-- shapes -->", "<!-- end of shapes -->", "\n".join(readme))
replace("docs/shapes.md", "<!-- shape quality -->", "<!-- end of shape quality -->", "\n".join(docs))
PY
echo "wrote the tables of README.md and docs/shapes.md" >&2
