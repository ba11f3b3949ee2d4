#!/usr/bin/env bash
# Runs `ccbuild COMMAND ARGS --json --svg` and re-checks both outputs with the independent
# checkers: for plan-layer check_plan.py and check_svg.py (one nozzle: also the lower
# bound's --bound-certificate with check_bound.py), for climb check_climbs.py and
# the SVG parsed as XML with its groups present, for schedule check_schedule.py on its
# -o file (and `ccbuild report` reading it back) and check_report.py (headless Chromium) on its --report; with each JSON checker's self-test (it must catch planted corruptions of this
# very output) when the run succeeded. SELF_TEST=0 and REPORT=0 leave out the self-test and
# Chromium where the same kind of output is checked so elsewhere; EXPECT_PLAN=REGEX asks
# that some layer's plan key match it.
# Usage: check_outputs.sh CCBUILD PYTHON EXPECTED_EXIT plan-layer|climb|schedule ARGS...
set -euo pipefail
ccbuild=$1 python=$2 expected=$3 command=$4
shift 4
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# One nozzle's plan also writes the connected bound's certificate.
certificate=()
if [ "$command" = plan-layer ] && [[ " $* " != *" --nozzles "* ]]; then
  certificate=(--bound-certificate "$out/bound.json")
fi
set +e
if [ "$command" = schedule ]; then
  # --no-compare: the other objective's schedule is not what is checked here.
  "$ccbuild" schedule "$@" --quiet --no-compare -o "$out/out.json" --report "$out/out.html" \
    > "$out/summary.txt"
else
  "$ccbuild" "$command" "$@" --json --svg "$out/out.svg" "${certificate[@]}" > "$out/out.json"
fi
code=$?
set -e
if [ "$code" -ne "$expected" ]; then
  echo "ccbuild $command $*: exit $code, expected $expected" >&2
  exit 1
fi
case "$command" in
  plan-layer)
    "$python" "$here/check_plan.py" "$out/out.json"
    "$python" "$here/check_svg.py" "$out/out.svg" "$out/out.json"
    if [ ${#certificate[@]} -gt 0 ]; then
      "$python" "$here/check_bound.py" "$out/bound.json" --plan "$out/out.json"
      [ "$expected" -ne 0 ] || "$python" "$here/check_bound.py" --self-test "$out/bound.json"
    fi
    checker=check_plan.py
    ;;
  climb)
    "$python" "$here/check_climbs.py" "$out/out.json"
    "$python" - "$out/out.svg" <<'PY'
import sys
import xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
ids = {e.get("id") for e in root.iter() if e.get("id")}
missing = {"title", "walls", "elevation"} - ids
if missing:
    sys.exit("check_outputs: the climbs' SVG lacks %s" % sorted(missing))
PY
    checker=check_climbs.py
    ;;
  schedule)
    "$python" "$here/check_schedule.py" "$out/out.json"
    # EXPECT_PLAN=REGEX: some layer's plan key matches it (a held-back plan, `h$`, say), so
    # that a rule the schedule could do without is seen to be used.
    if [ -n "${EXPECT_PLAN:-}" ]; then
      "$python" - "$out/out.json" "$EXPECT_PLAN" <<'PY'
import json, re, sys
keys = [layer["plan"] for layer in json.load(open(sys.argv[1]))["layers"]]
if not any(re.search(sys.argv[2], key) for key in keys):
    sys.exit("check_outputs: no layer's plan key matches %r (keys: %s)" % (sys.argv[2], sorted(set(keys))))
PY
    fi
    # ccbuild's own re-validation (read_schedule) accepts what the scheduler wrote.
    "$ccbuild" report "$out/out.json" -o "$out/again.html" > /dev/null
    # The report, in headless Chromium: every section drawn, no console error. REPORT=0
    # where a report of the same kind (the same sections and drawings) is opened elsewhere.
    if [ "${REPORT:-1}" != 0 ]; then
      "$python" "$here/check_report.py" "$out/out.html" $([ "$expected" -eq 1 ] && echo --infeasible)
    fi
    # REPORT_SELF_TEST=1: check_report.py must catch a page that draws other numbers than
    # the schedule's (a buildability ratio, an anchor's strength, an interval in clock
    # time where the window is in equivalent age), each planted in the page's script.
    if [ "${REPORT_SELF_TEST:-0}" = 1 ]; then
      for plant in \
        's#l.below_strength_mpa / l.below_required_mpa,#l.below_strength_mpa / l.below_required_mpa * 1.001,#|buildability:' \
        's#y(q\[1\]).toFixed(2)#y(q[1] * 1.01).toFixed(2)#|climb ' \
        's#return equivalent ? l.equivalent_interval_min_s : l.local_interval_min_s;#return l.local_interval_min_s;#|intervals:'; do
        sed "${plant%|*}" "$out/out.html" > "$out/planted.html"
        if cmp -s "$out/out.html" "$out/planted.html"; then
          echo "check_outputs: the plant '${plant%|*}' changed nothing in the page" >&2
          exit 1
        fi
        if "$python" "$here/check_report.py" "$out/planted.html" > "$out/planted.txt"; then
          echo "check_outputs: check_report.py passed a page planted with '${plant%|*}'" >&2
          exit 1
        fi
        if ! grep -q "^problem: ${plant#*|}" "$out/planted.txt"; then
          echo "check_outputs: check_report.py caught '${plant%|*}' only as:" >&2
          cat "$out/planted.txt" >&2
          exit 1
        fi
        echo "report self-test: caught ${plant%|*}"
      done
    fi
    checker=check_schedule.py
    ;;
  *)
    echo "check_outputs.sh: no checker for '$command'" >&2
    exit 2
    ;;
esac
# SELF_TEST=0: the checker's self-test is run on a schedule of the same kind elsewhere (a
# tower's self-test takes a minute: each planted corruption is a whole check).
if [ "$expected" -eq 0 ] && [ "${SELF_TEST:-1}" != 0 ]; then
  "$python" "$here/$checker" --self-test "$out/out.json"
fi
