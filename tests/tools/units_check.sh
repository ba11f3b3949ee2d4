#!/usr/bin/env bash
# Runs one ccbuild command and checks its text output with check_units.py: no column and
# no recurring figure in two units. The command may answer "no" (exit 1); bad input or a
# crash fails the check.
# With --lengths ft (or m) every length and volume must be in that system. Every table's
# columns must be explained, in a legend line of the output or in the command's --help.
# Usage: units_check.sh CCBUILD PYTHON [--lengths ft|m] COMMAND [ARGS...]   (@OUT@: see below)
set -euo pipefail
ccbuild=$1 python=$2
shift 2
lengths=()
if [ "${1:-}" = --lengths ]; then
  lengths=(--lengths "$2")
  shift 2
fi
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# @OUT@ in the arguments names a file in the temporary folder (an -o the command writes);
# @TXT@ a text file there (export --format days), checked as well as the output.
args=()
for a in "$@"; do
  a=${a//@OUT@/$out/written}
  args+=("${a//@TXT@/$out/written.txt}")
done
rc=0
"$ccbuild" "${args[@]}" > "$out/stdout.txt" 2> "$out/stderr.txt" || rc=$?
if [ "$rc" -gt 1 ]; then
  echo "units_check: ccbuild $* exited $rc" >&2
  cat "$out/stderr.txt" >&2
  exit 1
fi
"$ccbuild" "$1" --help > "$out/help.txt"
echo "ccbuild $*: $(wc -l < "$out/stdout.txt") lines"
"$python" "$here/check_units.py" "${lengths[@]}" --help-text "$out/help.txt" "$out/stdout.txt" ||
  { cat "$out/stdout.txt"; exit 1; }
if [ -f "$out/written.txt" ]; then
  echo "the text it wrote: $(wc -l < "$out/written.txt") lines"
  "$python" "$here/check_units.py" "${lengths[@]}" --help-text "$out/help.txt" "$out/written.txt" ||
    { cat "$out/written.txt"; exit 1; }
fi
