#!/bin/sh
# vtouching play / export with haptic files: a .haptic clip played (no glove) into a recording,
# the recording exported to HJIF, AHAP and .haptic, and the HJIF played back (and converted) to the
# same WAV.
set -eu
vtouching=$1 out=$3
rm -rf "$out" && mkdir -p "$out"
cat > "$out/tap-index.haptic" <<'JSON'
{"version": {"major": 1, "minor": 0, "patch": 0}, "metadata": {"description": "test tap"},
 "signals": {"continuous": {"envelopes": {
   "amplitude": [{"time": 0.0, "amplitude": 0.0}, {"time": 0.1, "amplitude": 0.8}, {"time": 0.3, "amplitude": 0.2}],
   "frequency": [{"time": 0.0, "frequency": 0.4}, {"time": 0.3, "frequency": 0.6}]}}}}
JSON
"$vtouching" play "$out/tap-index.haptic" --glove none --record-csv "$out/rec.csv" --record-wav "$out/rec.wav"
"$vtouching" export "$out/rec.csv" "$out/rec.wav" --out "$out/rec.hjif"
"$vtouching" export "$out/rec.csv" --out "$out/rec.ahap"
"$vtouching" export "$out/rec.csv" --out "$out/rec.haptic"
test -s "$out/rec.ahap" && test -s "$out/rec.haptic"  # one active actuator: one file each
"$vtouching" play "$out/rec.hjif" --glove none --record-wav "$out/again.wav"
"$vtouching" play "$out/rec.ahap" --glove none --record-wav "$out/ahap.wav"
cmp "$out/rec.wav" "$out/again.wav"
# convert: HJIF -> WAV gives the recorded WAV back byte for byte; the losses are stated.
"$vtouching" convert "$out/rec.hjif" --out "$out/back.wav" > "$out/convert.txt"
cmp "$out/rec.wav" "$out/back.wav"
"$vtouching" convert "$out/rec.hjif" --out "$out/conv-index.ahap" > "$out/convert-ahap.txt"
grep -q "lost: the waveform is not carried" "$out/convert-ahap.txt"
"$vtouching" play "$out/conv-index.ahap" --glove none > /dev/null
if "$vtouching" convert "$out/rec.hjif" --out "$out/x.mp3" 2>"$out/conv-err.txt"; then exit 1; fi
grep -q "x.mp3': expected .hjif, .ahap, .haptic or .wav" "$out/conv-err.txt"
if "$vtouching" play "$out/missing.hjif" --glove none 2>"$out/err.txt"; then exit 1; fi
grep -q "missing.hjif" "$out/err.txt"
# A clip for a glove that is not there is an error, not a silent run (no glove on a test machine).
if "$vtouching" play "$out/tap-index.haptic" --glove hid:NO-SUCH-SERIAL 2>"$out/hid.txt"; then exit 1; fi
grep -q "no glove found for --glove hid:NO-SUCH-SERIAL" "$out/hid.txt"
echo PASS
