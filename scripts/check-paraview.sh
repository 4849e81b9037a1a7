#!/usr/bin/env bash
# Proves that ParaView reads an sdflow run's time series: opens DIR/series.pvd with pvpython
# (Debian packages `paraview` and `python3-paraview`, large: `apt-get install --no-install-recommends
# paraview python3-paraview`),
# checks the time steps against the .pvd and the per-vertex arrays H, N and w of the last dataset.
#   scripts/check-paraview.sh RUN_DIR
# Without RUN_DIR it makes a short run of samples/meshes/ellipsoid_5_4_3.ply in a temporary folder
# with the sdflow binary found in build/ (or $SDFLOW).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v pvpython > /dev/null || { echo "check-paraview: pvpython not found (apt-get install paraview python3-paraview)"; exit 2; }

run_dir=${1:-}
if [[ -z "$run_dir" ]]; then
  sdflow=${SDFLOW:-$(find build -name sdflow -type f -perm -u+x | head -n 1)}
  [[ -x "$sdflow" ]] || { echo "check-paraview: no sdflow binary (build with -DSDFLOW_BUILD_CLI=ON)"; exit 2; }
  run_dir=$(mktemp -d)/run
  trap 'rm -rf "$(dirname "$run_dir")"' EXIT
  "$sdflow" -q run --input samples/meshes/ellipsoid_5_4_3.ply --out "$run_dir" --steps 12 --snapshot-every 4 --quiet
fi

# pvpython needs an X-less offscreen context only for rendering; reading and fetching data does not.
pvpython --force-offscreen-rendering - "$run_dir/series.pvd" <<'PY'
import re, sys
from paraview import simple, servermanager
pvd = sys.argv[-1]
expected = [float(t) for t in re.findall(r'timestep="([^"]+)"', open(pvd).read())]
reader = simple.PVDReader(FileName=pvd)
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
assert len(times) == len(expected) and all(abs(a - b) <= 1e-12 * max(1.0, abs(b)) for a, b in zip(times, expected)), \
    f"time steps {times} differ from the .pvd's {expected}"
reader.UpdatePipeline(times[-1])
data = servermanager.Fetch(reader)
points = data.GetPointData()
for name, components in (("H", 1), ("N", 3), ("w", 1)):
    array = points.GetArray(name)
    assert array is not None, f"no point array {name}"
    assert array.GetNumberOfComponents() == components, f"{name} has {array.GetNumberOfComponents()} components"
    assert array.GetNumberOfTuples() == data.GetNumberOfPoints()
print(f"check-paraview: {pvd}: {len(times)} time steps (last t = {times[-1]}), "
      f"{data.GetNumberOfPoints()} points, {data.GetNumberOfCells()} triangles, arrays H, N, w: OK")
PY
