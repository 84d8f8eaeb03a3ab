#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and renders the flagship graph
# headless to underwater.png (pass another output path as the first argument), at `final` (full
# size, sharp outlines: the graph's default too; `--quality final` keeps it so whatever the graph
# file says).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-underwater.png}"
scripts/install-deps.sh
scripts/build.sh
./build/app/aquarelle render graphs/underwater.json -o "$out" --quality final --stats
echo "rendered $out"
