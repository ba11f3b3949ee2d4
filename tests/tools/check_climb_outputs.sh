#!/usr/bin/env bash
# Runs `ccbuild climb ARGS --json --svg` and re-checks the outputs independently:
# check_climbs.py (with its self-test when the climbs are feasible) and the SVG parsed as
# XML with the drawing's groups present.
# Usage: check_climb_outputs.sh CCBUILD PYTHON EXPECTED_EXIT ARGS...
set -euo pipefail
ccbuild=$1 python=$2 expected=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
set +e
"$ccbuild" climb "$@" --json --svg "$out/climbs.svg" > "$out/climbs.json"
code=$?
set -e
if [ "$code" -ne "$expected" ]; then
  echo "ccbuild climb $*: exit $code, expected $expected" >&2
  exit 1
fi
"$python" "$here/check_climbs.py" "$out/climbs.json"
if [ "$expected" -eq 0 ]; then
  "$python" "$here/check_climbs.py" --self-test "$out/climbs.json"
fi
"$python" - "$out/climbs.svg" <<'PY'
import sys
import xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
ids = {e.get("id") for e in root.iter() if e.get("id")}
missing = {"title", "walls", "elevation"} - ids
if missing:
    sys.exit("check_climb_outputs: the SVG lacks %s" % sorted(missing))
PY
