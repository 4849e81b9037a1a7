#!/usr/bin/env bash
# Installs the dependencies, builds the sdflow command and runs the demo: statistics of the
# paper's torus (R = 6, r = 3), with its volume cross-checked by TetGen.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DSDFLOW_BUILD_TESTS=OFF > /dev/null
cmake --build build/release -j "$(nproc)" --target sdflow
build/release/cli/sdflow stats samples/meshes/torus_6_3.off
