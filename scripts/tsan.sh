#!/usr/bin/env bash
# Builds the libraries below the renderer with ThreadSanitizer into build-tsan and runs their
# tests there: the seqlock LatestValue, the SpscRing, the pose history, the haptic loop's
# epoch reclamation of scene snapshots, the glove driver's threads and the network sessions.
# Extra args go to ctest (e.g. -R haptics).
set -euo pipefail
cd "$(dirname "$0")/.."
# clang at -O1 with line tables: several times faster to compile than gcc -O2 -g (see
# scripts/build-asan.sh), and reports still name file and line.
flags="-O1 -gline-tables-only -DNDEBUG"
CC=clang CXX=clang++ BUILD_DIR=${BUILD_DIR:-build-tsan} BUILD_TYPE=RelWithDebInfo bash scripts/build.sh \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="$flags" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld -DVT_SANITIZE_THREAD=ON -DVT_BUILD_BENCH=OFF -DVT_ONLY="core;scene;collision;haptics;net"
cd "${BUILD_DIR:-build-tsan}"
# halt_on_error: the first race fails its test. second_deadlock_stack: readable lock reports.
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1}
ctest --output-on-failure -j "$(nproc)" --timeout 900 "$@"
