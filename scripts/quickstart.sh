#!/usr/bin/env bash
# Quick start, step 1: install what is missing, build, and run the main job (the whole
# schedule) on the bundled example building and its dry-run against simulated machines
# over LCM, ending with where its report is.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
example=config/buildings/house.yaml
echo
echo "== ccbuild validate $example"
./build/ccbuild validate "$example"
echo
echo "== ccbuild layers $example"
./build/ccbuild layers "$example"
echo
echo "== ccbuild plan-layer $example --floor 0 --layer 12 --objective time --svg build/house-floor0-layer12.svg"
./build/ccbuild plan-layer "$example" --floor 0 --layer 12 --objective time --force \
  --svg build/house-floor0-layer12.svg
echo
echo "== ccbuild schedule $example -o build/house.schedule.json --report build/house.report.html"
./build/ccbuild schedule "$example" --force -o build/house.schedule.json \
  --report build/house.report.html
echo
echo "== ccbuild dry-run build/house.schedule.json (simulated machines over LCM, in a network namespace of its own)"
./scripts/in-netns.sh ./build/ccbuild dry-run build/house.schedule.json
echo
echo "== the report: $(pwd)/build/house.report.html"
echo "   one self-contained page (open it in a browser): the verdict and totals, the Gantt chart,"
echo "   the work by day, intervals, heat maps, strength, the tool paths and a 3-D playback;"
echo "   docs/images/report-*.png show each section (scripts/report-screenshots.sh redraws them)"
