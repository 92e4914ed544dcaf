#!/usr/bin/env bash
# vtouching --xr on xrsim with --output audio (ALSA's file plugin captures what the card would
# play) and --output osc (a UDP listener counts the messages), the audio capture compared with
# --record-wav of the same session. Prints PASS.
set -euo pipefail
vt="$1"
out="$2"
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$out"

# One session and its checks; prints PASS last when they all hold.
session() {
rm -f "$out/audio.raw" "$out/record.wav" "$out/osc.port" "$out/osc.count"
# An OSC listener on a free port: counts /vtouching/levels datagrams until 2 s of quiet.
/usr/bin/python3 - "$out" <<'PY' &
import socket, sys
out = sys.argv[1]
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.bind(("127.0.0.1", 0))
open(out + "/osc.port", "w").write(str(s.getsockname()[1]))
s.settimeout(20)
count = 0
try:
    while True:
        data = s.recv(4096)
        s.settimeout(2)
        if data.startswith(b"/vtouching/levels\0"):
            count += 1
except socket.timeout:
    pass
open(out + "/osc.count", "w").write(str(count))
PY
listener=$!
for _ in $(seq 50); do [ -s "$out/osc.port" ] && break; sleep 0.1; done
port="$(cat "$out/osc.port")"
# XRSIM_HAPTIC_PCM: the controller sink takes every frame too (the PCM path of headset mode).
XRSIM_HAPTIC_PCM=1 "$vt" --xr --glove none --intensity normalised --output "audio:file:FILE=$out/audio.raw,FORMAT=raw" --channels index,-,thumb \
  --output "osc://127.0.0.1:$port" --record-wav "$out/record.wav"
wait "$listener"
grep -q '"event":"pcm"' "$XRSIM_OUTPUT_DIR/haptics.jsonl" || { echo "FAIL: no PCM haptics logged by xrsim"; exit 1; }
echo "OSC levels messages: $(cat "$out/osc.count")"
[ "$(cat "$out/osc.count")" -gt 10 ] || { echo "FAIL: too few OSC messages"; exit 1; }
/usr/bin/python3 "$here/compare_audio_capture.py" "$out/audio.raw" 3 48000 "$out/record.wav" 1,-,0
}

# A host that takes the CPU from the audio thread for long stretches (CI's shared 2-core VMs:
# headset frames at 44 ms instead of 20, every window below 0.9, the capture seconds behind)
# starves blocks the recording has. As the live gates do, a miss runs the session up to twice
# more and fails when all three miss: a wrong channel, rate or signal misses every time.
for attempt in 1 2 3; do
  session 2>&1 | tee "$out/attempt$attempt.log" || true
  if [ "$(tail -n 1 "$out/attempt$attempt.log")" = PASS ]; then exit 0; fi
  [ "$attempt" -lt 3 ] && echo "attempt $attempt missed; running the session again"
done
echo "FAIL: all three sessions missed"
exit 1
