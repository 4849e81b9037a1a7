#!/usr/bin/env bash
# Before merging a branch: the checks that a GCC build and its test suite do not make, but CI does.
#   scripts/check-merge.sh BUILD_DIR [BASE]
# BUILD_DIR is a configured and built tree (tests and CLI on); BASE (default: the merge base with
# main) is where the branch's changes start. Three checks, each quick next to CI:
#   1. clang 14 parses every toolbox, CLI, fuzz and test source the branch changed or that includes a
#      header it changed, directly or not (BUILD_DIR's dependency lists say which): CI's sanitizer
#      build is clang's, which refuses some things GCC accepts;
#   2. clang parses the unity units of the tests and the CLI (CI builds them so: two files of one
#      unit must not define one name in their anonymous namespaces);
#   3. scripts/test-package.sh BUILD_DIR: the installed package, README's C++ snippets included.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: scripts/check-merge.sh BUILD_DIR [BASE]}
base=${2:-$(git merge-base HEAD main)}
fail() { echo "check-merge.sh: FAIL: $*" >&2; exit 1; }
[[ -f $build/CMakeCache.txt ]] || fail "$build is not a CMake build directory"
command -v clang++ > /dev/null || fail "clang++ is not installed (scripts/install-deps.sh --fuzz)"

# A clang configuration with the unity build on and no precompiled headers: only its compile
# commands are used, nothing is built in it.
check=build/check-merge
cmake -S . -B "$check" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DSDFLOW_BUILD_TESTS=ON -DSDFLOW_BUILD_CLI=ON -DSDFLOW_BUILD_FUZZERS=ON -DSDFLOW_UNITY_BUILD=ON \
  -DSDFLOW_PRECOMPILE_HEADERS=OFF -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > "$check.configure.log" 2>&1 ||
  { cat "$check.configure.log"; fail "configuring $check with clang"; }

mapfile -t changed < <(git diff --name-only "$base" -- toolbox cli fuzz tests | grep -E '\.(cpp|h)$' || true)
echo "check-merge.sh: ${#changed[@]} changed source file(s) since $(git rev-parse --short "$base")"

# The compile commands to parse: changed sources, sources that include a changed header directly or
# through others (by BUILD_DIR's dependency lists, `ninja -t deps`), and every unity unit.
ninja -C "$build" -t deps > "$check.deps"
python3 - "$check/compile_commands.json" "$build" "$check.deps" "${changed[@]}" > "$check.commands" <<'PYTHON'
import json, os, shlex, sys
entries = json.load(open(sys.argv[1]))
build, deps_file = sys.argv[2], sys.argv[3]
changed = {os.path.abspath(p) for p in sys.argv[4:]}
headers = {p for p in changed if p.endswith(".h")}
# Sources whose dependency list names a changed header (each list starts with its source).
affected, source = set(), None
for line in open(deps_file):
    if not line.startswith(" "):
        source = None
        continue
    path = os.path.abspath(os.path.join(build, line.strip()))
    if source is None:
        source = path
    elif path in headers:
        affected.add(source)
for entry in entries:
    source = os.path.abspath(os.path.join(entry["directory"], entry["file"]))
    if not ("/Unity/unity_" in source or source in changed or source in affected):
        continue
    args = shlex.split(entry["command"]) if "command" in entry else entry["arguments"]
    out, skip = [], False
    for arg in args:
        if skip:
            skip = False
        elif arg == "-o":
            skip = True
        elif arg != "-c":
            out.append(arg)
    print(entry["directory"] + "\t" + shlex.join(out + ["-fsyntax-only"]))
PYTHON
count=$(wc -l < "$check.commands")
echo "check-merge.sh: clang parses $count translation unit(s)"
status=0
# Two at a time; each failure prints clang's diagnostics.
while IFS=$'\t' read -r directory command; do
  printf '%s\0%s\0' "$directory" "$command"
done < "$check.commands" |
  xargs -0 -n 2 -P "$(nproc)" sh -c 'cd "$1" && eval "$2" 2>&1 || { echo "check-merge.sh: clang refused: $2" | cut -c1-300; exit 1; }' sh ||
  status=1
[[ $status == 0 ]] || fail "clang refuses code above (CI's sanitizer build would fail)"

scripts/test-package.sh "$build" || fail "the installed package or README's snippets"
echo "check-merge.sh: PASS (clang: $count unit(s) parsed; package and README snippets built)"
