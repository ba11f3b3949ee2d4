#!/usr/bin/env bash
# Exports a schedule as CSV and re-checks it with check_csv_export.py (Python's csv module,
# none of ccbuild's code). A building (.yaml) is scheduled first, with ARGS.
# Usage: export_check.sh CCBUILD PYTHON SCHEDULE.json|BUILDING.yaml [--start T] [ARGS...]
set -euo pipefail
ccbuild=$1 python=$2 source=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
start=()
if [ "${1:-}" = --start ]; then start=(--start "$2"); shift 2; fi
schedule=$source
if [[ "$source" == *.yaml ]]; then
  "$ccbuild" schedule "$source" "$@" --quiet -o "$out/schedule.json" > /dev/null
  schedule=$out/schedule.json
fi
"$ccbuild" export "$schedule" --format csv -o "$out/tasks.csv" "${start[@]}"
"$python" "$here/check_csv_export.py" "$schedule" "$out/tasks.csv" "${start[@]}"
