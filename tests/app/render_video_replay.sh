#!/bin/sh
# Offscreen runs that export (docs/app.md): `render --trajectory --video` encodes one video with
# the frame count and size asked for (ffprobe); `replay FILE --out DIR` re-renders a recording as
# frames, traces and figures; the single-view `render --quiet` prints nothing.
# Usage: render_video_replay.sh VTOUCHING SOURCE_DIR OUT_DIR (exit 77 = skipped: no ffmpeg)
set -eu
vtouching=$1 source=$2 out=$3
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$out" && mkdir -p "$out"
slide=$source/assets/trajectories/slide.csv

# The single view: --quiet leaves stdout and stderr empty, the frame written.
"$vtouching" render --builtin --frames 1 --size 160x90 --out "$out/single" --quiet >"$out/single.log" 2>&1
test ! -s "$out/single.log" || { cat "$out/single.log"; fail "render --quiet printed"; }
test -s "$out/single/frame.png" || fail "render --quiet wrote no frame.png"

# A short recording (the slide's first 4.5 s: across the back row; no frames) replayed into
# frames and figures.
awk -F, '/^#/ || $1 == "t_s" || $1 + 0 <= 4.5' "$slide" > "$out/short.csv"
"$vtouching" render --trajectory "$out/short.csv" --fps 0 --out "$out/recorded" --record "$out/short.rec" --quiet
"$vtouching" replay "$out/short.rec" --out "$out/replay" --size 160x90 --fps 5 --quiet >"$out/replay.log" 2>&1 ||
  { cat "$out/replay.log"; fail "replay --out failed"; }
grep -q " 0 differ" "$out/replay.log" || { cat "$out/replay.log"; fail "replay differs"; }
frames=$(ls "$out/replay" | grep -c '^frame_[0-9]*\.png$' || true)
[ "$frames" = 23 ] || fail "replay --out wrote $frames frame PNGs (expected 23: 4.5 s at 5 fps)"
test -s "$out/replay/figure.png" || fail "replay --out wrote no figure.png"
test -s "$out/replay/traces.csv" && test -s "$out/replay/actuator_frames.csv" || fail "replay --out wrote no traces"
grep -q '"recording"' "$out/replay/traces.json" || fail "traces.json does not name the recording"

# --video: the frames go into one file; without ffmpeg the option is refused at parsing.
if ! command -v ffmpeg >/dev/null 2>&1 || ! command -v ffprobe >/dev/null 2>&1; then
  PATH=/nonexistent "$vtouching" render --trajectory "$out/short.csv" --out "$out/novideo" --video "$out/x.mp4" 2>"$out/novideo.log" &&
    fail "--video without ffmpeg was accepted"
  grep -q "Debian package ffmpeg" "$out/novideo.log" || fail "--video without ffmpeg: message does not name the package"
  echo "SKIP: ffmpeg/ffprobe not installed (Debian package ffmpeg); only the refusal was checked"
  exit 77
fi
"$vtouching" render --trajectory "$out/short.csv" --out "$out/video" --size 320x180 --fps 10 --video "$out/video/run.mp4" --quiet
probe=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames,width,height -of csv=p=0 "$out/video/run.mp4")
[ "$probe" = "320,180,46" ] || fail "ffprobe says '$probe' (expected 320,180,46: 4.5 s at 10 fps)"
ls "$out/video" | grep -q '^frame_' && fail "--video also wrote PNG frames"
test -s "$out/video/figure.png" || fail "--video run wrote no figure"
PATH=/nonexistent "$vtouching" render --trajectory "$out/short.csv" --out "$out/novideo" --video "$out/x.mp4" 2>"$out/novideo.log" &&
  fail "--video without ffmpeg was accepted"
grep -q "Debian package ffmpeg" "$out/novideo.log" || fail "--video without ffmpeg: message does not name the package"
echo PASS
