#!/usr/bin/env bash
# A networked V-Touching session over a real link: `vtouching serve` in one network namespace,
# the headless `vtouching client` in another, joined by a veth pair (server 10.77.0.1/24,
# client 10.77.0.2/24). Impairment goes on both veth ends with netem when the kernel has it,
# otherwise (one line says so) into the programs' in-process impairment on what each side
# receives, so the run still crosses the veth link. Checks the client's report and that its
# recorded output ends silent; prints a summary. Namespaces and processes are always removed.
#
#   sudo VTOUCHING=build/app/vtouching scripts/netns-session.sh [--seconds 5]
#        [--delay-ms D] [--jitter-ms J] [--loss PCT] [--reorder PCT] [--codecs LIST]
#        [--in-process] [--max-p99-ms MS] [--out DIR] [--bin PATH]
#
# Exit: 0 sane, 1 a check failed, 2 usage or setup error, 77 cannot run here (not root, no
# `ip`, namespaces or veth refused).
set -euo pipefail

usage() { sed -n '9,14p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
die() { echo "netns-session: $*" >&2; exit 2; }
skip() { echo "netns-session: skipped: $*"; exit 77; }
number() { [[ $2 =~ ^[0-9]+([.][0-9]+)?$ ]] || die "$1 expects a non-negative number, not '$2'"; echo "$2"; }

bin=${VTOUCHING:-}
seconds=5 delay=0 jitter=0 loss=0 reorder=0 codecs=perceptual,pcm16,raw-f32
in_process=0 max_p99=100 out=""
while [ $# -gt 0 ]; do
  case $1 in
    --bin) bin=${2:?--bin PATH}; shift ;;
    --seconds) seconds=$(number "$1" "${2:-}"); shift ;;
    --delay-ms) delay=$(number "$1" "${2:-}"); shift ;;
    --jitter-ms) jitter=$(number "$1" "${2:-}"); shift ;;
    --loss) loss=$(number "$1" "${2:-}"); shift ;;
    --reorder) reorder=$(number "$1" "${2:-}"); shift ;;
    --codecs) codecs=${2:?--codecs LIST}; shift ;;
    --in-process) in_process=1 ;;
    --max-p99-ms) max_p99=$(number "$1" "${2:-}"); shift ;;
    --out) out=${2:?--out DIR}; shift ;;
    -h|--help) usage ;;
    *) die "unknown option '$1' (--help lists them)" ;;
  esac
  shift
done
[ -n "$bin" ] || die "no vtouching binary: set VTOUCHING=PATH or pass --bin PATH"
[ -x "$bin" ] || die "$bin is not an executable"
bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
awk -v l="$loss" -v r="$reorder" 'BEGIN { exit !(l <= 100 && r <= 100) }' || die "--loss and --reorder are percentages 0..100"

[ "$(id -u)" -eq 0 ] || skip "needs root for network namespaces (run with sudo)"
command -v ip >/dev/null || skip "'ip' (iproute2) is not installed"

srv=vt-srv-$$ cli=vt-cli-$$ srv_if=vts$$ cli_if=vtc$$
srv_addr=10.77.0.1 cli_addr=10.77.0.2 port=47800
work=$(mktemp -d "${TMPDIR:-/tmp}/vt-netns.XXXXXX")
server_pid="" client_pid="" made_srv=0 made_cli=0

