#!/bin/bash
# One shutdown path: SIGINT ends each mode cleanly (exit 0, end-of-run report, silent sinks).
# Usage: shutdown.sh VTOUCHING OUT_DIR MODE [XRSIM_MANIFEST]
#   desktop   the desktop preview (run under xvfb-run), recording: the recording replays
#   headset   headset mode on xrsim: the session ends through xrEndSession, report printed
#   client    a headless client and its server: the client's bye reaches the server (no
#             timeout), both print their reports; then the server itself
#   acquire   an acquisition interrupted mid-run writes nothing (exit 130), or had finished
#   render    an offscreen trajectory run ends early with its traces, figures and recording whole
#   play      a haptic clip on the simulated glove ends on a silent frame
set -u
bin=$1 out=$2 mode=$3
mkdir -p "$out"
rm -rf "${out:?}/$mode".*
fail() { echo "FAIL ($mode): $*"; exit 1; }
# Starts "$@" in the background with its output in $out/$mode.$name.log, waits until the log
# matches $ready (or 30 s), sends SIGINT, and returns the exit status.
interrupt() {
  local name=$1 ready=$2; shift 2
  "$@" >"$out/$mode.$name.log" 2>&1 &
  local pid=$!
  # Not before the program runs: a signal in the forked shell's first instants (before its
  # redirection and exec) ends the shell itself, with exit 130 and no log at all.
  local exe
  exe=$(readlink -f "$1")
  for _ in $(seq 250); do
    [ "$(readlink -f /proc/$pid/exe 2>/dev/null)" = "$exe" ] && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.02
  done
  for _ in $(seq 300); do
    [ "$ready" = - ] && { sleep 0.05; break; }  # no start line: signal mid-run, once main has begun
    grep -q -- "$ready" "$out/$mode.$name.log" 2>/dev/null && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.1
  done
  [ "$ready" = - ] || sleep "${SETTLE_S:-1}"  # past start-up: the mode is running
  kill -INT $pid 2>/dev/null
  for _ in $(seq 150); do kill -0 $pid 2>/dev/null || break; sleep 0.1; done
  kill -0 $pid 2>/dev/null && { kill -9 $pid; cat "$out/$mode.$name.log"; fail "$name still running 15 s after SIGINT"; }
  wait $pid
}
clean_log() {  # no error or warning lines from us, the loaders, the runtime or a sanitizer
  ! grep -E "^\[(warn|error)\]|vtouching: (error|unexpected)|ERROR|Sanitizer|abort" "$1" || fail "errors in $1"
}

