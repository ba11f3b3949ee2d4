#!/usr/bin/env bash
# Rewrites the golden schedules of the example buildings (tests/regression/), after a
# change that is meant to change the schedules. Review `ccbuild diff` of old against new
# before committing them with the change.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/ccbuild ] || ./scripts/build.sh
for name in house apartment tower; do
  golden=tests/regression/$name.schedule.json
  rc=0
  ./build/ccbuild schedule "config/buildings/$name.yaml" --quiet --force -o "$golden" >/dev/null || rc=$?
  if [ "$rc" -gt 1 ]; then echo "refresh-goldens: $name failed ($rc)" >&2; exit 1; fi
  echo "refreshed $golden"
done
