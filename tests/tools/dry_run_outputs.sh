#!/usr/bin/env bash
# The dry-run's outputs over a real run, in a network namespace of its own: a journal and
# a folder of machine records belong to one schedule (another schedule's are refused and
# left as they were); a log that cannot be written stops the run with exit 2 and leaves
# nothing behind; a log on a device is refused; the fastest speed the machines accept
# completes, on the site clock and on the machines' own (statuses then come at the longest
# period they accept).
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
  TMPDIR="$out/tmp" $netns sh -c 'ulimit -f "$1" && shift && ip link set lo up &&
    ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo && exec "$@"' sh \
    "${FILE_BLOCKS:-unlimited}" timeout 120 "$ccbuild" dry-run "$@" > "$out/$name.txt" \
    2> "$out/$name.err" && code=0 || code=$?
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

# A log on a device: refused before the run (outputs are regular files only).
run full "$out/twin.json" --log /dev/full
expect full 2 "--log: is a character device"
[ -c /dev/full ] || fail "/dev/full is no longer a character device"
# A log or a journal that cannot be written (a file-size limit, as a full disk): the run
# stops, exit 2, no log left behind.
FILE_BLOCKS=160  # KiB: room for the journal (about 30 KiB), not the log (250 KiB)
run limited "$out/twin.json" --log "$out/limited.lcmlog"
FILE_BLOCKS=unlimited
# Whichever grows past the limit first (the journal's write-ahead log or the LCM log)
# stops the run with its flag named: exit 2, never an internal error.
[ "$code" = 2 ] || { cat "$out/limited.txt" "$out/limited.err"; fail "limited: exit code $code, expected 2"; }
grep -qE -- "--log: writing the LCM log failed|--journal: cannot write the journal" "$out/limited.err" ||
  { cat "$out/limited.err"; fail "limited: neither the log nor the journal named"; }
[ ! -e "$out/limited.lcmlog" ] || fail "a log that could not be written was left behind"
ls "$out" | grep -q 'limited.lcmlog.tmp' && fail "the log's temporary file was left behind"

# The fastest speed: statuses at the longest period a machine accepts (86400 s).
run fast "$out/twin.json" --speed 1e9
expect fast 0 "completed within its constraints"
# The same on the machines' own clocks: the status period kept under 200 a real second
# (5e6 s at this speed) is clamped to the longest they accept, never refused.
run fast_own "$out/twin.json" --speed 1e9 --own-clock
expect fast_own 0 "completed within its constraints"

echo "dry_run_outputs: journal and records kept to their schedule; log errors stop the run; devices refused; --speed 1e9 fine, on the site clock and on their own"
