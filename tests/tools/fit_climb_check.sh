#!/usr/bin/env bash
# Fits the climbing machine family to BUILDING and checks every output with programs that
# are not ccbuild: the fitted URDF with Debian's check_urdf (urdfdom), the climbs planned on
# the fitted machine with check_climbs.py (against that URDF), the schedule with
# check_schedule.py; and that `climb` and `schedule` place the same stages, and that the
# family fitted on the fly gives the same stages as the fitted file (left out with
# `--no-fly`: the tower fits and plans its climbs again for it, 16 s, and the other
# buildings check it).
# Usage: fit_climb_check.sh CCBUILD PYTHON FAMILY BUILDING [--no-fly]
set -euo pipefail
ccbuild=$1 python=$2 family=$3 building=$4 fly=${5:-}
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
command -v check_urdf >/dev/null || { echo "check_urdf missing: scripts/install-deps.sh installs liburdfdom-tools" >&2; exit 1; }

"$ccbuild" fit "$building" --machine "$family" -o "$out/fitted.yaml" --quiet > "$out/fit.txt"
check_urdf "$out/fitted.urdf" > "$out/check_urdf.txt" || { cat "$out/check_urdf.txt" >&2; exit 1; }
grep -q "Successfully Parsed XML" "$out/check_urdf.txt"

"$ccbuild" climb "$building" --machine "$out/fitted.yaml" --json > "$out/climbs.json"
"$python" "$here/check_climbs.py" "$out/climbs.json"
"$ccbuild" schedule "$building" --machine "$out/fitted.yaml" --quiet --no-compare -o "$out/schedule.json" > /dev/null
"$python" "$here/check_schedule.py" "$out/schedule.json"
if [ "$fly" = --no-fly ]; then
  cp "$out/climbs.json" "$out/on_the_fly.json"
else
  "$ccbuild" climb "$building" --machine "$family" --json > "$out/on_the_fly.json"
fi

"$python" - "$out/climbs.json" "$out/schedule.json" "$out/on_the_fly.json" <<'PY'
import json
import sys
climbs, schedule, fly = (json.load(open(p)) for p in sys.argv[1:])
if not schedule["feasible"]:
    sys.exit("the schedule on the fitted machine is not feasible")
if climbs["stages"] != schedule["stages"]:
    sys.exit("climb and schedule place different stages")
if fly["stages"] != climbs["stages"]:
    sys.exit("the family fitted on the fly places different stages from the fitted file")
if len(climbs["stages"]) < 2:
    sys.exit("expected the building to need climbs")
print("%d stages, %d climbs: fitted, climbed and scheduled" % (len(climbs["stages"]), len(climbs["climbs"])))
PY
