#!/usr/bin/env bash
# The README's run command: install dependencies, build (Release), run the main job.
# With a display: the desktop preview. Without: the offscreen demo, frames and plots in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
vt=build/app/vtouching
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && "$vt" help | grep -q "^  run "; then
  exec "$vt" "$@"
fi
mkdir -p out
"$vt" render --out out/render --size 1280x720 --overlay "$@"
echo "offscreen demo written to $(pwd)/out/"
