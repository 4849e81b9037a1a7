#!/usr/bin/env bash
# Installs the dependencies, builds sdflow and runs the whole test suite twice: an optimised build,
# then an AddressSanitizer + UndefinedBehaviorSanitizer build. Usage: scripts/test.sh [--fast]
# (--fast skips the sanitizer pass).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs=$(nproc)

run_suite() { # build directory, then extra CMake arguments
  local dir=$1; shift
  cmake -S . -B "$dir" -G Ninja -DSDFLOW_BUILD_TESTS=ON -DSDFLOW_BUILD_CLI=ON "$@" > "$dir.configure.log" \
    || { cat "$dir.configure.log"; return 1; }
  cmake --build "$dir" -j "$jobs"
  ctest --test-dir "$dir" --output-on-failure -j "$jobs"
}

mkdir -p build
run_suite build/release -DCMAKE_BUILD_TYPE=Release -DSDFLOW_BUILD_MESHLAB_PLUGIN=OFF
if [[ "${1:-}" != "--fast" ]]; then
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    run_suite build/sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSDFLOW_SANITIZE=ON -DSDFLOW_BUILD_MESHLAB_PLUGIN=OFF
fi
echo "test.sh: all tests passed"
