#!/usr/bin/env bash
# A/B timing of plugin builds side by side on this noisy machine:
#
#   scripts/ab-plugins.sh [options] NODE VARIANT VARIANT...
#
# NODE is a node that runs a pass of its own (a fused node is timed with its reader). A VARIANT
# is a space-separated list of PLUGIN=FILE.so (e.g. "cel_light=/tmp/light_a.so
# gbuffer=/tmp/gbuffer_a.so"), or "base" for the build as it is. For each round, each variant's
# plugins are copied over the build's (the build's own are restored afterwards, also on ^C) and
# `aquarelle bench` times the graph at quality final, 1280x720; one line per run: NODE's median
# ms with every node running and with static nodes cached, the copy pass of the same run, and
# the frame in copy passes. Variants alternate within each round, so a change of the machine's
# load reaches all of them alike; compare rounds, not single runs. Make the variants' .so files
# by building the plugin with the change and copying build/plugins/aquarelle_NAME.so aside.
#
# Options: --rounds N (default 3), --graph FILE (default graphs/underwater.json),
#          --frames N (default 7), --build DIR (default build).
set -euo pipefail
usage() { sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; }
rounds=3 graph=graphs/underwater.json frames=7 build=build
while [ $# -gt 0 ]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --rounds) rounds=$2; shift 2 ;;
    --graph) graph=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    -*) echo "ab-plugins.sh: unknown option $1 (see --help)" >&2; exit 1 ;;
    *) break ;;
  esac
done
if [ $# -lt 2 ]; then
  echo "ab-plugins.sh: give a node and at least one variant (see --help)" >&2
  exit 1
fi
node=$1
shift
app=$build/app/aquarelle
[ -x "$app" ] || { echo "ab-plugins.sh: $app not built; run scripts/build.sh" >&2; exit 2; }
for variant in "$@"; do
  [ "$variant" = base ] && continue
  for pair in $variant; do
    so=${pair#*=}
    [ -f "$so" ] || { echo "ab-plugins.sh: $so (in \"$variant\") does not exist" >&2; exit 1; }
    [ -f "$build/plugins/aquarelle_${pair%%=*}.so" ] ||
      { echo "ab-plugins.sh: no plugin ${pair%%=*} in $build/plugins" >&2; exit 1; }
  done
done

saved=$(mktemp -d)
cp "$build"/plugins/aquarelle_*.so "$saved"/
restore() { cp "$saved"/*.so "$build"/plugins/ && rm -rf "$saved"; }
trap restore EXIT

printf '%-5s %-40s %10s %10s %8s %8s\n' round variant "every ms" "cached ms" "copy ms" copies
for round in $(seq "$rounds"); do
  for variant in "$@"; do
    cp "$saved"/*.so "$build"/plugins/
    if [ "$variant" != base ]; then
      for pair in $variant; do cp "${pair#*=}" "$build/plugins/aquarelle_${pair%%=*}.so"; done
    fi
    # The table pads numbers inside brackets ("[ 3.1 .."): close them up so fields stay put.
    report=$("$app" bench "$graph" --quality final --size 1280x720 --frames "$frames" \
      --pipeline-only --no-sweep -q 2>&1 | sed 's/\[ */[/g')
    every=$(awk -v n="$node" '$1 == n {print $3}' <<<"$report")
    cached=$(awk -v n="$node" '$1 == n {print $8}' <<<"$report")
    copy=$(awk '/^copy pass/ {print $4}' <<<"$report")
    copies=$(awk '/^copy_passes_per_frame/ {print $3}' <<<"$report")
    printf '%-5s %-40s %10s %10s %8s %8s\n' "$round" "${variant:0:40}" "${every:-?}" \
      "${cached:-?}" "${copy:-?}" "${copies:-?}"
  done
done
