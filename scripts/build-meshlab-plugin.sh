#!/usr/bin/env bash
# Builds the MeshLab filter plugin for Debian's MeshLab 2020.09: installs the Debian packages it
# needs (scripts/install-deps.sh --meshlab), fetches MeshLab's headers from Debian's source package
# at configure time, and builds libfilter_sdflow.so. Then install it into Debian's MeshLab with
#   sudo cmake --install build/meshlab-plugin --component meshlab_plugin
# (into /usr/lib/<arch>/meshlab/plugins; `--prefix DIR` installs under DIR instead).
#   scripts/build-meshlab-plugin.sh [BUILD_DIR]     (default build/meshlab-plugin)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --meshlab
dir=${1:-build/meshlab-plugin}
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DSDFLOW_BUILD_MESHLAB_PLUGIN=ON -DSDFLOW_BUILD_CLI=OFF -DSDFLOW_BUILD_TESTS=OFF > /dev/null
cmake --build "$dir" -j "${JOBS:-$(nproc)}" --target filter_sdflow
echo "build-meshlab-plugin.sh: built $dir/meshlab_plugin/libfilter_sdflow.so; install it with"
echo "  sudo cmake --install $dir --component meshlab_plugin"
