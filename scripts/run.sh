#!/usr/bin/env bash
# The README's first command: install what the application needs, build only the application
# (scripts/test.sh builds the tests, benches and fuzzers), install it so that `vtouching` is on
# the PATH, and run the main job: with a display the desktop preview; without one the example
# slide offscreen (frames, per-finger traces and the Fig. 5 plots) into out/slide/.
# One progress line per step. VT_PREFIX overrides where it installs (default: /usr/local as
# root, else ~/.local); arguments go to vtouching.
set -euo pipefail
cd "$(dirname "$0")/.."
started=$SECONDS
step() { printf '[run.sh %4ds] %s\n' "$((SECONDS - started))" "$*"; }
if [ "$(id -u)" = 0 ]; then prefix=${VT_PREFIX:-/usr/local}; else prefix=${VT_PREFIX:-$HOME/.local}; fi
build_dir=${BUILD_DIR:-build}
log=$build_dir/run-sh.log
mkdir -p "$build_dir"

step "1/4 packages for building and running (scripts/install-deps.sh run)"
if [ "$(id -u)" = 0 ]; then bash scripts/install-deps.sh run; else step "     not root: skipped (run scripts/install-deps.sh as root once)"; fi

step "2/4 building vtouching, the headless OpenXR runtime and the man page on $(nproc) cores (log: $log)"
if ! VT_BUILD_TARGETS=installable bash scripts/build.sh >"$log" 2>&1; then
  tail -n 30 "$log" >&2
  echo "run.sh: the build failed (the whole log: $log)" >&2
  exit 1
fi

step "3/4 installing into $prefix"
cmake --install "$build_dir" --prefix "$prefix" >>"$log"
vt=$prefix/bin/vtouching
if [ "$(command -v vtouching || true)" != "$vt" ]; then
  step "     $prefix/bin is not first on your PATH: add it (export PATH=$prefix/bin:\$PATH) to call vtouching by name"
fi

if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  step "4/4 vtouching: the desktop preview (Esc quits)"
  exec "$vt" "$@"
fi
step "4/4 no display: the offscreen demo (vtouching render --trajectory ... --out out/slide)"
"$vt" render --trajectory "$prefix/share/vtouching/assets/trajectories/slide.csv" --out out/slide --fps 10 \
  --size 960x540 "$@"
step "done: out/slide/ (frame_*.png, traces.csv, figure*.png); vtouching help lists every command"
