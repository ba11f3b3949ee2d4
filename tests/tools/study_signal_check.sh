#!/usr/bin/env bash
# Issue 49: SIGTERM, SIGINT or SIGHUP to `ccbuild study` stops its variants: each variant's
# `ccbuild schedule` runs in a process group of its own, which the study kills and waits
# for; nothing is recorded for them (no result.json); the study exits 128 + the signal.
# And a study killed with SIGKILL leaves its variant's schedule running, holding the
# variant's lock: the same study run again beside it says so and does not run that variant
# a second time.
# Usage: study_signal_check.sh CCBUILD   (from the source tree)
set -euo pipefail
ccbuild=$(realpath "$1")
root=$(pwd)
work=$(mktemp -d /tmp/ccbuild-study-signal.XXXXXX)
orphans=""
cleanup() {
  for g in $orphans; do kill -KILL -- -"$g" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "study_signal_check: $*"; exit 1; }

# Two variants of the apartment (a few seconds each), run two at once.
cat > "$work/s.yaml" <<EOF
name: signals
base:
  building: $root/config/buildings/apartment.yaml
  machine: $root/config/machines/cc-gantry.yaml
  material: $root/config/materials/standard-mix.yaml
axes:
  objective: [fewest-nozzles, shortest]
EOF

# The pid of the `ccbuild schedule` of variant $2 of results folder $1, once it runs.
schedule_pid() {
  local pid
  for _ in $(seq 1 600); do
    pid=$(pgrep -f -- "$1/variants/$2/schedule.json" | head -1 || true)
    [ -n "$pid" ] && { echo "$pid"; return 0; }
    sleep 0.05
  done
  return 1
}

for sig in TERM INT HUP; do
  out="$work/$sig"
  "$ccbuild" study "$work/s.yaml" -o "$out" --jobs 2 > "$work/$sig.txt" 2>&1 &
  study=$!
  p1=$(schedule_pid "$out" v0001) && p2=$(schedule_pid "$out" v0002) ||
    { cat "$work/$sig.txt"; fail "the variants never ran"; }
  g1=$(ps -o pgid= -p "$p1" | tr -d ' ') g2=$(ps -o pgid= -p "$p2" | tr -d ' ')
  [ "$g1" = "$p1" ] && [ "$g2" = "$p2" ] || fail "a variant is not in a process group of its own"
  [ "$g1" != "$(ps -o pgid= -p "$study" | tr -d ' ')" ] || fail "a variant is in the study's group"
  kill -"$sig" "$study"
  rc=0
  wait "$study" || rc=$?
  expected=$((128 + $(kill -l "$sig")))
  [ "$rc" -eq "$expected" ] || { cat "$work/$sig.txt"; fail "SIG$sig: exit $rc, expected $expected"; }
  for g in $g1 $g2; do
    if pgrep -g "$g" >/dev/null; then orphans="$orphans $g"; fail "SIG$sig: process group $g runs on"; fi
  done
  for v in v0001 v0002; do
    [ ! -e "$out/variants/$v/result.json" ] || fail "SIG$sig: $v stopped but recorded: $(cat "$out/variants/$v/result.json")"
  done
  grep -q "^study: stopped by signal $(kill -l "$sig")" "$work/$sig.txt" || { cat "$work/$sig.txt"; fail "SIG$sig: not said"; }
done
echo "study_signal_check: SIGTERM, SIGINT, SIGHUP: exit 143, 130, 129; the variants' groups gone; nothing recorded"

# A study killed outright (SIGKILL: no handler runs) while v0001 schedules: its schedule runs on,
# holding v0001's lock. The study run again beside it leaves v0001 to it, and runs v0002.
out="$work/lock"
"$ccbuild" study "$work/s.yaml" -o "$out" --jobs 1 > "$work/first.txt" 2>&1 &
study=$!
p1=$(schedule_pid "$out" v0001) || { cat "$work/first.txt"; fail "v0001 never ran"; }
orphans="$p1"
kill -KILL "$study"
wait "$study" 2>/dev/null || true
kill -0 "$p1" 2>/dev/null || fail "v0001's schedule ended with its study; nothing to test"
rc=0
"$ccbuild" study "$work/s.yaml" -o "$out" --jobs 2 > "$work/second.txt" 2>&1 || rc=$?
cat "$work/second.txt"
grep -q "^study: v0001 not run here: another process runs it now (it holds $out/variants/v0001/lock)" "$work/second.txt" ||
  fail "the resumed study did not leave the locked v0001 alone"
[ "$(grep -c '^\$ ' "$out/variants/v0001/log.txt")" -eq 1 ] || fail "v0001 was started twice: $(cat "$out/variants/v0001/log.txt")"
[ -e "$out/variants/v0002/result.json" ] || fail "v0002 was not run"
[ "$rc" -eq 1 ] || fail "the resumed study exited $rc; expected 1 (v0001 has no result yet)"
echo "study_signal_check: a variant still running after its study was killed is not run twice"
