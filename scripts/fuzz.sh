#!/usr/bin/env bash
# Fuzzes the graph reader and validator with libFuzzer for N seconds (default 60), then the
# mesh header checks (PLY, glTF, GLB, FBX) and image reading (PNG, EXR, TIFF, JPEG, HDR, BMP) for
# AQUARELLE_FUZZ_HEADER_SECONDS each (default 30), all under a memory limit:
#   scripts/fuzz.sh [SECONDS] [extra libFuzzer flags...]
# Builds tests/fuzz (a separate clang project) in build-fuzz, seeds a working corpus from
# tests/fuzz/corpus and graphs/*.json, and loads the node types of build/plugins when that
# exists (AQUARELLE_FUZZ_PLUGIN_DIR overrides). Installs clang and libclang-rt-14-dev if
# missing. A crash leaves its input as build-fuzz/crash-*: add it as a regression test in
# tests/core/bad_graph_test.cpp (graphs) or tests/bad_input/ (meshes, images) and to the
# corpus (tests/fuzz/corpus, tests/fuzz/mesh_corpus; image seeds are made here with oiiotool).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true

missing=()
for package in clang libclang-rt-14-dev; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "fuzz: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

build=build-fuzz
generator=()
if command -v ninja >/dev/null; then generator=(-G Ninja); fi
cmake -S tests/fuzz -B "$build" "${generator[@]}" -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j2

# The checked-in corpus stays small and reviewed; libFuzzer grows a scratch copy.
work="$build/corpus"
mkdir -p "$work"
cp -n tests/fuzz/corpus/* graphs/*.json "$work"/ 2>/dev/null || true

plugin_dir="${AQUARELLE_FUZZ_PLUGIN_DIR:-build/plugins}"
if [ -d "$plugin_dir" ]; then
  # Absolute: the fuzzer runs from inside the build folder.
  export AQUARELLE_PLUGIN_PATH="$(cd "$plugin_dir" && pwd)"
else
  echo "fuzz: no $plugin_dir (build first for the plugins' node types); fake types only"
  unset AQUARELLE_PLUGIN_PATH
fi

# Plugins are built without ASan; their static constructors allocate nothing the fuzzer
# checks, but leak detection at exit would blame dlopen's bookkeeping: leaks stay checked
# per input (-detect_leaks=1), not at exit.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
header_seconds="${AQUARELLE_FUZZ_HEADER_SECONDS:-30}"
mesh_work="$build/mesh_corpus"
mkdir -p "$mesh_work"
cp -n tests/fuzz/mesh_corpus/* "$mesh_work"/ 2>/dev/null || true
# Image seeds: one tiny file per format, behind the byte that picks its extension.
image_work="$build/image_corpus"
mkdir -p "$image_work"
if command -v oiiotool >/dev/null; then
  index=0
  for ext in png exr tif jpg hdr bmp; do
    seed="$image_work/seed_$ext"
    if [ ! -f "$seed" ]; then
      oiiotool --pattern checker:width=2:height=2 4x3 3 -o "$build/seed.$ext" 2>/dev/null &&
        { printf "\\$(printf '%03o' "$index")"; cat "$build/seed.$ext"; } >"$seed"
    fi
    index=$((index + 1))
  done
fi

cd "$build"
status=0
./graph_reader_fuzzer -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -max_len=65536 -print_final_stats=1 "$@" corpus || status=$?
# Hostile headers must be refused before they allocate: 1 GB is far above the 256 MB memory
# budget the fuzzers read with, and far below what a forged size would reserve.
./mesh_header_fuzzer -max_total_time="$header_seconds" -timeout=10 -rss_limit_mb=1024 \
  -max_len=65536 -print_final_stats=1 "$@" mesh_corpus || status=$?
# OpenImageIO keeps error strings it never frees (not ours to fix): no leak checks for images.
# Those strings and ASan's quarantine grow the process slowly over ~10^5 inputs (one hour-long
# run passed 1 GB with 56 MB live), so the limit that matters is on a single allocation:
# any one allocation of 1 GB fails, the whole process may reach 3 GB.
ASAN_OPTIONS="detect_leaks=0:abort_on_error=1:quarantine_size_mb=64" \
  AQUARELLE_MEMORY_BUDGET_MB=256 \
  ./image_header_fuzzer -detect_leaks=0 -max_total_time="$header_seconds" -timeout=10 \
  -rss_limit_mb=3072 -malloc_limit_mb=1024 -max_len=16384 -print_final_stats=1 "$@" \
  image_corpus || image_status=$?
# An out-of-memory (exit 71) fails like a crash: a header let a declared size through. (The
# last one, a PNG text chunk declaring 1.9 GB, is refused by check_png_chunks since 2026-12-02.)
if [ "${image_status:-0}" -ne 0 ]; then
  status="$image_status"
fi
exit "$status"