stopped_rc=0
stop() {  # stop child PID: SIGTERM (the programs end cleanly), SIGKILL after 3 s; sets stopped_rc
  local pid=$1
  kill -TERM "$pid" 2>/dev/null || true
  for _ in $(seq 30); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  kill -KILL "$pid" 2>/dev/null || true
  stopped_rc=0
  wait "$pid" 2>/dev/null || stopped_rc=$?
}
cleanup() {
  local rc=$? ns pid
  trap - EXIT INT TERM
  [ -z "$client_pid" ] || stop "$client_pid"
  [ -z "$server_pid" ] || stop "$server_pid"
  for ns in "$cli" "$srv"; do
    # Anything left in our own namespaces was started by this script.
    if ip netns list 2>/dev/null | grep -qw "$ns"; then
      for pid in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$pid" 2>/dev/null || true; done
    fi
  done
  [ "$made_cli" -eq 0 ] || ip netns del "$cli" 2>/dev/null || true
  [ "$made_srv" -eq 0 ] || ip netns del "$srv" 2>/dev/null || true  # removes the veth pair too
  if [ -n "$out" ] && mkdir -p "$out"; then cp "$work"/server.log "$work"/client.* "$out"/ 2>/dev/null || true; fi
  rm -rf "$work"
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# --- the link -----------------------------------------------------------------------------
ip netns add "$srv" 2>"$work/ip.err" || skip "network namespace refused: $(head -1 "$work/ip.err")"
made_srv=1
ip netns add "$cli" 2>"$work/ip.err" || skip "network namespace refused: $(head -1 "$work/ip.err")"
made_cli=1
ip link add "$srv_if" netns "$srv" type veth peer name "$cli_if" netns "$cli" 2>"$work/ip.err" ||
  skip "veth pair refused: $(head -1 "$work/ip.err")"
{ ip -n "$srv" addr add "$srv_addr/24" dev "$srv_if" && ip -n "$cli" addr add "$cli_addr/24" dev "$cli_if" &&
  ip -n "$srv" link set lo up && ip -n "$cli" link set lo up &&
  ip -n "$srv" link set "$srv_if" up && ip -n "$cli" link set "$cli_if" up; } 2>"$work/ip.err" ||
  skip "configuring the veth link refused: $(head -1 "$work/ip.err")"
ip netns exec "$srv" true 2>"$work/ip.err" || skip "ip netns exec refused: $(head -1 "$work/ip.err")"

# --- impairment: netem on both ends (each impairs what it sends), else in-process on receive --
impaired=$(awk -v d="$delay" -v j="$jitter" -v l="$loss" -v r="$reorder" 'BEGIN { print (d + j + l + r > 0) }')
netem=()
[ "$(awk -v d="$delay" -v j="$jitter" 'BEGIN { print (d + j > 0) }')" -eq 0 ] || netem+=(delay "${delay}ms" "${jitter}ms")
[ "$loss" = 0 ] || netem+=(loss "${loss}%")
[ "$reorder" = 0 ] || netem+=(reorder "${reorder}%")
impair_args=()
how="none"
if [ "$impaired" -eq 1 ]; then
  if [ "$in_process" -eq 0 ] && command -v tc >/dev/null &&
     ip netns exec "$srv" tc qdisc add dev "$srv_if" root netem "${netem[@]}" 2>"$work/tc.err" &&
     ip netns exec "$cli" tc qdisc add dev "$cli_if" root netem "${netem[@]}" 2>"$work/tc.err"; then
    how="netem ${netem[*]} on both veth ends"
  else
    if [ "$in_process" -eq 1 ]; then why="--in-process given"
    elif ! command -v tc >/dev/null; then why="no 'tc'"
    else why="tc: $(head -1 "$work/tc.err")"; fi
    ip netns exec "$srv" tc qdisc del dev "$srv_if" root 2>/dev/null || true
    echo "netns-session: netem not used ($why); applying the impairment in-process on both sides instead"
    impair_args=(--loss "$(awk -v p="$loss" 'BEGIN { print p / 100 }')" --delay-ms "$delay"
                 --jitter-ms "$jitter" --reorder "$(awk -v p="$reorder" 'BEGIN { print p / 100 }')")
    how="in-process ${impair_args[*]} on both sides"
  fi
fi

# --- the session --------------------------------------------------------------------------
export VT_LOG=${VT_LOG:-warn}
: >"$work/server.log"  # exists before the background job opens it (the wait below reads it)
# Off loopback sessions are authenticated: serve writes a new key to the file, the client reads it.
ip netns exec "$srv" "$bin" serve --bind "$srv_addr:$port" --key "$work/session.key" --seconds "$(awk -v s="$seconds" 'BEGIN { print s + 30 }')" \
  --codecs "$codecs" "${impair_args[@]}" >"$work/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 100); do
  grep -q "^serving" "$work/server.log" && break
  kill -0 "$server_pid" 2>/dev/null || break
  sleep 0.1
done
if ! grep -q "^serving" "$work/server.log"; then
  echo "netns-session: the server did not start:" >&2; cat "$work/server.log" >&2; exit 1
fi

client_rc=0
ip netns exec "$cli" timeout -k 5 "$(awk -v s="$seconds" 'BEGIN { print int(s + 30) }')" \
  "$bin" client --connect "$srv_addr:$port" --bind "$cli_addr:0" --key "$work/session.key" --headless --glove none --seconds "$seconds" \
  --codecs "$codecs" "${impair_args[@]}" --record-csv "$work/client.csv" --json >"$work/client.json" 2>"$work/client.log" &
client_pid=$!
wait "$client_pid" || client_rc=$?
client_pid=""
stop "$server_pid"
server_pid="" server_rc=$stopped_rc

# --- checks -------------------------------------------------------------------------------
field() {  # a scalar of the client's JSON report, empty when absent
  sed -n "s/^ *\"$1\": *\"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}\$/\1/p" "$work/client.json" 2>/dev/null | head -1
}
show() { local v; v=$(field "$1"); echo "${v:-?}"; }
failures=()
check() { awk -v a="$2" -v b="$4" "BEGIN { exit !(a $3 b) }" || failures+=("$1 = $2, expected $3 $4"); }
[ "$client_rc" -eq 0 ] || failures+=("client exit code $client_rc")
[ "$server_rc" -eq 0 ] || failures+=("server exit code $server_rc")
poses=$(field poses_sent) played=$(field frames_played)
[ -n "$poses" ] && [ -n "$played" ] || failures+=("no client JSON report")
check poses_sent "${poses:-0}" ">" 0
check frames_played "${played:-0}" ">" 0
p50=$(field latency_p50_ms) p99=$(field latency_p99_ms)
# Impaired: the injected one-way delay + jitter, twice over, on top of the same bound.
bound=$(awk -v m="$max_p99" -v d="$delay" -v j="$jitter" 'BEGIN { print m + 2 * (d + j) }')
check latency_p99_ms "${p99:-1e9}" "<" "$bound"
# Recorder CSV: t_ns,sequence, then each actuator's level (0..1), then each one's frequency.
# Peak over the levels; the last row (the client's final silent frame) must be all zeros.
if [ -s "$work/client.csv" ]; then
  read -r rows peak last < <(awk -F, 'NR > 1 { n++; last = 0
      for (i = 3; i <= NF; i++) { v = $i < 0 ? -$i : $i + 0; if (v > last) last = v; if (i <= 2 + (NF - 2) / 2 && v > peak) peak = v } }
      END { print n + 0, peak + 0, last + 0 }' "$work/client.csv")
  check recorded_rows "$rows" ">" 0
  check peak_level "$peak" ">" 0  # the example trajectory touches within half a second
  check last_row_max "$last" "==" 0
else
  rows=0 peak=0 last="?"
  failures+=("no recorded output CSV")
fi

echo "netns-session: $srv_addr <-veth-> $cli_addr, ${seconds} s, codecs $codecs, impairment: $how"
echo "netns-session: poses_sent ${poses:-?} frames_received $(show frames_received) played ${played:-?}" \
     "concealed $(show frames_concealed) lost $(show frames_lost) late $(show frames_late)" \
     "reordered $(show frames_reordered) rejected $(show rejected_datagrams)"
echo "netns-session: codec $(show codec), latency p50 ${p50:-?} ms p99 ${p99:-?} ms (bound $bound)," \
     "playout delay $(show playout_delay_ms) ms; recorded $rows frames, peak level $peak, last row max $last"
grep -h "^server:" "$work/server.log" | sed 's/^/netns-session: /' || true
if [ ${#failures[@]} -gt 0 ]; then
  printf 'netns-session: FAILED: %s\n' "${failures[@]}" >&2
  echo "--- server log" >&2; cat "$work/server.log" >&2
  echo "--- client stderr" >&2; cat "$work/client.log" >&2
  echo "--- client stdout" >&2; cat "$work/client.json" >&2
  exit 1
fi
echo "netns-session: OK"
