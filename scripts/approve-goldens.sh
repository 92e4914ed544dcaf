#!/usr/bin/env bash
# Regenerates the golden images (tests/golden/*.png) from the current build, after an intended
# visual change: the renderer's, the server video frame's (vt_app_tests) and both headset eyes'
# (vt_xr_tests, on xrsim). Review the images (git diff shows them changed) before committing.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-Release} >/dev/null
cmake --build "$build_dir" --target vt_renderer_tests vt_app_tests vt_xr_tests
VT_UPDATE_GOLDENS=1 "$build_dir/tests/renderer/vt_renderer_tests" "[golden]"
VT_UPDATE_GOLDENS=1 "$build_dir/tests/app/vt_app_tests" "[golden]"
VT_UPDATE_GOLDENS=1 "$build_dir/tests/xr/vt_xr_tests" "[golden]"
git status --short tests/golden
