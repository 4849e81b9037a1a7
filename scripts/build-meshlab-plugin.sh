#!/usr/bin/env bash
# Builds the MeshLab filter plugin for Debian's MeshLab 2020.09: installs the Debian packages it
# needs (scripts/install-deps.sh --meshlab), fetches MeshLab's headers from Debian's source package
# at configure time, and builds libfilter_sdflow.so. It reuses build/release when that exists (the
# toolbox already built there is not built again); otherwise it builds in build/meshlab-plugin.
# Then install it into Debian's MeshLab with
#   cmake --install BUILD_DIR --component meshlab_plugin        (as root; `sudo` before it otherwise)
# (into /usr/lib/<arch>/meshlab/plugins; `--prefix DIR` installs under DIR instead).
#   scripts/build-meshlab-plugin.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --meshlab
if [[ -n ${1:-} ]]; then
  dir=$1
elif [[ -f build/release/CMakeCache.txt ]]; then
  dir=build/release
else
  dir=build/meshlab-plugin
fi
if [[ -f $dir/CMakeCache.txt ]]; then
  # An existing build keeps its options (CLI, tests, Python); only the plugin is switched on.
  cmake -S . -B "$dir" -DSDFLOW_BUILD_MESHLAB_PLUGIN=ON -DCMAKE_INSTALL_PREFIX=/usr > /dev/null
else
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
    -DSDFLOW_BUILD_MESHLAB_PLUGIN=ON -DSDFLOW_BUILD_CLI=OFF -DSDFLOW_BUILD_TESTS=OFF > /dev/null
fi
cmake --build "$dir" -j "${JOBS:-$(nproc)}" --target filter_sdflow
echo "build-meshlab-plugin.sh: built $dir/meshlab_plugin/libfilter_sdflow.so; install it with"
echo "  cmake --install $dir --component meshlab_plugin   (as root; with sudo otherwise)"
