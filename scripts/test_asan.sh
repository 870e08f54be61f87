#!/usr/bin/env bash
# The core, verify and CLI tests built with the `asan` preset (AddressSanitizer +
# UndefinedBehaviorSanitizer, every finding fatal) and run under it. Only the three test binaries
# and what they need (glintlab, the test plug-ins) are built. The tests labelled `power`
# (tests/test_tiers.cmake) are left out: they are slow for their sample counts or a cubature's
# precision, over code paths that the sanitized tests named beside each of them also take; the
# sanitizers find memory and UB errors, which depend on the paths, not on the counts
# (docs/building.md).
# The executables are linked -no-pie (the asan preset): a start then applies none of the UBSan
# check data's relocations (docs/building.md "The sanitizer run").
# Usage: bash scripts/test_asan.sh (after scripts/setup.sh); scripts/test.sh (and so CI) ends with it.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${GLINTLAB_JOBS:-$(nproc)}"
source scripts/steps.sh
step asan-configure cmake --preset asan >/dev/null
step asan-build cmake --build --preset asan -j "$jobs" \
  --target glintlab_core_tests glintlab_verify_tests glintlab_cli_tests glintlab_gpu_tests glintlab_gpu_compare
export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
step asan-ctest ctest --preset asan -j "$jobs" -L '^(core|verify|cli|gpu)$' -LE '^power$'
