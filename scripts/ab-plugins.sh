#!/usr/bin/env bash
# A/B timing of plugin builds side by side on this noisy machine:
#
#   scripts/ab-plugins.sh [options] NODE VARIANT VARIANT...
#
# NODE is a node that runs a pass of its own (a fused node shows `fused`: time its reader). A
# VARIANT is a space-separated list of PLUGIN=FILE.so (e.g. "cel_light=/tmp/light_a.so
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

# NODE's median wall ms in both modes, the copy pass and the frame in copy passes, from the
# bench's JSON report; a node that is fused into its reader has no time of its own.
summarize='
import json, sys
report, node = json.load(sys.stdin), sys.argv[1]
modes = report["modes"]
def median(mode):
    for entry in modes[mode]["nodes"]:
        if entry["id"] == node:
            return "fused" if entry["fused"] else "%.3f" % entry["wall_ms"]["median"]
    sys.exit("ab-plugins.sh: no node %r in the graph (nodes: %s)"
             % (node, ", ".join(e["id"] for e in modes[mode]["nodes"])))
print(median("every_node_runs"), median("cached_static_nodes"),
      "%.3f" % report["copy_pass_ms"], "%.2f" % report["copy_passes_per_frame"])
'

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
    json=$("$app" bench "$graph" --quality final --size 1280x720 --frames "$frames" \
      --pipeline-only --no-sweep -q --json)
    summary=$(python3 -c "$summarize" "$node" <<<"$json")
    read -r every cached copy copies <<<"$summary"
    printf '%-5s %-40s %10s %10s %8s %8s\n' "$round" "${variant:0:40}" "$every" "$cached" \
      "$copy" "$copies"
  done
done
