#!/usr/bin/env bash
# Quick start, step 2: install what is missing, build, and run the test suite through CTest:
# every test but those labelled `long` (the apartment's 200-variant study, about 9 minutes:
# `cd build && ctest -L long`).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
cd build
ctest --output-on-failure -j2 --timeout 300 -LE long
