#!/usr/bin/env bash
# Installs what is missing (apt), configures and builds ccbuild in build/ (Release, -j2).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
