#!/usr/bin/env bash
# The README's test command: install dependencies, build, and run every test.
#   1. Release build, the whole ctest suite (unit, property, golden-image, window under
#      Xvfb, OpenXR through xrsim, network loopback, fuzz corpora).
#   2. The same suite built with ASan + UBSan.
#   3. ThreadSanitizer over the libraries with threads below the renderer (core, scene,
#      collision, haptics, net): lock-free channels, snapshots, glove and network threads.
#   4. Every libFuzzer target for a bounded time (clang).
# VT_TEST_STAGES picks stages (default "release sanitize tsan fuzz"); VT_FUZZ_SECONDS per target.
set -euo pipefail
cd "$(dirname "$0")/.."
stages=${VT_TEST_STAGES:-release sanitize tsan fuzz}
bash scripts/install-deps.sh
for stage in $stages; do
  echo "=== test stage: $stage"
  case "$stage" in
    release)
      bash scripts/build.sh
      (cd "${BUILD_DIR:-build}" && ctest --output-on-failure -j "$(nproc)" --timeout 600) ;;
    sanitize) bash scripts/sanitize.sh ;;
    tsan) bash scripts/tsan.sh ;;
    fuzz) bash scripts/fuzz.sh "${VT_FUZZ_SECONDS:-10}" ;;
    *) echo "unknown test stage '$stage' (release, sanitize, tsan, fuzz)" >&2; exit 2 ;;
  esac
done
echo "=== all test stages passed: $stages"
