#!/usr/bin/env bash
# Writes sdflow's man page with help2man from the program's own help: the top-level --help, and a
# COMMANDS section holding every verb's --help, so the page cannot drift from the program.
#   cli/man/make-man-page.sh SDFLOW_BINARY OUTPUT.1
set -euo pipefail
sdflow=$1 out=$2
include=$(mktemp)
trap 'rm -f "$include" "$out.tmp"' EXIT
# Roff-safe text: backslashes doubled, a leading '.' or "'" (a roff request) protected.
roff() { sed -e 's/\\/\\\\/g' -e "s/^\\([.']\\)/\\\\\\&\\1/"; }
{
  echo "[COMMANDS]"
  "$sdflow" --help | awk '/^Subcommands:/ { on = 1; next } on && NF { print $1 }' | while read -r verb; do
    echo ".SS \"sdflow $verb\""
    echo ".nf"
    "$sdflow" "$verb" --help | sed "s|^Usage: [^ ]*sdflow|Usage: sdflow|" | roff
    echo ".fi"
  done
  echo "[CONVENTIONS]"
  echo "Every verb takes -q (errors only, no progress) and -v (debugging detail) before or after its name;"
  echo "an output is -o, --output or --out; PLY and STL are written binary unless --ascii is given."
  echo "Results go to stdout; logs, errors and progress to stderr. --json prints the result as one JSON"
  echo "object on stdout, or on failure {error, message, exit_code, findings}."
  echo "[EXIT STATUS]"
  echo "0 success; 1 out of memory or an unexpected internal error; 2 bad input (unreadable or invalid"
  echo "file, parameter out of range); 128 + N a run stopped by signal N (checkpoint written);"
  echo "3 numerical failure (the flow cannot go on stably); 4 environment failure (disk full)."
  echo "[SEE ALSO]"
  echo "README.md and docs/ in the sdflow sources."
} > "$include"
help2man --no-info --name "surface diffusion flow on triangulated surfaces" --section 1 \
  --include "$include" --output "$out.tmp" "$sdflow"
mv "$out.tmp" "$out"
