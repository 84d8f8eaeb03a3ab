#!/usr/bin/env bash
# Regenerates the golden frames of graphs/underwater.json that tests/app/golden_test.cpp
# compares against (frames 1 and 24 at 160x90, float precision, EXR). Run it only when a
# change to the picture is intended, and say why in the commit message.
set -euo pipefail
cd "$(dirname "$0")/.."
app=build/app/aquarelle
[ -x "$app" ] || scripts/build.sh
for frame in 1 24; do
  "$app" render graphs/underwater.json --gl egl --frames "$frame" --size 160x90 \
    --precision float --quality final --float -q -o "tests/golden/underwater_${frame}.exr"
done
echo "updated tests/golden/underwater_{1,24}.exr: commit them with the reason for the change"
