#!/usr/bin/env bash
# Exports a schedule and re-checks the file with programs outside ccbuild:
#   csv:   check_csv_export.py (Python's csv module);
#   ical:  check_ical_export.py (Debian's python3-icalendar) and ical2html (libical);
#   mspdi: GNOME Planner's msp2planner.xsl (xsltproc), then check_mspdi_export.py;
#   days:  check_days_export.py (the work packages by day).
# A building (.yaml) is scheduled first, with ARGS. PYTHON must see python3-icalendar for
# ical (Debian's /usr/bin/python3).
# Usage: export_check.sh CCBUILD PYTHON FORMAT SCHEDULE.json|BUILDING.yaml [--start T] [ARGS...]
set -euo pipefail
ccbuild=$1 python=$2 format=$3 source=$4
shift 4
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
start=()
if [ "${1:-}" = --start ]; then start=(--start "$2"); shift 2; fi
schedule=$source
if [[ "$source" == *.yaml ]]; then
  "$ccbuild" schedule "$source" "$@" --quiet --no-compare -o "$out/schedule.json" > /dev/null
  schedule=$out/schedule.json
fi
case $format in
  csv)
    "$ccbuild" export "$schedule" --format csv -o "$out/tasks.csv" "${start[@]}"
    "$python" "$here/check_csv_export.py" "$schedule" "$out/tasks.csv" "${start[@]}"
    ;;
  ical)
    "$ccbuild" export "$schedule" --format ical -o "$out/tasks.ics" "${start[@]}"
    # ical2html shows the days from the schedule's first to its last (its arguments: the
    # first date and a duration in days).
    read -r first days zone < <("$python" - "$schedule" "${start[@]}" <<'PY'
import json, math, sys
doc = json.load(open(sys.argv[1]))
site = doc["inputs"].get("site")
first = (site["start"] if site else sys.argv[3])[:10].replace("-", "")
print(first, math.ceil(doc["totals"]["makespan_s"] / 86400) + 2, site["time_zone"] if site else "UTC")
PY
)
    ical2html -z "$zone" -d "$first" "P${days}D" "$out/tasks.ics" > "$out/tasks.html"
    "$python" "$here/check_ical_export.py" "$schedule" "$out/tasks.ics" "${start[@]}" \
      --ical2html "$out/tasks.html"
    ;;
  mspdi)
    "$ccbuild" export "$schedule" --format mspdi -o "$out/tasks.xml" "${start[@]}"
    xsltproc /usr/share/planner/stylesheets/msp2planner.xsl "$out/tasks.xml" > "$out/planner.xml"
    "$python" "$here/check_mspdi_export.py" "$schedule" "$out/planner.xml" "$out/tasks.xml" \
      "${start[@]}"
    ;;
  days)
    "$ccbuild" export "$schedule" --format days -o "$out/days.txt" "${start[@]}"
    "$python" "$here/check_days_export.py" "$schedule" "$out/days.txt" "${start[@]}"
    ;;
  *) echo "export_check.sh: unknown format $format" >&2; exit 2 ;;
esac
