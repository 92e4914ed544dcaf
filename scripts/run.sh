#!/usr/bin/env bash
# The README's run command: install dependencies, build (Release), run the main job.
# With a display: the desktop preview. Without: an offscreen run of the example slide
# (frames, per-finger traces and the Fig. 5 plots) written to out/slide/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
vt=build/app/vtouching
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec "$vt" "$@"
fi
echo "no display: running the offscreen demo instead of the desktop preview"
"$vt" render --trajectory assets/trajectories/slide.csv --out out/slide --fps 10 --size 960x540 "$@"
echo "offscreen demo written to $(pwd)/out/slide/ (frame_*.png, traces.csv, figure*.png)"
