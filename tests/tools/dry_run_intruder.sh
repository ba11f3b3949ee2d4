#!/usr/bin/env bash
# Hostile messages on gantry-1's channels while the twin cottages are dry-run (bus_intruder:
# random bytes, a truncated job, another type, a job for another machine, a replayed job,
# a stale job with an id the schedule lacks, a stale pause). The machine must reject and
# log each, execute none, and the dry-run complete with every job once by the machines'
# own records (a stale pause obeyed would stall it; a stale job run would add a job).
# Usage: dry_run_intruder.sh CCBUILD BUS_INTRUDER   (from the source tree)
set -euo pipefail
if [ "$(id -u)" -eq 0 ]; then netns="unshare -n"; else netns="unshare -rn"; fi
ccbuild=$1
intruder=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
url='udpm://239.255.76.67:7667?ttl=0'
"$ccbuild" schedule tests/data/buildings/twin-cottages.yaml -o "$out/twin.json" --quiet > /dev/null
$netns sh -c 'ip link set lo up && ip link set lo multicast on &&
  ip route add 224.0.0.0/4 dev lo || exit 1
  "$1" dry-run "$2/twin.json" --speed 200 --timeout 60 --state-dir "$2/state" \
    > "$2/summary.txt" 2> "$2/progress.txt" &
  run=$!
  "$3" "$4" gantry-1 > "$2/intruder.txt" || { kill $run; exit 1; }
  wait $run' sh "$ccbuild" "$out" "$intruder" "$url" ||
  { cat "$out/summary.txt" "$out/progress.txt" "$out/intruder.txt"; exit 1; }
cat "$out/intruder.txt"
grep -v '^floor ' "$out/summary.txt"
expect() {  # expect COUNT PATTERN: at least COUNT lines of the machines' log match
  local n
  n=$(grep -c -- "$2" "$out/progress.txt" || true)
  [ "$n" -ge "$1" ] || { echo "expected $1 x '$2' in the log, found $n"; cat "$out/progress.txt"; exit 1; }
  echo "logged $n x: $2"
}
expect 3 "ccbuild-sim gantry-1: rejected a message on CCBUILD_JOB_gantry-1 .* does not decode"
expect 1 "ccbuild-sim gantry-1: fault: a job for machine 'gantry-9'"
expect 1 "rejected a replayed message on CCBUILD_JOB_gantry-1 .*seen before"
expect 1 "rejected a replayed message on CCBUILD_JOB_gantry-1 .*older than the newest"
expect 1 "rejected a replayed message on CCBUILD_COMMAND_gantry-1 .*older than the newest"
if grep -q "ccbuild-sim gantry-1: paused" "$out/progress.txt"; then
  echo "gantry-1 obeyed a stale pause"; exit 1
fi
all=$(grep -E '^[^ ]+: [0-9]+ of [0-9]+ jobs executed' "$out/summary.txt" | sed -E 's/.* of ([0-9]+) jobs.*/\1/')
ran=$(cat "$out"/state/*.state | awk '{print $1}' | sort | wc -l)
unique=$(cat "$out"/state/*.state | awk '{print $1}' | sort -u | wc -l)
[ "$ran" = "$unique" ] || { echo "a job ran twice"; exit 1; }
[ "$unique" = "$all" ] || { echo "the machines ran $unique jobs, the schedule has $all"; exit 1; }
grep -q '^completed within its constraints' "$out/summary.txt" || { echo "not completed"; exit 1; }
echo "dry_run_intruder: every hostile message rejected and logged, none executed; $all jobs once each"
