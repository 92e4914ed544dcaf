#!/bin/bash
# `vtouching serve` and `vtouching client` as users run them, on loopback (docs/protocol.md).
# Usage: client_server.sh VTOUCHING OUT_DIR MODE
#   headless  the example trajectory drives the client: frames played, touches felt, silent end
#   desktop   the desktop client (run under xvfb-run): validation clean, frames played, touches felt,
#             its recording (the meter's inputs) written and refused by replay
#   headset   the headset client on xrsim (XR_RUNTIME_JSON etc. set by the caller)
#   mismatch  a client showing another scene is refused, naming both scenes in full; the server logs it
#   localhost the client reaches the server by host name (--connect localhost:PORT)
#   ipv6      serve --bind [::1]:0 and a client connecting to it (skipped, 77, without IPv6)
#   wrong_key a keyed server logs each refusal of a client with another key as it happens
#   busy      a second client is refused while the first is connected
#   video     the server's virtual camera (serve --video) reaches a headless client as JPEG files
#   record    serve --record-wav/--record-csv writes what it rendered for a client asking 16 ms blocks
#   block_refused  serve --block-ms 4 refuses a client asking 128 ms, naming both
set -u
bin=$1 out=$2 mode=$3
mkdir -p "$out"
rm -f "$out/$mode".*

# The server binds port 0 (no clashes with parallel tests) and prints the address it got.
server_args=()
[ "$mode" = video ] && server_args=(--video --video-fps 10)
[ "$mode" = record ] && server_args=(--record-wav "$out/$mode.server.wav" --record-csv "$out/$mode.server.csv")
[ "$mode" = block_refused ] && server_args=(--block-ms 4)
[ "$mode" = wrong_key ] && server_args=(--key "$out/$mode.server.key")
bind=127.0.0.1:0
if [ "$mode" = ipv6 ]; then
  bind=[::1]:0
  python3 -c 'import socket; socket.socket(socket.AF_INET6, socket.SOCK_DGRAM).bind(("::1", 0))' 2>/dev/null ||
    { echo "SKIP: no IPv6 loopback"; exit 77; }
fi
VT_LOG=info "$bin" serve --bind "$bind" --seconds 60 "${server_args[@]}" >"$out/$mode.server.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null; wait $server 2>/dev/null' EXIT
. "$(dirname "$0")/server_address.sh"
address=$(server_address "$out/$mode.server.log") || { echo "server did not start:"; cat "$out/$mode.server.log"; exit 1; }

fail() { echo "FAIL ($mode): $*"; exit 1; }
# Runs the client, its output to $mode.client.log; a non-zero exit fails the test with the log.
run_client() {
  "$bin" client --connect "$address" "$@" >"$out/$mode.client.log" 2>&1
  local rc=$?
  [ $rc -eq 0 ] || { cat "$out/$mode.client.log"; fail "client exit code $rc"; }
}
json_number() { sed -n "s/.*\"$1\": \([0-9.e+-]*\).*/\1/p" "$out/$mode.client.log" | head -1; }
# Every CSV row has t_ns,sequence then the actuator levels: some touched, the last one silent.
check_felt_and_silent() {
  local csv=$out/$mode.csv
  [ -s "$csv" ] || fail "no actuator recording $csv"
  awk -F, 'NR > 1 { for (i = 3; i <= 7; ++i) if ($i > 0.01) { print "touch"; exit } }' "$csv" | grep -q touch ||
    fail "no actuator level above 0.01 in $csv"
  tail -1 "$csv" | awk -F, '{ for (i = 3; i <= NF; ++i) if ($i != 0) exit 1 }' || fail "last frame not silent: $(tail -1 "$csv")"
}
check_played() {
  local played
  played=$(json_number frames_played)
  [ -n "$played" ] && [ "$played" -ge "$1" ] || fail "frames_played '$played' < $1"
  echo "frames_played $played, latency p50 $(json_number latency_p50_ms) ms p99 $(json_number latency_p99_ms) ms"
}

