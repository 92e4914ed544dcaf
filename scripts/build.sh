#!/usr/bin/env bash
# Configures and builds into ${BUILD_DIR:-build} (Release). Extra args go to cmake configure.
# VT_BUILD_TARGETS="a b" builds only those targets (scripts/run.sh: what the application needs).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
export CCACHE_DIR=${CCACHE_DIR:-$HOME/.cache/ccache}
# Test programs use precompiled headers (cmake/VtTarget.cmake): ccache caches those compilations
# only with these sloppiness settings.
export CCACHE_SLOPPINESS=${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime,include_file_ctime}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-Release} "$@" >/dev/null
targets=()
for t in ${VT_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build_dir" -j "$(nproc)" "${targets[@]}"
