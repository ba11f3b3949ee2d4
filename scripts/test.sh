#!/usr/bin/env bash
# Quick start, step 2: install what is missing, build, and run every test through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
cd build
ctest --output-on-failure -j2 --timeout 300
