#!/bin/sh
# `cmake --install` into a fresh prefix; the installed vtouching, run from another folder, finds
# its assets beside itself (traces.json names the prefix's dataset, relative to the working folder), runs the no-display demo,
# and the installed xrsim manifest (a path relative to itself) loads the runtime.
set -eu
build=$1 out=$2
rm -rf "$out" && mkdir -p "$out/elsewhere"
cmake --install "$build" --prefix "$out/prefix" > "$out/install.log"
prefix=$out/prefix
for f in bin/vtouching share/man/man1/vtouching.1 share/bash-completion/completions/vtouching \
         share/vtouching/assets/trajectories/slide.csv share/vtouching/assets/dataset \
         share/vtouching/xrsim/xrsim.json share/doc/vtouching/README.md share/doc/vtouching/docs/app.md; do
  test -e "$prefix/$f" || { echo "FAIL: $f is not installed"; exit 1; }
done
head -1 "$prefix/share/man/man1/vtouching.1" | grep -q '^\.TH VTOUCHING 1' || { echo "FAIL: man page"; exit 1; }
cd "$out/elsewhere"
env -u DISPLAY -u WAYLAND_DISPLAY "$prefix/bin/vtouching" run > demo.log
grep -q "offscreen demo: [1-9][0-9]* frames" demo.log || { cat demo.log; echo "FAIL: no demo"; exit 1; }
grep -q "prefix/share/vtouching/assets/dataset" vtouching-demo/traces.json ||
  { cat vtouching-demo/traces.json; echo "FAIL: the demo did not use the installed assets"; exit 1; }
if [ -e "$prefix/lib/vtouching/libxrsim.so" ]; then
  XR_RUNTIME_JSON=$prefix/share/vtouching/xrsim/xrsim.json XRSIM_FRAMES=5 XRSIM_HAND_TRACKING=false \
    "$prefix/bin/vtouching" run --xr-required --no-mirror --glove none > xr.log 2>&1 ||
    { cat xr.log; echo "FAIL: the installed xrsim runtime"; exit 1; }
  grep -q "headset mode: [1-9][0-9]* frames rendered" xr.log || { cat xr.log; echo "FAIL: no headset frames"; exit 1; }
fi
echo PASS
