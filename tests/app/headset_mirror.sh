#!/bin/sh
# Headset mode on xrsim with the mirror window (run under xvfb-run): exit 0, the mirror rendered
# frames and saved the last one, and the validation layer reported nothing.
# Usage: headset_mirror.sh VTOUCHING OUT.png [MORE OPTIONS...]
bin=$1 png=$2
shift 2
out=$("$bin" --xr --glove none --validate --size 320x180 --frames 20 --screenshot "$png" "$@")
rc=$?
echo "$out"
test $rc -eq 0 || { echo "exit code $rc"; exit 1; }
echo "$out" | grep -q "mirror window 320x180, [1-9][0-9]* frames" || { echo "no mirror frames"; exit 1; }
echo "$out" | grep -q "^validation messages: 0$" || { echo "validation messages"; exit 1; }
test -s "$png" || { echo "no mirror capture $png"; exit 1; }
