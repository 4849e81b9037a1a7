#!/usr/bin/env bash
# Builds the libFuzzer harnesses of fuzz/ with clang (SDFLOW_BUILD_FUZZERS, AddressSanitizer and
# UndefinedBehaviorSanitizer on the whole toolbox) and runs each for a short time on a copy of the
# seed corpus in fuzz/corpus/. A crash, a leak of a non-sdflow exception or a sanitizer report
# stops the script with the reproducer (crash-*, in build/fuzz/findings/NAME/).
#   scripts/fuzz.sh                  every harness for 10 s, fuzz_run (two steps of a run per input,
#                                    a hundred times a reader's work) for 60 s (CI: about 3 minutes in all)
#   scripts/fuzz.sh --seconds 600    longer runs (README: "Fuzzing"), fuzz_run too
#   scripts/fuzz.sh --run-seconds N  fuzz_run's time when longer than --seconds (default 60)
#   scripts/fuzz.sh --only ply       one harness (fuzz_read_ply); --jobs N builds with N jobs
#   scripts/fuzz.sh --no-build       run what build/fuzz already holds
#   scripts/fuzz.sh --build-dir DIR  build and run the harnesses in DIR (default build/fuzz); a DIR
#                                    already configured with SDFLOW_BUILD_FUZZERS (scripts/test.sh
#                                    --sanitize's build/sanitize, as CI does) is built, not configured
#   scripts/fuzz.sh --seed N         libFuzzer's random seed (default: a new one each run); CI fixes
#                                    it, so that a clean checkout fuzzes the same inputs each time
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=10
run_seconds=60
only=""
jobs=$(nproc)
build=1
seed=0
dir=build/fuzz
while (($#)); do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --run-seconds) run_seconds=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --no-build) build=0; shift ;;
    --seed) seed=$2; shift 2 ;;
    --build-dir) dir=$2; shift 2 ;;
    *) echo "fuzz.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done

[[ $seed =~ ^[0-9]+$ ]] || { echo "fuzz.sh: --seed takes a non-negative integer, got '$seed'" >&2; exit 2; }
for n in "$seconds" "$run_seconds"; do
  [[ $n =~ ^[0-9]+$ ]] || { echo "fuzz.sh: --seconds and --run-seconds take a whole number, got '$n'" >&2; exit 2; }
done
harnesses=(read_off read_obj read_ply read_stl read_vtp validate repair scenario schedule checkpoint run)
if [[ -n $only ]]; then harnesses=("$only"); fi
if ((build)); then
  scripts/install-deps.sh --fuzz
  grep -q '^SDFLOW_BUILD_FUZZERS:BOOL=ON' "$dir/CMakeCache.txt" 2>/dev/null ||
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
    -DCMAKE_CXX_COMPILER=clang++ -DSDFLOW_BUILD_FUZZERS=ON -DSDFLOW_BUILD_TESTS=OFF -DSDFLOW_BUILD_CLI=OFF \
    -DSDFLOW_BUILD_MESHLAB_PLUGIN=OFF > /dev/null
  cmake --build "$dir" -j "$jobs" --target "${harnesses[@]/#/fuzz_}"
fi

export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
for h in "${harnesses[@]}"; do
  seeds=fuzz/corpus/${h#read_}
  work=$dir/corpus/$h findings=$dir/findings/$h
  mkdir -p "$work" "$findings"
  cp -n "$seeds"/* "$work"/ 2>/dev/null || true
  # fuzz_run starts from its findings too (the regression meshes): the bugs were near them.
  [[ $h == run ]] && cp -n tests/data/fuzz_run/*.off "$work"/
  log=$dir/fuzz_$h.log
  # fuzz_run's inputs are OFF files of up to 400 vertices, but the re-triangulation may refine one
  # tenfold (the torus seed to 1355 vertices: 0.2 s in the release build, 4 to 7 s instrumented on
  # a busy 2-core machine, where a 10 s limit stopped a run on it), so its per-input limit is 30 s.
  max_len=4096 time=$seconds timeout=10
  [[ $h == run ]] && max_len=20000 time=$((run_seconds > seconds ? run_seconds : seconds)) timeout=30
  if "$dir/fuzz/fuzz_$h" -seed="$seed" -max_total_time="$time" -max_len="$max_len" -rss_limit_mb=2048 -timeout="$timeout" \
       -artifact_prefix="$findings/" -print_final_stats=1 "$work" > "$log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
    echo "fuzz.sh: fuzz_$h: $runs executions in ${time} s, no finding"
  else
    status=1
    echo "fuzz.sh: fuzz_$h FOUND A PROBLEM (reproducer in $findings/):" >&2
    grep -E 'ERROR|SUMMARY|terminate|what\(\)|^fuzz_run:' "$log" | head -5 >&2 || tail -20 "$log" >&2
  fi
done
exit $status
