#!/usr/bin/env bash
# Before merging a branch: the checks that a GCC build and its test suite do not make, but CI does.
#   scripts/check-merge.sh BUILD_DIR [BASE]
# BUILD_DIR is a configured and built tree (tests and CLI on); BASE (default: the merge base with
# main) is where the branch's changes start. Three checks, each quick next to CI:
#   1. clang 14 parses every toolbox, CLI, fuzz and test source the branch changed or that includes a
#      header it changed (CI's sanitizer build is clang's, which refuses some things GCC accepts);
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

# The compile commands to parse: changed sources, sources including a changed header (by its path
# below the include root, e.g. sdflow/flow/stepper.h), and every unity unit.
python3 - "$check/compile_commands.json" "${changed[@]}" > "$check.commands" <<'PYTHON'
import json, os, re, shlex, sys
entries = json.load(open(sys.argv[1]))
changed = [os.path.abspath(p) for p in sys.argv[2:]]
headers = [p for p in changed if p.endswith(".h")]
# The spelling an #include uses: the path below toolbox/ (sdflow/...), or the file name for others.
spellings = [p.split("/toolbox/", 1)[1] if "/toolbox/" in p else os.path.basename(p) for p in headers]
def includes_changed(path):
    try:
        text = open(path, encoding="utf-8", errors="replace").read()
    except OSError:
        return False
    return any(re.search(r'#include\s+"([^"]*/)?' + re.escape(s) + '"', text) for s in spellings)
for entry in entries:
    source = os.path.abspath(os.path.join(entry["directory"], entry["file"]))
    unity = "/Unity/unity_" in source
    if not (unity or source in changed or (spellings and includes_changed(source))):
        continue
    args = shlex.split(entry["command"]) if "command" in entry else entry["arguments"]
    out = []
    skip = False
    for arg in args:
        if skip:
            skip = False
            continue
        if arg == "-o":
            skip = True
            continue
        if arg == "-c":
            continue
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
