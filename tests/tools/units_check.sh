#!/usr/bin/env bash
# Runs one ccbuild command and checks its text output with check_units.py: no column and
# no recurring figure in two units. The command may answer "no" (exit 1); bad input or a
# crash fails the check.
# With --lengths ft (or m) every length and volume must be in that system.
# Usage: units_check.sh CCBUILD PYTHON [--lengths ft|m] COMMAND [ARGS...]
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
rc=0
(cd "$(pwd)" && "$ccbuild" "$@" > "$out/stdout.txt" 2> "$out/stderr.txt") || rc=$?
if [ "$rc" -gt 1 ]; then
  echo "units_check: ccbuild $* exited $rc" >&2
  cat "$out/stderr.txt" >&2
  exit 1
fi
echo "ccbuild $*: $(wc -l < "$out/stdout.txt") lines"
"$python" "$here/check_units.py" "${lengths[@]}" "$out/stdout.txt" || { cat "$out/stdout.txt"; exit 1; }
