#!/usr/bin/env bash
# The dry-run as separate processes over udpm:// in a network namespace of its own (never
# on the shared network): `ccbuild dry-run` and one `ccbuild-sim` per gantry. Checks the
# exit code, that every job was executed, and, from the simulated machines' own records
# (not the dispatcher's), that each job ran exactly once.
# The journal must be consistent: every job done, or ended on a fault whose recovery job
# is done; no fault met by stopping. Lines the summary must hold can be given in EXPECT
# (one extended regular expression per line); EXPECT_EXIT=1 for a run that must stop
# (then jobs may be left, but none may run twice or go unreported). CHECK_JOINTS checks
# every joint between layers from the machines' messages (check_joints.py). The summary
# speaks one unit per column (check_units.py), lengths in LENGTHS (ft or m) when set, and
# explains every table's columns. ON_PLAN=1 requires every layer within 1 s of its plan
# and no re-plan (a clean run of a valid schedule), naming the first layer off plan.
# Usage: [EXPECT=...] dry_run_netns.sh CCBUILD ARGS...   (needs root for unshare -n)
set -euo pipefail
# As root, a network namespace; otherwise a user namespace with one (needs unprivileged
# user namespaces).
if [ "$(id -u)" -eq 0 ]; then netns="unshare -n"; else netns="unshare -rn"; fi
ccbuild=$1
shift
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# A temporary folder of its own, which the run must leave as it found it.
mkdir "$out/tmp"
TMPDIR="$out/tmp" $netns sh -c 'ip link set lo up && ip link set lo multicast on &&
  ip route add 224.0.0.0/4 dev lo && exec "$@"' sh \
  "$ccbuild" dry-run "$@" --state-dir "$out/state" --journal "$out/journal.sqlite" \
  --log "$out/conversation.lcmlog" \
  > "$out/summary.txt" 2> "$out/progress.txt" && code=0 || code=$?
expect_exit=${EXPECT_EXIT:-0}
[ "$code" = "$expect_exit" ] ||
  { cat "$out/summary.txt" "$out/progress.txt"; echo "exit code $code, expected $expect_exit"; exit 1; }
grep -v '^floor ' "$out/summary.txt"
left=$(ls -A "$out/tmp")
[ -z "$left" ] || { echo "the run left $left in its temporary folder"; exit 1; }
complete=$([ "$expect_exit" = 0 ] && echo yes || echo no)
line=$(grep -E '^[^ ]+: [0-9]+ of [0-9]+ jobs executed on [0-9]+ machine' "$out/summary.txt")
done_jobs=$(echo "$line" | sed -E 's/.*: ([0-9]+) of ([0-9]+) jobs.*/\1/')
all_jobs=$(echo "$line" | sed -E 's/.*: ([0-9]+) of ([0-9]+) jobs.*/\2/')
machines=$(echo "$line" | sed -E 's/.*executed on ([0-9]+) machine.*/\1/')
[ "$complete" = no ] || [ "$done_jobs" = "$all_jobs" ] ||
  { echo "only $done_jobs of $all_jobs jobs executed"; exit 1; }
records=$(ls "$out"/state/*.state | wc -l)
[ "$records" = "$machines" ] || { [ "$complete" = no ] && [ "$records" -le "$machines" ]; } ||
  { echo "$records machine records for $machines machines"; exit 1; }
ran=$(cat "$out"/state/*.state | awk '{print $1}' | sort | wc -l)
unique=$(cat "$out"/state/*.state | awk '{print $1}' | sort -u | wc -l)
[ "$ran" = "$unique" ] || { echo "a job ran twice: $ran runs of $unique jobs"; exit 1; }
[ "$complete" = no ] || [ "$unique" = "$all_jobs" ] ||
  { echo "the machines ran $unique of $all_jobs jobs"; exit 1; }
[ "$unique" = "$done_jobs" ] || { echo "the machines ran $unique jobs, $done_jobs reported"; exit 1; }
# The LCM log: lcm-logger's format (sync word 0xEDA1DA01 first), every job in it.
head -c 4 "$out/conversation.lcmlog" | od -An -tx1 | grep -q "ed a1 da 01" ||
  { echo "the LCM log does not start with lcm-logger's sync word"; exit 1; }
logged=$(grep -a -c "CCBUILD_JOB_" "$out/conversation.lcmlog" || true)
[ "$logged" -ge 1 ] || { echo "no job in the LCM log"; exit 1; }
python3 - "$out/journal.sqlite" "$complete" <<'PY'
import sqlite3, sys
db = sqlite3.connect(sys.argv[1])
complete = sys.argv[2] == "yes"
rows = dict(db.execute("SELECT job_id, state FROM job_state"))
for job, state in sorted(rows.items()):
    if state == "done" or (not complete and state in ("sent", "acked", "refused")):
        continue
    if state in ("clogged", "pin-missed") and any(
            other > job and other // 10 == job // 10 and s == "done" for other, s in rows.items()):
        continue
    sys.exit("journal: job %d is '%s' with no recovery done" % (job, state))
stops = db.execute("SELECT message FROM fault WHERE policy = 'stop'").fetchall()
if complete and stops:
    sys.exit("journal: stopped: %s" % stops)
print("journal: %d jobs, consistent; faults: %s" % (len(rows), db.execute(
    "SELECT group_concat(kind || ' ' || policy, '; ') FROM fault").fetchone()[0]))
PY
# Every joint between layers, from the machines' own messages in the LCM log (not the
# orchestrator's view): CHECK_JOINTS="--min S --max S [--expect-planned]".
if [ -n "${CHECK_JOINTS:-}" ]; then
  # shellcheck disable=SC2086
  python3 "$(dirname "$0")/check_joints.py" "$out/conversation.lcmlog" $CHECK_JOINTS
fi
# One unit per column and per recurring figure in the summary (check_units.py); with
# LENGTHS=ft (or m) every length in that system.
# Every table's columns explained once, in a legend line or in --help.
"$ccbuild" dry-run --help > "$out/help.txt"
python3 "$(dirname "$0")/check_units.py" ${LENGTHS:+--lengths "$LENGTHS"} \
  --help-text "$out/help.txt" "$out/summary.txt"
while IFS= read -r pattern; do
  [ -z "$pattern" ] && continue
  grep -Eq -- "$pattern" "$out/summary.txt" "$out/progress.txt" ||
    { echo "expected a line matching '$pattern'"; cat "$out/progress.txt"; exit 1; }
  echo "found: $pattern"
done <<< "${EXPECT:-}"
# ON_PLAN=1: a clean run, on plan. Every layer starts within 1 s of its planned start and
# nothing is re-planned; with --by-layer the first layer off plan is named.
if [ -n "${ON_PLAN:-}" ]; then
  if ! grep -Eq '^deviations: 0 of [0-9]+ layers' "$out/summary.txt" ||
     ! grep -Eq '^re-plans: 0$' "$out/summary.txt"; then
    python3 - "$out/summary.txt" <<'PY'
import re, sys
for line in open(sys.argv[1]):
    m = re.match(r"(floor \d+ layer \d+) .* ([+-]\d+\.\d) s ", line)
    if m and abs(float(m.group(2))) > 1.0:
        sys.exit("the first layer off plan: " + line.rstrip())
PY
    echo "not on plan: a layer started more than 1 s off its planned start, or a re-plan"
    exit 1
  fi
  echo "on plan: every layer within 1 s of its planned start, 0 re-plans"
fi
echo "dry_run_netns: $all_jobs jobs on $machines machines, each run exactly once by the machines' own records"
