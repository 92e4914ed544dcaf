#!/usr/bin/env bash
# Regenerates assets/dataset/: the app's default objects, produced by the real acquisition
# pipeline from synthetic scans (vtouching acquire --synthetic, then vtouching acquire), in
# the published Pixel2Taxel layout plus NAME_map.json (physical size, statistics).
#   bash scripts/make-assets.sh [path/to/vtouching]     (default: build/app/vtouching)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
vtouching="${1:-$root/build/app/vtouching}"
[ -x "$vtouching" ] || { echo "make-assets: '$vtouching' not found; build first (bash scripts/build.sh)" >&2; exit 1; }
out="$root/assets/dataset"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# kind  length_mm(Y, image width)  lines(X, 2 mm apart, image height)  seed
# Aspect ratios follow the published objects' images; 2 px/mm keeps every image <= 240 px.
objects=(
  "pattern_board          96 30 11"
  "relief_ceramic_tile    80 46 12"
  "notebook_cover         84 37 13"
  "plastic_grid           88 36 14"
  "gift_box              120 24 15"
  "red_envelope           50 50 16"
  "plastic_cutting_board  90 40 17"
  "smooth_ceramic_tile    60 45 18"
)
rm -rf "$out"
mkdir -p "$out"
for spec in "${objects[@]}"; do
  read -r kind length lines seed <<<"$spec"
  "$vtouching" acquire --synthetic "$kind" --out "$work/$kind" --length-mm "$length" --lines "$lines" \
    --seed "$seed" --scale 2 --quiet
  # No waveforms/: at 1 mm cells and one taxel crossing (50 ms at 8 kHz) they take 8.9 MB for
  # pattern_board alone (~75 MB for the eight); even 5 ms loops would add ~7.5 MB, and fitting
  # 2 MB would leave ~1 ms per cell, shorter than one period of the textures (25 ms at 40 Hz).
  # `vtouching acquire SCAN --out DIR` writes them for a local dataset.
  "$vtouching" acquire "$work/$kind" --out "$out" --no-float-map --no-waveforms --quiet
  rm -f "$out/$kind/${kind}_preview.png"
  echo "make-assets: $kind"
done
"$vtouching" stats "$out" --out "$out"
du -sh "$out"
