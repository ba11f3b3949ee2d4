#!/usr/bin/env bash
# A local design study of 200 apartment variants (studies/apartment-200.yaml) on this
# machine's cores, killed part way (SIGKILL to it and its variants' processes, once 50 have
# finished) and run again. Checks what a resumed study must do and prints variants per
# minute: the resumed run says the finished variants were not run again, their
# result.json are untouched (bytes and mtime), and all 200 end with a result (feasible or
# infeasible, none failed or missing). Exit 1 when one does not hold.
# Also CTest's Study.TwoHundredApartmentVariantsResumeAfterAKill, labelled `long` (about
# 9 minutes on 2 cores): `ctest -L long`; the default test run leaves it out.
# Usage: bench/study_apartment.sh [CCBUILD] [JOBS]
set -euo pipefail
ccbuild=$(realpath "${1:-build/ccbuild}") jobs=${2:-2}
cd "$(dirname "$0")/.."
work=$(mktemp -d /tmp/ccbuild-study-bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
fail() { echo "study_apartment: $*" >&2; exit 1; }
start=$(date +%s.%N)
setsid "$ccbuild" study studies/apartment-200.yaml -o "$work/s" --jobs "$jobs" > "$work/first.txt" 2>&1 &
pid=$!
# Killed (SIGKILL, its variants' processes too) once 50 variants have finished.
while [ "$( (find "$work/s/variants" -name result.json 2>/dev/null || true) | wc -l)" -lt 50 ]; do
  kill -0 "$pid" 2>/dev/null || { cat "$work/first.txt"; fail "the study ended before 50 variants finished"; }
  sleep 0.2
done
kill -KILL -- -"$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
# Each variant's schedule runs in a process group of its own (and holds the variant's lock:
# left running, the resumed study would leave that variant to it): killed too.
for group in $(pgrep -f -- "$work/s/variants/" | xargs -r ps -o pgid= -p | sort -u); do
  kill -KILL -- -"$group" 2>/dev/null || true
done
for _ in $(seq 1 100); do
  pgrep -f -- "$work/s/variants/" >/dev/null || break
  sleep 0.1
done
killed=$(date +%s.%N)
before=$(find "$work/s/variants" -name result.json | sort)
count=$(echo "$before" | grep -c .)
for f in $before; do cp -p "$f" "$f.saved"; done
rc=0
"$ccbuild" study studies/apartment-200.yaml -o "$work/s" --jobs "$jobs" > "$work/second.txt" 2>&1 || rc=$?
end=$(date +%s.%N)
grep -E "finished before with|variants:" "$work/second.txt" || true
[ "$rc" -eq 0 ] || { tail -20 "$work/second.txt"; fail "the resumed study exited $rc"; }
# A variant killed while it ran left no result.json (it is written last, atomically):
# every one found after the kill is a finished variant and must be skipped.
grep -Eq "^study: $count variant\(s\) finished before with the same inputs were not run again" "$work/second.txt" ||
  fail "the resumed run did not skip the $count variants finished before the kill"
for f in $before; do
  cmp -s "$f" "$f.saved" && [ ! "$f" -nt "$f.saved" ] || fail "$f was run again"
done
python3 - "$start" "$killed" "$end" "$work/s/results.csv" "$count" <<'PY'
import csv, sys
start, killed, end = map(float, sys.argv[1:4])
rows = list(csv.DictReader(open(sys.argv[4])))
done = [r for r in rows if r["status"] in ("feasible", "infeasible")]
if len(rows) != 200 or len(done) != 200:
    sys.exit("study_apartment: %d rows, %d with a result; expected 200 of 200" % (len(rows), len(done)))
print("study_apartment: %d variants (%d feasible) in %.0f s (killed at %.0f s after %s finished, "
      "resumed): %.1f variants per minute"
      % (len(done), sum(r["status"] == "feasible" for r in rows), end - start, killed - start,
         sys.argv[5], len(done) / (end - start) * 60))
PY
