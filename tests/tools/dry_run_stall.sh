#!/usr/bin/env bash
# The site watchdog against a stalled rail axis: the twin cottages on two gantries at the
# default 10,000x on the site clock,
# gantry-1's rail axis stalled at 75 s (at x = 6 m, where the first layer's plan builds
# walls along y before heading back to x = 2.5 m) while gantry-2 carries on towards it. With the
# watchdog every machine is paused before the gap falls under the gantry width; without
# it (--no-watchdog) the gantries collide. Both measured from the simulated machines' own
# statuses in the LCM log (check_gaps.py), not from the watchdog.
# Usage: dry_run_stall.sh CCBUILD   (from the source tree; needs unshare -n or -rn)
set -euo pipefail
if [ "$(id -u)" -eq 0 ]; then netns="unshare -n"; else netns="unshare -rn"; fi
ccbuild=$1
here=$(dirname "$0")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$ccbuild" schedule tests/data/buildings/twin-cottages.yaml -o "$out/twin.json" --quiet > /dev/null
run() {  # run NAME EXTRA-ARGS...: the dry-run, which must exit 1 (stopped)
  local name=$1
  shift
  set +e
  $netns sh -c 'ip link set lo up && ip link set lo multicast on &&
    ip route add 224.0.0.0/4 dev lo && exec "$@"' sh \
    "$ccbuild" dry-run "$out/twin.json" --inject stall=gantry-1@75 --timeout 60 \
    --log "$out/$name.lcmlog" "$@" > "$out/$name.txt" 2> "$out/$name.err"
  local code=$?
  set -e
  grep -v '^floor ' "$out/$name.txt"
  [ "$code" = 1 ] || { echo "$name: exit code $code, expected 1"; cat "$out/$name.err"; exit 1; }
}
run guarded
grep -q '^STOPPED safely: site watchdog' "$out/guarded.txt" ||
  { echo "the watchdog did not stop the run"; exit 1; }
python3 "$here/check_gaps.py" "$out/guarded.lcmlog" --width 1.5 --expect-paused
run unguarded --no-watchdog
python3 "$here/check_gaps.py" "$out/unguarded.lcmlog" --width 1.5 --expect-collision
echo "dry_run_stall: paused in time with the watchdog, collided without it"
