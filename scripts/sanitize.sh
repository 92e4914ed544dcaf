#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan (scripts/build-asan.sh)
# and runs the whole ctest suite there. Extra args go to ctest (e.g. -R haptics).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build-asan.sh
cd "${BUILD_DIR:-build-asan}"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --output-on-failure -j "$(nproc)" --timeout 900 "$@"
