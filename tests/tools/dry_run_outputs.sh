#!/usr/bin/env bash
# The dry-run's outputs over a real run, in a network namespace of its own: a journal and
# a folder of machine records belong to one schedule (another schedule's are refused and
# left as they were); a log that cannot be written stops the run with exit 2 and leaves
# nothing behind; a log into /dev/null is fine; the fastest speed the machines accept
# completes (statuses then come at the longest period they accept).
# Usage: dry_run_outputs.sh CCBUILD   (needs root for unshare -n)
set -euo pipefail
if [ "$(id -u)" -eq 0 ]; then netns="unshare -n"; else netns="unshare -rn"; fi
ccbuild=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
mkdir "$out/tmp"
fail() { echo "dry_run_outputs: $*"; exit 1; }
run() {  # run NAME ARGS...: exit code in $code, stdout in $out/NAME.txt, stderr in $out/NAME.err
  local name=$1
  shift
  TMPDIR="$out/tmp" $netns sh -c 'ip link set lo up && ip link set lo multicast on &&
    ip route add 224.0.0.0/4 dev lo && exec "$@"' sh \
    timeout 120 "$ccbuild" dry-run "$@" > "$out/$name.txt" 2> "$out/$name.err" && code=0 || code=$?
}
expect() {  # expect NAME CODE TEXT
  [ "$code" = "$2" ] || { cat "$out/$1.txt" "$out/$1.err"; fail "$1: exit code $code, expected $2"; }
  grep -qF -- "$3" "$out/$1.txt" "$out/$1.err" || { cat "$out/$1.txt" "$out/$1.err"; fail "$1: '$3' not said"; }
  [ -z "$(ls -A "$out/tmp")" ] || fail "$1 left $(ls -A "$out/tmp") in its temporary folder"
  ! pgrep -f "ccbuild-sim .*$out" > /dev/null || fail "$1 left a ccbuild-sim running"
}

twin=tests/data/buildings/twin-cottages.yaml
cottage=tests/data/buildings/cottage.yaml
"$ccbuild" schedule "$twin" --quiet -o "$out/twin.json" > /dev/null
"$ccbuild" schedule "$cottage" --quiet -o "$out/cottage.json" > /dev/null

run first "$out/twin.json" --journal "$out/journal.sqlite" --state-dir "$out/state" \
  --log "$out/run.lcmlog"
expect first 0 "completed within its constraints"
sum=$(sha256sum "$out/journal.sqlite" "$out/state/"* | sha256sum)

# Another schedule's journal and machine records: refused, untouched.
run other "$out/cottage.json" --journal "$out/journal.sqlite"
expect other 2 "--journal: belongs to another schedule"
run others "$out/cottage.json" --state-dir "$out/state"
expect others 2 "--state-dir: holds the machines' records of another schedule"
[ "$(sha256sum "$out/journal.sqlite" "$out/state/"* | sha256sum)" = "$sum" ] ||
  fail "a refused run changed the journal or the machines' records"
# The same schedule, as a building, resumes on them: nothing left to do.
run again "$twin" --journal "$out/journal.sqlite" --state-dir "$out/state"
expect again 0 "completed within its constraints"

# A log that cannot be written: the run stops, exit 2, nothing left behind.
run full "$out/twin.json" --log /dev/full
expect full 2 "--log: writing the LCM log failed: No space left on device"
# Into /dev/null: written into, the device kept.
run null "$out/twin.json" --log /dev/null
expect null 0 "LCM log: /dev/null"
[ -c /dev/null ] || fail "/dev/null is no longer a character device"

# The fastest speed: statuses at the longest period a machine accepts (86400 s).
run fast "$out/twin.json" --speed 1e9
expect fast 0 "completed within its constraints"

echo "dry_run_outputs: journal and records kept to their schedule; log errors stop the run; /dev/null and --speed 1e9 fine"
