#!/usr/bin/env bash
# Regenerates the measured part of docs/performance.md (issue 9: the whole pipeline at 1280x720
# in copy passes per frame, the per-node breakdown, and each quality preset's error against the
# float reference render) with one command:
#
#   scripts/update-performance.sh [GRAPH] [bench options...]
#
# Same machinery as scripts/update-accuracy.sh, with only the pipeline's preset sweep.
set -euo pipefail
cd "$(dirname "$0")/.."
graph=graphs/underwater.json
if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then
  graph=$1
  shift
elif [ ! -f "$graph" ]; then
  graph=graphs/scene_light.json
fi
AQ_BENCH_DOC=docs/performance.md AQ_BENCH_OUT=docs/performance \
  AQ_BENCH_COMMAND=scripts/update-performance.sh \
  exec scripts/update-accuracy.sh "$graph" --size 1280x720 --frames 5 --pipeline-only "$@"
