#!/usr/bin/env bash
# A local study killed part way (SIGKILL to it and its variants' process groups) resumes: run
# again, no variant finished before is run again (its result untouched) and the rest
# are; its results page, in headless Chromium, shows what results.json holds; what
# `study collect` prints passes check_units.py. (That a
# resumed study gives a whole run's bytes, Study.OnAOneNodeSlurmCluster... shows: its
# Slurm run is resumed by `collect --resubmit`.)
# Usage: study_resume_check.sh CCBUILD STUDY
set -euo pipefail
ccbuild=$(realpath "$1") study=$(realpath "$2")
work=$(mktemp -d /tmp/ccbuild-study-resume.XXXXXX)
trap 'rm -rf "$work"' EXIT
total=$(grep -c . <(python3 - "$study" <<'PY'
import sys, re
# The variants: the product of the axes' list lengths (the study file's lists only).
n = 1
for line in open(sys.argv[1]):
    m = re.match(r"\s+[\w.]+:\s*\[(.*)\]", line)
    if m: n *= len(m.group(1).split(","))
for _ in range(n): print(1)
PY
))
setsid "$ccbuild" study "$study" -o "$work/s" --jobs 2 > "$work/first.txt" 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  done_now=$( (find "$work/s/variants" -name result.json 2>/dev/null || true) | wc -l)
  [ "$done_now" -ge 6 ] && break
  sleep 0.1
done
kill -KILL -- -"$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
# ...and its variants' schedules, each in a process group of its own (a schedule left
# running holds its variant's lock: the resumed study would leave that variant to it).
for group in $(pgrep -f -- "$work/s/variants/" | xargs -r ps -o pgid= -p | sort -u); do
  kill -KILL -- -"$group" 2>/dev/null || true
done
for _ in $(seq 1 100); do
  pgrep -f -- "$work/s/variants/" >/dev/null || break
  sleep 0.1
done
before=$(find "$work/s/variants" -name result.json | sort)
count=$(echo "$before" | grep -c . || true)
[ "$count" -ge 6 ] && [ "$count" -lt "$total" ] ||
  { echo "killed with $count of $total variants finished; expected some but not all"; exit 1; }
for f in $before; do cp -p "$f" "$f.saved"; done
"$ccbuild" study "$study" -o "$work/s" --jobs 2 > "$work/second.txt" 2>&1 || { cat "$work/second.txt"; exit 1; }
grep -E "^study: $count variant\(s\) finished before with the same inputs were not run again" "$work/second.txt" ||
  { cat "$work/second.txt"; echo "the resumed run did not skip the $count finished variants"; exit 1; }
for f in $before; do
  cmp "$f" "$f.saved" && [ ! "$f" -nt "$f.saved" ] || { echo "$f was run again"; exit 1; }
  rm "$f.saved"
done
rows=$(tail -n +2 "$work/s/results.csv" | grep -c ',feasible,' || true)
[ "$rows" -eq "$total" ] || { echo "$rows of $total variants feasible after the resume"; exit 1; }
# The results page, opened in headless Chromium, against results.json.
python3 "$(dirname "$0")/check_study_page.py" "$work/s"
# What collect prints speaks one unit per figure and explains its tables (check_units.py).
"$ccbuild" study collect "$work/s" > "$work/collect.txt"
"$ccbuild" study --help > "$work/help.txt"
python3 "$(dirname "$0")/check_units.py" --lengths m --help-text "$work/help.txt" "$work/collect.txt" ||
  { cat "$work/collect.txt"; exit 1; }
echo "study_resume_check: killed after $count of $total variants; resumed, none run twice, all $total feasible"
