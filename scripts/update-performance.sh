#!/usr/bin/env bash
# Regenerates the measured parts of docs/performance.md with one command:
#
#   scripts/update-performance.sh [GRAPH] [bench options...]
#
# 1. Between the `bench` markers: the whole pipeline at quality final, 1280x720, in copy passes
#    per frame, the per-node breakdown, and each quality preset's error against the float
#    reference render (same machinery as scripts/update-accuracy.sh, only the preset sweep).
# 2. Between the `levers` markers: each optimisation lever switched off on its own (one bench
#    run each, `--set`), and all of them off, against all on: copy passes per frame, the cost of
#    the node it acts on, and the pipeline's PSNR against the reference render. Ratios are to
#    the copy pass of the same run; milliseconds of different runs do not compare.
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
  scripts/update-accuracy.sh "$graph" --size 1280x720 --frames 5 --pipeline-only \
  --quality final "$@"

[ "$graph" = graphs/underwater.json ] || exit 0
build=${AQ_BUILD_DIR:-build}
out=docs/performance/levers
mkdir -p "$out"
# name | node it acts on | the run's settings (bench --set ...) | on: the run has the lever
# (off by default), off: the run lacks it (on by default). The first run is the graph as it is.
levers=(
  "the graph's defaults|-||-"
  "blur: separable direct kernel|blur|blur.direct_kernel=full|off"
  "pigment: canvas densities kept while the view stays|canvas|canvas.cache=false|off"
  "pigment as canvas + pointwise apply (fused) instead of one node|pigment|one-node-pigment|off"
  "gbuffer: still meshes from a cached layer|gbuf|gbuf.cache_static=false|off"
  "wobble: the paper's precomputed gradient|wobble|-wobble.gradient|off"
  "gbuffer: normal, albedo and id in one packed surface texel for the light|light|-light.surface +light.normal=gbuf.normal +light.albedo=gbuf.albedo +light.id=gbuf.id|off"
  "caustics: grid from the footprint (off by default)|caustics|caustics.auto_grid=true|on"
  "caustics: coverage in closed form over 3 x 3 texels|caustics|caustics.window=2|off"
  "damage tracking: nodes with kept outputs redraw only what changed|light|env:AQUARELLE_DAMAGE=0|off"
  "the default levers off|-|blur.direct_kernel=full one-node-pigment pigment.cache_canvas=false gbuf.cache_static=false -wobble.gradient -light.surface +light.normal=gbuf.normal +light.albedo=gbuf.albedo +light.id=gbuf.id env:AQUARELLE_FORMATS_BY_NEED=0 env:AQUARELLE_EPILOGUE_FUSION=0 env:AQUARELLE_DAMAGE=0 env:AQUARELLE_MORPH_BLOCKED=0 env:AQUARELLE_MORPH_BLOCKS=0 env:AQUARELLE_DEFER_AXIS=0 env:AQUARELLE_BLUR_BLOCKS=0|off"
  "formats by need, all of it: 8-bit edge source and paper, 8-bit HDR light|edge|env:AQUARELLE_FORMATS_BY_NEED=0|off"
  "formats by need: light, morphology and pigment as 8-bit HDR|dilate|env:AQUARELLE_HDR8=0|off"
  "morphology: 2 x 2 blocks of packed 8-bit row extremes (square windows)|dilate|env:AQUARELLE_MORPH_BLOCKED=0|off"
  "morphology: the chain keeps its images in 2 x 2 blocks between its nodes|dilate|env:AQUARELLE_MORPH_BLOCKS=0|off"
  "morphology: a node's last 1D pass run by its reader with its own first (neighbourhood fusion; the three nodes together in the README)|dilate|env:AQUARELLE_DEFER_AXIS=0|off"
  "blur: the separable kernel's rows in 2 x 2 blocks of packed 8-bit pixels|tint|env:AQUARELLE_BLUR_BLOCKS=0|off"
  "fusion: vignette and tint in the blur's last draw, edge and pigment_apply in the wobble's (epilogue)|-|env:AQUARELLE_EPILOGUE_FUSION=0|off"
)
# AQ_LEVERS_FROM_JSON=1: only rewrite the table from the runs already in docs/performance/levers.
for i in "${!levers[@]}"; do
  [ -z "${AQ_LEVERS_FROM_JSON:-}" ] || break
  IFS='|' read -r name node settings sense <<< "${levers[$i]}"
  sets=()
  envs=()
  run_graph=$graph
  step=0
  for s in $settings; do
    if [ "$s" = one-node-pigment ]; then
      # The flagship's pigment_canvas + pigment_apply as the one `pigment` node they split from
      # (same parameters); later --set of pigment.* apply to that node.
      copy=$(dirname "$graph")/.levers-$i-pigment.json
      /usr/bin/python3 - "$run_graph" "$copy" <<'PYTHON'
