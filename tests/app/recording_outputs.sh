#!/bin/bash
# Every mode that renders actuator output writes --record-wav/--record-csv (serve: client_server.sh record).
# Usage: recording_outputs.sh VTOUCHING SOURCE_DIR OUT_DIR
#   render --trajectory ... --record-wav/--record-csv, and `run` without a display (the offscreen demo) --record-wav.
set -u
bin=$1 src=$2 out=$3
mkdir -p "$out"
rm -f "$out"/*.wav "$out"/*.csv
fail() { echo "FAIL: $*"; exit 1; }
# A WAV with a RIFF/WAVE header and some audio beyond it, some sample not zero.
check_wav() {
  [ -s "$1" ] || fail "no WAV $1"
  [ "$(head -c 4 "$1")" = RIFF ] && [ "$(head -c 12 "$1" | tail -c 4)" = WAVE ] || fail "$1 is not a RIFF/WAVE file"
  [ "$(stat -c %s "$1")" -gt 1044 ] || fail "$1 holds less than 1 kB of samples"
  tail -c +45 "$1" | od -An -v -tx1 | tr -d ' \n' | grep -q '[1-9a-f]' || fail "$1 is all silence"
}
"$bin" render --trajectory "$src/assets/trajectories/slide.csv" --builtin --quiet --fps 1 --size 160x90 \
  --out "$out/render" --record-wav "$out/render.wav" --record-csv "$out/render.csv" >"$out/render.log" 2>&1 ||
  { cat "$out/render.log"; fail "render exit code $?"; }
check_wav "$out/render.wav"
[ "$(wc -l <"$out/render.csv")" -gt 10 ] || fail "render.csv has fewer than 10 frames"
env -u DISPLAY -u WAYLAND_DISPLAY "$bin" run --demo-out "$out/demo" --record-wav "$out/run.wav" >"$out/run.log" 2>&1 ||
  { cat "$out/run.log"; fail "run exit code $?"; }
grep -q "offscreen demo" "$out/run.log" || fail "run did not take the offscreen demo: $(cat "$out/run.log")"
check_wav "$out/run.wav"
echo "PASS"
