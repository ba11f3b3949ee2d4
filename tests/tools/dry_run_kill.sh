#!/usr/bin/env bash
# The dispatcher killed (SIGKILL) at random points and restarted on the same journal and
# the same machine records: the dry-run completes with no job lost and none run twice,
# by the simulated machines' own records. Each run in a network namespace of its own.
# Usage: dry_run_kill.sh SEED CCBUILD ARGS...   (needs root for unshare -n)
set -euo pipefail
# As root, a network namespace; otherwise a user namespace with one (needs unprivileged
# user namespaces).
if [ "$(id -u)" -eq 0 ]; then netns="unshare -n"; else netns="unshare -rn"; fi
seed=$1 ccbuild=$2
shift 2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
RANDOM=$seed
# A temporary folder of the runs' own: given a journal and a state folder, a run makes
# nothing there, so even a killed one leaves it empty.
mkdir "$out/tmp"
run() {
  TMPDIR="$out/tmp" $netns sh -c 'ip link set lo up && ip link set lo multicast on &&
    ip route add 224.0.0.0/4 dev lo && exec "$@"' sh \
    "$ccbuild" dry-run "$@" --state-dir "$out/state" --journal "$out/journal.sqlite" \
    --seed "$seed"
}
kills=0
for attempt in 1 2 3; do
  after=$(( (RANDOM % 20) + 15 ))  # tenths of a second: 1.5 to 3.4 s
  if timeout -s KILL "$((after / 10)).$((after % 10))" bash -c "$(declare -f run); out=$out ccbuild=$ccbuild seed=$seed netns='$netns' run $(printf '%q ' "$@")" \
      > "$out/run$attempt.txt" 2>&1; then
    break
  fi
  kills=$((kills + 1))
  sleep 0.3  # the killed run's machines stop (they die with it)
done
before=$( (cat "$out"/state/*.state 2>/dev/null || true) | wc -l)
# The test means something only when a killed run had done part of the work.
[ "$kills" -ge 1 ] && [ "$before" -ge 1 ] ||
  { echo "no run was killed part-way (kills $kills, jobs done before the last run $before)"; exit 1; }
run "$@" > "$out/final.txt" 2> "$out/final.err" || { cat "$out/final.txt" "$out/final.err"; exit 1; }
cat "$out/final.txt"
line=$(grep -E 'jobs executed on' "$out/final.txt")
all_jobs=$(echo "$line" | sed -E 's/.*: ([0-9]+) of ([0-9]+) jobs.*/\2/')
ran=$(cat "$out"/state/*.state | awk '{print $1}' | sort | wc -l)
unique=$(cat "$out"/state/*.state | awk '{print $1}' | sort -u | wc -l)
[ "$ran" = "$unique" ] || { echo "a job ran twice: $ran runs of $unique jobs"; exit 1; }
[ "$unique" = "$all_jobs" ] || { echo "the machines ran $unique of $all_jobs jobs: some were lost"; exit 1; }
left=$(ls -A "$out/tmp")
[ -z "$left" ] || { echo "the runs left $left in their temporary folder"; exit 1; }
echo "dry_run_kill: killed $kills time(s) with $before jobs done; $all_jobs jobs, each run exactly once by the machines' own records"