import json, sys
graph = json.load(open(sys.argv[1]))
nodes = graph["nodes"]
canvas = nodes.pop("canvas")
apply = nodes["pigment"]
params = dict(canvas.get("params", {}))
params.pop("cache", None)
params.update(apply.get("params", {}))
inputs = {k: v for k, v in canvas.get("inputs", {}).items()}
inputs["image"] = apply["inputs"]["image"]
nodes["pigment"] = {"type": "pigment", "params": params, "inputs": inputs}
json.dump(graph, open(sys.argv[2], "w"), indent=2)
PYTHON
      [ "$run_graph" = "$graph" ] || rm -f "$run_graph"
      run_graph=$copy
    elif [ "${s#env:}" != "$s" ]; then
      envs+=("${s#env:}")  # env:NAME=VALUE: a host switch the bench has no --set for
    elif [ "${s#+}" != "$s" ]; then
      # +NODE.INPUT=SOURCE.PORT: the graph with that link added (a copy, as below).
      step=$((step + 1))  # each edit writes a copy of its own and removes the one before
      copy=$(dirname "$graph")/.levers-$i-$step.json
      /usr/bin/python3 - "$run_graph" "$copy" "${s#+}" <<'PYTHON'
import json, sys
graph = json.load(open(sys.argv[1]))
target, source = sys.argv[3].split("=")
node, port = target.split(".")
graph["nodes"][node].setdefault("inputs", {})[port] = source
json.dump(graph, open(sys.argv[2], "w"), indent=2)
PYTHON
      [ "$run_graph" = "$graph" ] || rm -f "$run_graph"
      run_graph=$copy
    elif [ "${s#-}" != "$s" ]; then
      # -NODE.INPUT: the graph without that link (a copy beside the original, so that paths
      # relative to the graph's folder still resolve).
      step=$((step + 1))
      copy=$(dirname "$graph")/.levers-$i-$step.json
      /usr/bin/python3 - "$run_graph" "$copy" "${s#-}" <<'PYTHON'
import json, sys
graph = json.load(open(sys.argv[1]))
node, port = sys.argv[3].split(".")
del graph["nodes"][node]["inputs"][port]
json.dump(graph, open(sys.argv[2], "w"), indent=2)
PYTHON
      [ "$run_graph" = "$graph" ] || rm -f "$run_graph"
      run_graph=$copy
    else
      sets+=(--set "$s")
    fi
  done
  echo "update-performance: lever run $((i + 1))/${#levers[@]}: $name" >&2
  env "${envs[@]}" "$build/app/aquarelle" bench "$run_graph" --size 1280x720 --frames 3 --warmup 1 \
    --quality final --pipeline-only --json -q "${sets[@]}" > "$out/$i.json"
  [ "$run_graph" = "$graph" ] || rm -f "$run_graph"
done

/usr/bin/python3 -B - "$out" docs/performance.md "${levers[@]}" <<'PYTHON'
import json, sys
sys.path.insert(0, "scripts")  # run from the repository root (cd above)
from doc_block import replace_block

out, doc_path, levers = sys.argv[1], sys.argv[2], sys.argv[3:]


def final_psnr(report):
    for sweep in report["sweeps"]:
        for p in sweep["points"]:
            if p["setting"] == "quality=final" and p["precision"] == report["precision"]:
                return p["psnr"]
    return None


def node_cost(report, node):
    """The node's cost in copy passes; a node fused into another's pass has none of its own:
    then the cost of the pass that runs it (its reader's, named "pass of <reader>")."""
    nodes = report["modes"]["cached_static_nodes"]["nodes"]
    for i, n in enumerate(nodes):
        if n["id"] != node:
            continue
        if not n.get("fused"):
            return n["wall_ms"]["median"] / report["copy_pass_ms"], node
        for owner in nodes[i + 1:]:
            if not owner.get("fused"):
                return owner["wall_ms"]["median"] / report["copy_pass_ms"], "pass of " + owner["id"]
    return None, node


runs = [json.load(open(f"{out}/{i}.json")) for i in range(len(levers))]
on = runs[0]
lines = ["Measured by `scripts/update-performance.sh`: `graphs/underwater.json` at quality final, "
         f"1280x720, {on['precision']} precision, {on['frames']} timed frames per run, static "
         "nodes cached; one `aquarelle bench --pipeline-only` run per row (PSNR against the "
         "reference render of the preset table).", "",
         "| lever | measured with | copy passes per frame, without → with | its node, "
         "without → with | PSNR dB, without → with |", "| --- | --- | --- | --- | --- |"]
fmt = lambda v, f="{:.1f}": "-" if v is None else f.format(v)
for i, spec in enumerate(levers[1:], start=1):
    name, node, settings, sense = spec.split("|")
    without, with_ = (runs[i], on) if sense == "off" else (on, runs[i])
    if node == "-":
        node_text = "-"
    else:
        (cost_without, name_without), (cost_with, name_with) = (node_cost(without, node),
                                                                node_cost(with_, node))
        node_text = (f"{name_without} {fmt(cost_without)} → {fmt(cost_with)}"
                     if name_without == name_with else
                     f"{name_without} {fmt(cost_without)} → {name_with} {fmt(cost_with)}")
    lines.append(f"| {name} | `{settings}` | {without['copy_passes_per_frame']:.1f} → "
                 f"{with_['copy_passes_per_frame']:.1f} | {node_text} | "
                 f"{fmt(final_psnr(without))} → {fmt(final_psnr(with_))} |")
lines.append("")
lines.append("Per run (copy pass ms, copy passes per frame static cached / every node running): " +
             "; ".join(f"{spec.split('|')[0]}: {r['copy_pass_ms']:.2f} ms, "
                       f"{r['copy_passes_per_frame']:.1f} / "
                       f"{r['copy_passes_per_frame_every_node_runs']:.1f}"
                       for spec, r in zip(levers, runs)) + ".")
block = "\n".join(lines)
replace_block(doc_path, "levers", block)
print(f"updated the lever table of {doc_path}")
PYTHON
