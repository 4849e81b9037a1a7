#!/usr/bin/env bash
# Builds the MeshLab filter plugin and runs its tests (ctest label `meshlab`): the conversion and
# the filter in process, then the plugin installed into a private MeshLab prefix and run headless by
# meshlabserver under Xvfb. Installs what it needs first (scripts/install-deps.sh --meshlab); the
# first configuration fetches MeshLab's headers (scripts/fetch-meshlab-source.sh).
#   scripts/test-meshlab-plugin.sh [BUILD_DIR]     (default build/meshlab; JOBS=n limits parallelism)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --meshlab
dir=${1:-build/meshlab}
jobs=${JOBS:-$(nproc)}

mkdir -p "$dir"
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSDFLOW_BUILD_TESTS=ON -DSDFLOW_BUILD_CLI=ON \
  -DSDFLOW_BUILD_MESHLAB_PLUGIN=ON > "$dir/configure.log" || { cat "$dir/configure.log"; exit 1; }
cmake --build "$dir" -j "$jobs" --target sdflow filter_sdflow sdflow_meshlab_tests sdflow_compare_meshes
ctest --test-dir "$dir" -L meshlab --output-on-failure -j "$jobs"
echo "test-meshlab-plugin.sh: all MeshLab plugin tests passed"
