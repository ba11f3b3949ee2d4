#!/usr/bin/env bash
# Regenerates the report's screenshots in docs/images/ (1400 px wide, as a laptop shows
# it): the ten-storey tower on the bundled weekday site, one picture per section, each
# taken by headless Chromium of the report showing that section alone (report.html?only=days).
# Usage: scripts/report-screenshots.sh   (builds ccbuild first when it is not built)
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/ccbuild ] || ./scripts/build.sh
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  echo "report-screenshots: Chromium is not installed (scripts/install-deps.sh installs it)" >&2
  exit 2
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
./build/ccbuild schedule config/buildings/tower.yaml --site config/sites/weekdays-berlin-2027.yaml \
  --quiet --jobs 2 -o "$work/tower.json" --report "$work/tower.html" > /dev/null
mkdir -p docs/images
for section in summary gantt days intervals heatmap strength toolpaths playback; do
  out=docs/images/report-$section.png
  HOME=$work "$browser" --headless --no-sandbox --disable-gpu --use-angle=swiftshader \
    --enable-unsafe-swiftshader --hide-scrollbars --disable-background-networking \
    --disable-component-update --disable-sync --no-first-run --window-size=1400,900 \
    --virtual-time-budget=20000 --user-data-dir="$work/profile" --screenshot="$out" \
    "file://$work/tower.html?only=$section" > /dev/null 2>&1
  [ -s "$out" ] || { echo "report-screenshots: no screenshot of $section" >&2; exit 1; }
  echo "wrote $out"
done
