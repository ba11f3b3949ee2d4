#!/usr/bin/env bash
# One dry-run of a schedule in a network namespace of its own, on the site clock, printing
# the summary lines a benchmark quotes (real time, messages a second, site clock ticks and
# repeats, gantry gaps and the watchdog's margin). For farm-bench (bench/README.md, "One
# site clock"):
#   farm-bench -n 3 -- bench/dry_run_site.sh tower.json
#   farm-bench -n 3 -- bench/dry_run_site.sh tower.json --inject drop=0.1,duplicate=0.1,reorder=0.1
# Usage: dry_run_site.sh SCHEDULE.json [DRY-RUN FLAGS...]   (from the repository's root)
set -euo pipefail
schedule=$1
shift
log=$(mktemp --suffix=.lcmlog)
trap 'rm -f "$log"' EXIT
if [ "$(id -u)" -eq 0 ]; then netns="unshare -n"; else netns="unshare -rn"; fi
$netns sh -c 'ip link set lo up && ip link set lo multicast on &&
  ip route add 224.0.0.0/4 dev lo && exec "$@"' sh \
  build/ccbuild dry-run "$schedule" --log "$log" --force "$@" 2>/dev/null |
  grep -E "jobs executed|gantry gaps|site clock|LCM log|completed"
