#!/usr/bin/env bash
# Times a local design study of 200 apartment variants on this machine's cores
# (studies/apartment-200.yaml), killed part way and resumed, and prints variants per
# minute. Never run by CI. Usage: bench/study_apartment.sh [CCBUILD] [JOBS]
set -euo pipefail
ccbuild=$(realpath "${1:-build/ccbuild}") jobs=${2:-2}
cd "$(dirname "$0")/.."
work=$(mktemp -d /tmp/ccbuild-study-bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
start=$(date +%s.%N)
setsid "$ccbuild" study studies/apartment-200.yaml -o "$work/s" --jobs "$jobs" > "$work/first.txt" 2>&1 &
pid=$!
# Killed (SIGKILL, its variants' processes too) once 50 variants have finished.
while [ "$( (find "$work/s/variants" -name result.json 2>/dev/null || true) | wc -l)" -lt 50 ]; do sleep 0.2; done
kill -KILL -- -"$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
killed=$(date +%s.%N)
"$ccbuild" study studies/apartment-200.yaml -o "$work/s" --jobs "$jobs" > "$work/second.txt" 2>&1 || true
end=$(date +%s.%N)
grep -E "finished before with|variants:" "$work/second.txt"
python3 - "$start" "$killed" "$end" "$work/s/results.csv" <<'PY'
import csv, sys
start, killed, end = map(float, sys.argv[1:4])
rows = list(csv.DictReader(open(sys.argv[4])))
done = [r for r in rows if r["status"] in ("feasible", "infeasible")]
print("study_apartment: %d variants (%d feasible) in %.0f s (killed at %.0f s, resumed): %.1f variants per minute"
      % (len(done), sum(r["status"] == "feasible" for r in rows), end - start, killed - start, len(done) / (end - start) * 60))
PY
