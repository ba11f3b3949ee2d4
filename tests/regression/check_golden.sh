#!/usr/bin/env bash
# Schedules BUILDING again and compares it with its golden schedule, with `ccbuild diff`
# (which names what changed) and byte for byte (the same inputs and seed give the same
# schedule). A golden that keeps its paths' digests (--path-digests) is compared with a
# schedule written so. Run from the source tree by CTest:
#   check_golden.sh CCBUILD BUILDING GOLDEN
# When a change of the schedules is intended: scripts/refresh-goldens.sh, and commit the
# new golden files with the change.
set -euo pipefail
ccbuild=$1 building=$2 golden=$3
out=$(mktemp --suffix=.schedule.json)
trap 'rm -f "$out"' EXIT
digests=()
grep -q '"waypoints_digest"' "$golden" && digests=(--path-digests)
rc=0
"$ccbuild" schedule "$building" --quiet --no-compare --force "${digests[@]}" -o "$out" >/dev/null || rc=$?
if [ "$rc" -gt 1 ]; then
  echo "check_golden: ccbuild schedule $building failed with exit code $rc" >&2
  exit 1
fi
if ! "$ccbuild" diff "$golden" "$out" || ! cmp -s "$golden" "$out"; then
  echo "check_golden: $building no longer schedules as $golden says." >&2
  echo "If the change is intended: scripts/refresh-goldens.sh, then commit the goldens." >&2
  exit 1
fi
