#!/usr/bin/env bash
# Regenerates the renderer's golden images (tests/golden/*.png) from the current build, after an
# intended visual change. Review the images (git diff shows them changed) before committing.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-Release} >/dev/null
cmake --build "$build_dir" --target vt_renderer_tests
VT_UPDATE_GOLDENS=1 "$build_dir/tests/renderer/vt_renderer_tests" "[golden]"
git status --short tests/golden
