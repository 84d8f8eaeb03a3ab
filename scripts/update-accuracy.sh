#!/usr/bin/env bash
# Regenerates the measured part of docs/accuracy.md (tables between the bench markers), the plot
# docs/accuracy/bench.png, and the raw docs/accuracy/bench.{csv,json} with one command:
#
#   scripts/update-accuracy.sh [GRAPH] [bench options...]
#   scripts/update-accuracy.sh graphs/underwater.json --size 1280x720 --frames 10
#
# GRAPH defaults to graphs/underwater.json, or graphs/scene_light.json while the full pipeline is
# not in the tree. AQ_BUILD_DIR chooses the build folder (default: build); it is configured
# (tests on, so the CPU references are linked) and the app and plugins are built first.
# AQ_BENCH_DOC and AQ_BENCH_OUT choose the page and the data folder (scripts/update-performance.sh
# uses them for docs/performance.md).
set -euo pipefail
cd "$(dirname "$0")/.."

build=${AQ_BUILD_DIR:-build}
graph=graphs/underwater.json
if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then
  graph=$1
  shift
elif [ ! -f "$graph" ]; then
  graph=graphs/scene_light.json
fi

if [ ! -f "$build/CMakeCache.txt" ]; then
  generator=()
  if command -v ninja >/dev/null; then generator=(-G Ninja); fi
  cmake -S . -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DAQUARELLE_BUILD_TESTS=ON
fi
# Plugin targets are named after the first argument of aquarelle_add_plugin in each folder.
mapfile -t plugins < <(sed -n 's/^ *aquarelle_add_plugin(\([A-Za-z0-9_]*\).*/aquarelle_plugin_\1/p' \
  plugins/*/CMakeLists.txt | sort -u)
cmake --build "$build" --target aquarelle -j"$(nproc)"
# A plugin that does not build (work in progress) only matters if the graph uses it: bench then
# names the missing node type.
if ! cmake --build "$build" --target "${plugins[@]}" -j"$(nproc)"; then
  echo "update-accuracy: warning: some plugins did not build; measuring with those that did" >&2
fi

doc=${AQ_BENCH_DOC:-docs/accuracy.md}
out=${AQ_BENCH_OUT:-docs/accuracy}
command_name=${AQ_BENCH_COMMAND:-scripts/update-accuracy.sh}
mkdir -p "$out"
"$build/app/aquarelle" bench "$graph" --csv "$out/bench.csv" --plot "$out/bench.png" --json \
  "$@" > "$out/bench.json.tmp"
mv "$out/bench.json.tmp" "$out/bench.json"

# The tables go between the markers of docs/accuracy.md; the prose around them stays.
/usr/bin/python3 -B - "$out/bench.json" "$doc" "$command_name $graph $*" <<'PYTHON'
import json, sys
sys.path.insert(0, "scripts")  # run from the repository root (cd above)
from doc_block import replace_block

report = json.load(open(sys.argv[1]))
doc_path, command = sys.argv[2], sys.argv[3].strip()


def ms(value):
    return "-" if value is None else f"{value:.3f}"


def err(value):
    return "-" if value is None else ("0" if value == 0 else f"{value:.3g}")


lines = []
w, h = report["size"]
lines.append(f"Measured by `{command}`: graph `{report['graph']}` at "
             f"{w}x{h}, quality {report.get('quality', '?')}, {report['precision']} precision, "
             f"{report['frames']} timed frames after "
             f"{report['warmup']} warm-up; {report['gl']}.")
lines.append("")
copy = report["copy_pass"]["wall_ms"]
lines.append(f"- copy pass (the yardstick): **{ms(copy['median'])} ms** median "
             f"(min {ms(copy['min'])}, max {ms(copy['max'])})")
modes = report["modes"]
lines.append(f"- frame, every node running: {ms(modes['every_node_runs']['frame_ms']['median'])} ms"
             f" = {report['copy_passes_per_frame_every_node_runs']:.1f} copy passes")
lines.append(f"- frame, static nodes cached: {ms(modes['cached_static_nodes']['frame_ms']['median'])}"
             f" ms = **{report['copy_passes_per_frame']:.1f} copy passes per frame**")
lines.append("")
lines.append("| node | type | ms median [min .. max], every node runs | copy passes | "
             "ms median, static cached | runs (cached) | GL timestamp ms |")
lines.append("| --- | --- | --- | --- | --- | --- | --- |")
cached = {n["id"]: n for n in modes["cached_static_nodes"]["nodes"]}
for n in modes["every_node_runs"]["nodes"]:
    c = cached.get(n["id"])
    g = n["wall_ms"]
    if n.get("fused"):
        lines.append(f"| {n['id']} | {n['type']} | fused into its reader's pass | - | - | - | - |")
        continue
    lines.append(f"| {n['id']} | {n['type']} | {ms(g['median'])} [{ms(g['min'])} .. {ms(g['max'])}] "
                 f"| {n['copy_passes']:.1f} | {ms(c['wall_ms']['median']) if c else '-'} "
                 f"| {c['runs'] if c else '-'} of {report['frames']} | {ms(n['gpu_ms']['median'])} |")
lines.append("")
if not report["cpu_references"]:
    lines.append("No CPU references in this build (configure with -DAQUARELLE_BUILD_REFERENCES=ON).")
    lines.append("")
for sweep in report["sweeps"]:
    lines.append(f"#### {sweep['series']} ({sweep['kind'].replace('_', ' ')})")
    lines.append("")
    lines.append(f"Reference: {sweep['reference']}." + (f" {sweep['note']}." if sweep["note"] else ""))
    lines.append("")
    unit = "frame ms" if sweep["time_measure"] == "frame wall" else "node ms"
    lines.append(f"| setting | precision | {unit} | max abs | mean abs | PSNR dB | Pareto |")
    lines.append("| --- | --- | --- | --- | --- | --- | --- |")
    for p in sweep["points"]:
        psnr = "inf" if p["psnr"] is None and p["mean_abs"] == 0 else (
            "-" if p["psnr"] is None else f"{p['psnr']:.1f}")
        setting = p["setting"] + (" (reference)" if p["is_reference"] else "")
        lines.append(f"| {setting} | {p['precision']} | {ms(p['time_ms']['median'])} | "
                     f"{err(p['max_abs'])} | {err(p['mean_abs'])} | {psnr} | "
                     f"{'yes' if p['pareto'] else ''} |")
    lines.append("")

block = "\n".join(lines)
replace_block(doc_path, "bench", block)
print(f"updated {doc_path} and {sys.argv[1].rsplit('/', 1)[0]}/bench.{{png,csv,json}}")
PYTHON
