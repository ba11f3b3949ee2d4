#!/usr/bin/env bash
# The dry-run as separate processes over udpm:// in a network namespace of its own (never
# on the shared network): `ccbuild dry-run` and one `ccbuild-sim` per gantry. Checks the
# exit code, that every job was executed, and, from the simulated machines' own records
# (not the orchestrator's), that each job ran exactly once.
# Usage: dry_run_netns.sh CCBUILD ARGS...   (needs root for unshare -n)
set -euo pipefail
# As root, a network namespace; otherwise a user namespace with one (needs unprivileged
# user namespaces).
if [ "$(id -u)" -eq 0 ]; then netns="unshare -n"; else netns="unshare -rn"; fi
ccbuild=$1
shift
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
$netns sh -c 'ip link set lo up && ip link set lo multicast on &&
  ip route add 224.0.0.0/4 dev lo && exec "$@"' sh \
  "$ccbuild" dry-run "$@" --state-dir "$out/state" --journal "$out/journal.sqlite" \
  --log "$out/conversation.lcmlog" \
  > "$out/summary.txt" 2> "$out/progress.txt" || { cat "$out/summary.txt" "$out/progress.txt"; exit 1; }
cat "$out/summary.txt"
line=$(grep -E '^[^ ]+: [0-9]+ of [0-9]+ jobs executed on [0-9]+ machine' "$out/summary.txt")
done_jobs=$(echo "$line" | sed -E 's/.*: ([0-9]+) of ([0-9]+) jobs.*/\1/')
all_jobs=$(echo "$line" | sed -E 's/.*: ([0-9]+) of ([0-9]+) jobs.*/\2/')
machines=$(echo "$line" | sed -E 's/.*executed on ([0-9]+) machine.*/\1/')
[ "$done_jobs" = "$all_jobs" ] || { echo "only $done_jobs of $all_jobs jobs executed"; exit 1; }
records=$(ls "$out"/state/*.state | wc -l)
[ "$records" = "$machines" ] || { echo "$records machine records for $machines machines"; exit 1; }
ran=$(cat "$out"/state/*.state | awk '{print $1}' | sort | wc -l)
unique=$(cat "$out"/state/*.state | awk '{print $1}' | sort -u | wc -l)
[ "$ran" = "$unique" ] || { echo "a job ran twice: $ran runs of $unique jobs"; exit 1; }
[ "$unique" = "$all_jobs" ] || { echo "the machines ran $unique of $all_jobs jobs"; exit 1; }
# The LCM log: lcm-logger's format (sync word 0xEDA1DA01 first), every job in it.
head -c 4 "$out/conversation.lcmlog" | od -An -tx1 | grep -q "ed a1 da 01" ||
  { echo "the LCM log does not start with lcm-logger's sync word"; exit 1; }
logged=$(grep -a -c "CCBUILD_JOB_" "$out/conversation.lcmlog" || true)
[ "$logged" -ge 1 ] || { echo "no job in the LCM log"; exit 1; }
echo "dry_run_netns: $all_jobs jobs on $machines machines, each run exactly once by the machines' own records"
