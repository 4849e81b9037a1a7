#!/usr/bin/env bash
# Checks that sdflow is consumable: installs a built tree into a temporary prefix, then builds and
# runs tests/package against it with find_package(sdflow), and configures tests/package again with
# sdflow as a subproject (add_subdirectory), which must leave the parent's build type alone.
#   scripts/test-package.sh BUILD_DIR     (a configured and built tree; CI passes build/release)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:?usage: scripts/test-package.sh BUILD_DIR}
fail() { echo "test-package.sh: FAIL: $*" >&2; exit 1; }
[[ -f $dir/CMakeCache.txt ]] || fail "$dir is not a CMake build directory"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix

# Run a step quietly; on failure show its output and fail with the given message.
step() { # message, command...
  local message=$1; shift
  "$@" > "$tmp/step.log" 2>&1 || { cat "$tmp/step.log"; fail "$message"; }
}

step "cmake --install $dir" cmake --install "$dir" --prefix "$prefix"
# Private headers (a detail/ folder, docs/design.md §4) stay out of the installed tree.
private=$(find "$prefix/include" -path '*/detail*')
[[ -z $private ]] || fail "private headers were installed: $private"
# Every sdflow header an installed header includes is installed too.
while read -r header; do
  [[ -f $prefix/include/$header ]] || fail "an installed header includes $header, which is not installed"
done < <(grep -rhoE '#include "sdflow/[^"]+"' "$prefix/include" | sed 's/.*"\(.*\)"/\1/' | sort -u)

# The Python module, when the build has it, lands in the interpreter's site directory under the prefix.
site=$(sed -n 's/^SDFLOW_PYTHON_INSTALL_DIR:STRING=//p' "$dir/CMakeCache.txt")
if [[ -n $site ]]; then
  python=$(sed -n 's/^_Python3_EXECUTABLE:INTERNAL=//p' "$dir/CMakeCache.txt")
  [[ -f $prefix/$site/sdflow/__init__.py ]] || fail "the Python package was not installed into $prefix/$site"
  (cd "$tmp" && PYTHONPATH=$prefix/$site "${python:-python3}" -c \
     "import sdflow, sys; V, F = sdflow.shape('sphere', vertices=200); sys.exit(sdflow.__file__.startswith('$prefix') is False)") \
    || fail "the installed Python package does not import from $prefix/$site"
fi

step "configure tests/package against $prefix" \
  cmake -S tests/package -B "$tmp/installed" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix"
step "build tests/package against $prefix" cmake --build "$tmp/installed"
"$tmp/installed/consume" || fail "tests/package/consume.cpp against the installed package"

# Configuring is enough to see the build type; building would compile the toolbox once more.
step "configure tests/package with sdflow as a subproject" \
  cmake -S tests/package -B "$tmp/subproject" -G Ninja -DSDFLOW_SOURCE_DIR="$PWD"
echo "test-package.sh: PASS (installed: tests/package and README's C++ snippets built, consume run${site:+, the Python module imported}; subproject: build type kept)"
