#!/usr/bin/env bash
# Installs the dependencies, builds sdflow and runs the whole test suite on an optimised build.
#   scripts/test.sh              the suite (what CI runs)
#   scripts/test.sh --sanitize   then again under AddressSanitizer + UndefinedBehaviorSanitizer
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs=$(nproc)

run_suite() { # build directory, then extra CMake arguments
  local dir=$1; shift
  mkdir -p "$dir"
  cmake -S . -B "$dir" -G Ninja -DSDFLOW_BUILD_TESTS=ON -DSDFLOW_BUILD_CLI=ON -DSDFLOW_BUILD_MESHLAB_PLUGIN=OFF "$@" \
    > "$dir/configure.log" || { cat "$dir/configure.log"; return 1; }
  cmake --build "$dir" -j "$jobs"
  ctest --test-dir "$dir" --output-on-failure -j "$jobs"
}

run_suite build/release -DCMAKE_BUILD_TYPE=Release
if [[ "${1:-}" == "--sanitize" ]]; then
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    run_suite build/sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSDFLOW_SANITIZE=ON
fi
echo "test.sh: all tests passed"
