#!/usr/bin/env bash
# Installs the dependencies, builds sdflow and runs the whole test suite on an optimised build.
#   scripts/test.sh              the suite, Python's pytest included (the README's test command; CI runs it first)
#   scripts/test.sh --sanitize   the suite under AddressSanitizer + UndefinedBehaviorSanitizer, built with
#                                clang in build/sanitize together with the libFuzzer harnesses, which
#                                scripts/fuzz.sh --build-dir build/sanitize then runs (CI does both)
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ "${1:-}" == "--sanitize" ]]; then scripts/install-deps.sh --fuzz; else scripts/install-deps.sh; fi
jobs=$(nproc)

skip=() # ctest arguments leaving tests out
run_suite() { # build directory, then extra CMake arguments
  local dir=$1; shift
  mkdir -p "$dir"
  # Unity build of the tests and the CLI: about a third less compile time (issue 34 item 8).
  cmake -S . -B "$dir" -G Ninja -DSDFLOW_BUILD_TESTS=ON -DSDFLOW_BUILD_CLI=ON -DSDFLOW_BUILD_MESHLAB_PLUGIN=OFF \
    -DSDFLOW_UNITY_BUILD=ON "$@" \
    > "$dir/configure.log" || { cat "$dir/configure.log"; return 1; }
  cmake --build "$dir" -j "$jobs"
  ctest --test-dir "$dir" --output-on-failure -j "$jobs" "${skip[@]}"
}

if [[ "${1:-}" == "--sanitize" ]]; then
  export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  # The long convergence studies run in the optimised suite only (tests/long-under-sanitizers.txt says
  # which, and which shorter tests run their code under the sanitizers).
  skip=(-E "$(grep -v '^#' tests/long-under-sanitizers.txt | paste -sd'|')")
  # The tests' own code is compiled without the sanitizers, at -O1 (tests/CMakeLists.txt): they watch
  # the toolbox and the CLI. Line tables only (-g1): enough for the sanitizers' stack traces, and much quicker to compile and
  # link than full debug information, which CI's time budget does not afford. Clang, with the fuzz
  # harnesses: the toolbox is compiled once, instrumented for both (its libFuzzer edge counters cost the
  # tests little).
  run_suite build/sanitize -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DSDFLOW_SANITIZE=ON -DSDFLOW_BUILD_FUZZERS=ON
else
  # The Python module and its pytest suite (ctest runs it) are part of the optimised build only: an
  # extension built with AddressSanitizer would need the sanitizer runtime preloaded into python3.
  run_suite build/release -DCMAKE_BUILD_TYPE=Release -DSDFLOW_BUILD_PYTHON=ON
fi
echo "test.sh: all tests passed"
