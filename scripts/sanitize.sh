#!/usr/bin/env bash
# Builds Aquarelle with AddressSanitizer and UndefinedBehaviorSanitizer in build-asan
# (-DAQUARELLE_SANITIZE=ON, no editor) and runs the core tests (ctest label `core`) and a few
# per-node tests under them:
#   scripts/sanitize.sh                      core + the default per-node tests
#   scripts/sanitize.sh 'plugins\.blur_test' core + the tests matching that regex
# Any report, leaks at exit included, fails the test that made it (halt_on_error).
# Suppressions, only for third-party libraries and each explained, are in tests/sanitizer/*.supp.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
plugin_tests="${1:-plugins\.(tint|vignette|blur|fog|hard_cases|watercolor_graph)_test}"
build=build-asan

generator=()
if command -v ninja >/dev/null; then generator=(-G Ninja); fi
cmake -S . -B "$build" "${generator[@]}" -DAQUARELLE_SANITIZE=ON -DAQUARELLE_BUILD_EDITOR=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null

# Only the test executables that run here (each pulls in the app and the plugins).
mapfile -t core_targets < <(cd tests/core && ls ./*_test.cpp | sed 's|^\./|core_|; s|\.cpp$||')
mapfile -t node_targets < <(cd tests/plugins && ls ./*_test.cpp | sed 's|^\./|plugins_|; s|\.cpp$||' |
                              grep -E "^${plugin_tests//\\./_}\$" || true)
cmake --build "$build" -j"${AQ_JOBS:-2}" --target "${core_targets[@]}" "${node_targets[@]}"

# Leak checking at exit is on (AQ_DETECT_LEAKS=0 turns it off). The test main
# (tests/support/test_main.cpp) frees the harness's contexts after the last test and keeps
# Mesa's EGL driver loaded, so what is left is ours or named in tests/sanitizer/lsan.supp.
# new_delete_type_mismatch and alloc_dealloc_mismatch stay on.
asan="detect_leaks=${AQ_DETECT_LEAKS:-1}:halt_on_error=1:abort_on_error=0:strict_string_checks=1"
asan+=":detect_stack_use_after_return=0"
export LSAN_OPTIONS="suppressions=$root/tests/sanitizer/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="suppressions=$root/tests/sanitizer/ubsan.supp:print_stacktrace=1:halt_on_error=1"

# Tests whose third-party leak lsan.supp can name only from a full stack: run with slow (DWARF)
# unwinding, a few seconds for these (no GL), where the rest would take minutes (llvmpipe
# allocates on every shader compile).
slow_unwind_tests='core\.image_io_test'
status=0
ASAN_OPTIONS="$asan" ctest --test-dir "$build" --output-on-failure -j"${AQ_JOBS:-2}" \
  -R "^(core\..*|${plugin_tests})\$" -E "^(${slow_unwind_tests})\$" || status=$?
ASAN_OPTIONS="$asan:fast_unwind_on_malloc=0" ctest --test-dir "$build" --output-on-failure \
  -R "^(${slow_unwind_tests})\$" || status=$?
exit "$status"
