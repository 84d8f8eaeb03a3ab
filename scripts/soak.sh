#!/usr/bin/env bash
# Soak: renders 1000 frames (or FRAMES) of graphs/underwater.json (scene_light.json until it
# exists; AQ_SOAK_GRAPH picks another) at 64x36 with one evaluator and checks that the
# texture pool, the heap in use and process memory (RSS) stay flat after the warm-up:
#   scripts/soak.sh [FRAMES] [BUILD_DIR]
# The check is tests/app/soak_test.cpp; ctest runs it short (150 frames), this runs it long.
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-1000}"
build="${2:-build}"
if [ ! -d "$build" ]; then
  cmake -S . -B "$build" -G Ninja >/dev/null
fi
cmake --build "$build" -j"${AQ_JOBS:-2}" --target app_soak_test
AQ_SOAK_FRAMES="$frames" "$build/tests/app_soak_test" --gtest_brief=0
