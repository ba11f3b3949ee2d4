#!/usr/bin/env bash
# Rewrites the golden schedules of the example buildings (tests/regression/), after a
# change that is meant to change the schedules. Review `ccbuild diff` of old against new
# before committing them with the change. The house's golden keeps its timed paths (tests
# read them); the apartment's and the tower's keep their digests (--path-digests), which
# `ccbuild diff` compares exactly, at a third of the size.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/ccbuild ] || ./scripts/build.sh
for name in house apartment tower; do
  golden=tests/regression/$name.schedule.json
  digests=()
  [ "$name" = house ] || digests=(--path-digests)
  rc=0
  ./build/ccbuild schedule "config/buildings/$name.yaml" --quiet --force "${digests[@]}" \
    -o "$golden" >/dev/null || rc=$?
  if [ "$rc" -gt 1 ]; then echo "refresh-goldens: $name failed ($rc)" >&2; exit 1; fi
  echo "refreshed $golden"
done
