#!/usr/bin/env bash
# Runs `ccbuild plan-layer ARGS --json --svg` and re-checks both outputs with the
# independent checkers (check_plan.py, check_svg.py), including the plan checker's
# self-test (it must catch planted corruptions of this very plan).
# Usage: check_outputs.sh CCBUILD PYTHON EXPECTED_EXIT ARGS...
set -euo pipefail
ccbuild=$1 python=$2 expected=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
set +e
"$ccbuild" plan-layer "$@" --json --svg "$out/plan.svg" > "$out/plan.json"
code=$?
set -e
if [ "$code" -ne "$expected" ]; then
  echo "ccbuild plan-layer $*: exit $code, expected $expected" >&2
  exit 1
fi
"$python" "$here/check_plan.py" "$out/plan.json"
"$python" "$here/check_svg.py" "$out/plan.svg" "$out/plan.json"
if [ "$expected" -eq 0 ]; then
  "$python" "$here/check_plan.py" --self-test "$out/plan.json"
fi