case $mode in
  headless)
    run_client --headless --seconds 2 --glove sim --record-csv "$out/$mode.csv" --json
    check_played 300
    check_felt_and_silent
    ;;
  desktop)
    run_client --frames 30 --scripted-input --validate --size 640x360 --record-csv "$out/$mode.csv" \
      --record "$out/$mode.rec" --json
    grep -q "^validation messages: 0$" "$out/$mode.client.log" || fail "validation messages"
    check_played 1
    check_felt_and_silent
    # The client's recording: the consistency meter's inputs (poses, the contacts it rebuilt,
    # frames played, frames drawn), marked as a client's, which replay refuses by name.
    rec=$out/$mode.rec
    grep -qx "remote server=$address" "$rec" || fail "no 'remote server=$address' line in $rec"
    for kind in P F D E; do grep -q "^$kind " "$rec" || fail "no $kind records in $rec"; done
    grep -q "^C [0-9]* [0-9]* 1 " "$rec" || fail "no in-contact C record in $rec"
    if "$bin" replay "$rec" >"$out/$mode.replay.log" 2>&1; then fail "replay accepted a client's recording"; fi
    grep -q "a client's recording" "$out/$mode.replay.log" || fail "replay's refusal: $(cat "$out/$mode.replay.log")"
    ;;
  headset)
    run_client --xr-required --glove none --record-csv "$out/$mode.csv" --json
    grep -q "headset mode: [1-9][0-9]* frames rendered" "$out/$mode.client.log" || fail "no headset frames"
    check_played 1
    check_felt_and_silent
    ;;
  mismatch)
    if "$bin" client --connect "$address" --headless --builtin --seconds 1 >"$out/$mode.client.log" 2>&1; then
      fail "a client with another scene was accepted"
    fi
    # Both scenes named whole: the server's as `serve` printed it, the client's own.
    served=$(sed -n 's/^serving \(.*\) on [^ ]* (model .*/\1/p' "$out/$mode.server.log")
    [ -n "$served" ] || fail "no 'serving' line in the server log"
    grep -qF "scene mismatch: the server renders $served; this client renders built-in demo scene (" \
      "$out/$mode.client.log" || fail "the refusal does not name both scenes whole: $(cat "$out/$mode.client.log")"
    [ "$(wc -l <"$out/$mode.client.log")" -eq 1 ] || fail "more than one line: $(cat "$out/$mode.client.log")"
    for _ in $(seq 20); do grep -q "server: refused 127.0.0.1:[0-9]*: scene mismatch" "$out/$mode.server.log" && break; sleep 0.1; done
    grep -q "server: refused 127.0.0.1:[0-9]*: scene mismatch" "$out/$mode.server.log" || fail "the server did not log the refusal"
    ;;
  localhost|ipv6)
    [ "$mode" = localhost ] && address=localhost:${address##*:}
    run_client --headless --seconds 1 --glove none --json
    check_played 100
    [ "$mode" = ipv6 ] && { grep -q "session 1 with \[::1\]:" "$out/$mode.server.log" || fail "no session from [::1]"; }
    ;;
  wrong_key)
    # Three clients with another key, a second apart: a refusal line each, while the server runs.
    head -c 32 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$out/$mode.other.hex"
    for attempt in 1 2 3; do
      if "$bin" client --connect "$address" --key "$(cat "$out/$mode.other.hex")" --headless --seconds 1 --glove none \
        >"$out/$mode.client.log" 2>&1; then
        fail "a client with another key was accepted"
      fi
      lines=$(grep -c "server: refused 127.0.0.1:[0-9]*: authentication failed" "$out/$mode.server.log")
      [ "$lines" -ge "$attempt" ] || fail "$lines refusal lines after $attempt refused clients: $(cat "$out/$mode.server.log")"
    done
    # Each client retried for its whole connect timeout: far more hellos than lines (rate-limited).
    [ "$lines" -le 12 ] || fail "$lines refusal lines: not rate-limited"
    grep -q "other refusals since the last line" "$out/$mode.server.log" || fail "no count of the refusals not shown"
    ;;
  busy)
    "$bin" client --connect "$address" --headless --seconds 4 --glove none >"$out/$mode.first.log" 2>&1 &
    first=$!
    for _ in $(seq 50); do grep -q "session 1 with" "$out/$mode.server.log" && break; sleep 0.1; done
    if "$bin" client --connect "$address" --headless --seconds 1 --glove none >"$out/$mode.client.log" 2>&1; then
      fail "a second client was accepted"
    fi
    grep -q "refused the session: busy" "$out/$mode.client.log" || fail "no busy refusal"
    wait $first || fail "the first client failed: $(cat "$out/$mode.first.log")"
    ;;
  video)
    rm -rf "$out/video-frames"
    run_client --headless --seconds 2 --glove none --video-out "$out/video-frames" --json
    check_played 300
    frames=$(json_number video_frames_received)
    [ -n "$frames" ] && [ "$frames" -ge 5 ] || fail "video_frames_received '$frames' < 5"
    [ "$(find "$out/video-frames" -name 'frame_*.jpg' -size +2k | wc -l)" -ge 5 ] || fail "fewer than 5 JPEG files"
    echo "video frames received: $frames"
    ;;
  record)
    run_client --headless --seconds 2 --glove none --block-ms 16 --json
    check_played 300
    kill -INT $server
    wait $server || fail "server exit code $?: $(cat "$out/$mode.server.log")"
    trap - EXIT
    grep -q "16 ms blocks" "$out/$mode.server.log" || fail "the session was not in 16 ms blocks"
    wav=$out/$mode.server.wav
    [ -s "$wav" ] && [ "$(head -c 4 "$wav")" = RIFF ] || fail "no server WAV $wav"
    [ "$(stat -c %s "$wav")" -gt 10044 ] || fail "server WAV $wav holds less than 10 kB of samples"
    awk -F, 'NR > 1 { for (i = 3; i <= 7; ++i) if ($i > 0.01) { print "touch"; exit } }' "$out/$mode.server.csv" |
      grep -q touch || fail "no actuator level above 0.01 in the server's CSV"
    ;;
  block_refused)
    if "$bin" client --connect "$address" --headless --seconds 1 --glove none --block-ms 128 >"$out/$mode.client.log" 2>&1; then
      fail "a client asking 128 ms blocks was accepted by serve --block-ms 4"
    fi
    grep -q "block length 128 ms asked, this server streams 4 ms blocks" "$out/$mode.client.log" || fail "no block length refusal"
    ;;
  *) fail "unknown mode" ;;
esac
cat "$out/$mode.client.log"
echo "PASS ($mode)"
