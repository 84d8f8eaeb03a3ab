#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and renders the flagship graph
# headless to underwater.png (pass another output path as the first argument). One still frame,
# so it renders at `final` (full size, sharp outlines) whatever the graph's default quality,
# which stays the faster half-size `preview` for animations until `final` is fast enough.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-underwater.png}"
scripts/install-deps.sh
scripts/build.sh
./build/app/aquarelle render graphs/underwater.json -o "$out" --quality final --stats
echo "rendered $out"
