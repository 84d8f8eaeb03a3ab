#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and renders the flagship graph
# headless to underwater.png (pass another output path as the first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-underwater.png}"
scripts/install-deps.sh
scripts/build.sh
./build/app/aquarelle render graphs/underwater.json -o "$out" --stats
echo "rendered $out"