case "$mode" in
  desktop)
    SETTLE_S=3 VT_LOG=info interrupt app "desktop preview" "$bin" run --size 480x270 --record "$out/$mode.rec" --record-csv "$out/$mode.csv"
    rc=$?
    [ $rc -eq 0 ] || { cat "$out/$mode.app.log"; fail "exit $rc after SIGINT"; }
    clean_log "$out/$mode.app.log"
    grep -q "recorded [0-9]* actuator frames" "$out/$mode.app.log" || fail "no recording report"
    "$bin" replay "$out/$mode.rec" >"$out/$mode.replay.log" 2>&1 || { cat "$out/$mode.replay.log"; fail "replay failed"; }
    tail -1 "$out/$mode.csv" | awk -F, '{ for (i = 3; i <= NF; ++i) if ($i != 0) exit 1 }' || fail "last frame not silent"
    ;;
  headset)
    export XR_RUNTIME_JSON=$4 XRSIM_REALTIME=1 XRSIM_OUTPUT_DIR=$out/$mode.xrsim
    VT_LOG=debug interrupt app "headset mode:" "$bin" run --xr-required --no-mirror --record-csv "$out/$mode.csv"
    rc=$?
    [ $rc -eq 0 ] || { cat "$out/$mode.app.log"; fail "exit $rc after SIGINT"; }
    clean_log "$out/$mode.app.log"
    grep -q "headset mode: [0-9]* frames rendered" "$out/$mode.app.log" || fail "no end-of-run report"
    # STOPPING (6) -> xrEndSession -> IDLE (1) -> EXITING (8): the runtime ended the session.
    grep -q "session state 6 -> 1" "$out/$mode.app.log" || fail "the session did not go STOPPING -> IDLE (xrEndSession)"
    ;;
  client)
    VT_LOG=info "$bin" serve --bind 127.0.0.1:0 >"$out/$mode.server.log" 2>&1 &
    server=$!
    . "$(dirname "$0")/server_address.sh"
    address=$(server_address "$out/$mode.server.log") || { kill $server; fail "server did not start"; }
    VT_LOG=info interrupt client "client: session" "$bin" client --connect "$address" --headless --seconds 60
    rc=$?
    [ $rc -eq 0 ] || { cat "$out/$mode.client.log"; kill $server; fail "client exit $rc after SIGINT"; }
    grep -q "frames_played" "$out/$mode.client.log" || { kill $server; fail "no client report"; }
    sleep 0.3
    kill -INT $server
    wait $server
    rc=$?
    [ $rc -eq 0 ] || { cat "$out/$mode.server.log"; fail "server exit $rc after SIGINT"; }
    clean_log "$out/$mode.server.log"
    grep -q "server: 1 sessions, 0 refused, 0 timeouts" "$out/$mode.server.log" ||
      { cat "$out/$mode.server.log"; fail "the client's bye did not end the session (a timeout instead)"; }
    ;;
  acquire)
    "$bin" acquire --synthetic pattern_board --out "$out/$mode.scan" --quiet >/dev/null 2>&1 || fail "synthetic scan"
    interrupt app "-" "$bin" acquire "$out/$mode.scan" --out "$out/$mode.dataset" --quiet
    rc=$?
    if [ $rc -eq 130 ]; then
      grep -q "interrupted; nothing written" "$out/$mode.app.log" || fail "no interruption message"
      [ -z "$(ls -A "$out/$mode.dataset" 2>/dev/null)" ] || fail "an interrupted acquisition wrote $(ls "$out/$mode.dataset")"
    else
      [ $rc -eq 0 ] || { cat "$out/$mode.app.log"; fail "exit $rc"; }
      echo "note: the acquisition finished before the signal"
    fi
    ;;
  render)
    # A ten-minute path rendered without frames: Ctrl-C ends it with its traces and figures whole.
    printf 't_s,x_m,y_m,z_m\n0,-0.22,0.032,0.065\n600,0.30,0.032,0.065\n' >"$out/$mode.path.csv"
    interrupt app "render: " "$bin" render --trajectory "$out/$mode.path.csv" --out "$out/$mode.out" --fps 0 \
      --record-csv "$out/$mode.csv"
    rc=$?
    [ $rc -eq 0 ] || { cat "$out/$mode.app.log"; fail "exit $rc after SIGINT"; }
    grep -q "stopped (Ctrl-C) after [0-9]* haptic ticks" "$out/$mode.app.log" || { cat "$out/$mode.app.log"; fail "no stop report"; }
    [ -s "$out/$mode.out/traces.csv" ] && [ -s "$out/$mode.out/figure.png" ] || fail "traces or figure missing"
    tail -1 "$out/$mode.csv" | awk -F, '{ for (i = 3; i <= NF; ++i) if ($i != 0) exit 1 }' || fail "last frame not silent"
    ;;
  play)
    # A one-minute clip played in real time on the simulated glove: Ctrl-C ends it on silence.
    printf '{"version": {"major": 1, "minor": 0, "patch": 0}, "metadata": {"description": "long"}, "signals": {"continuous": {"envelopes": {"amplitude": [{"time": 0.0, "amplitude": 0.8}, {"time": 60.0, "amplitude": 0.8}]}}}}\n' >"$out/$mode.haptic"
    interrupt app "playing " "$bin" play "$out/$mode.haptic" --glove sim --record-csv "$out/$mode.csv"
    rc=$?
    [ $rc -eq 0 ] || { cat "$out/$mode.app.log"; fail "exit $rc after SIGINT"; }
    grep -q "stopped (Ctrl-C) at" "$out/$mode.app.log" || { cat "$out/$mode.app.log"; fail "no stop report"; }
    clean_log "$out/$mode.app.log"
    tail -1 "$out/$mode.csv" | awk -F, '{ for (i = 3; i <= NF; ++i) if ($i != 0) exit 1 }' || fail "last frame not silent"
    ;;
  *) fail "unknown mode" ;;
esac
echo "PASS ($mode)"
