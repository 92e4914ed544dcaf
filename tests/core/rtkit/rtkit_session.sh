#!/usr/bin/env bash
# Runs a command as an unprivileged user next to a RealtimeKit daemon on a private D-Bus system
# bus (dbus-daemon + a polkit stand-in that authorizes everything + rtkit-daemon), all started
# here and stopped on exit. The machine's own system bus is never touched.
#
#   tests/core/rtkit/rtkit_session.sh [--no-rtkit] [--user USER] -- COMMAND [ARGS...]
#
# --no-rtkit: the same private bus without the daemon (the "refused" baseline).
# Exits 77 (ctest: skipped) with a message when it cannot start: not root (rtkit-daemon must
# start as root to keep CAP_SYS_NICE), or dbus-daemon / rtkit-daemon / python3-dbus missing.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
user=nobody
rtkit=1
while [ $# -gt 0 ]; do
  case "$1" in
    --no-rtkit) rtkit=0; shift ;;
    --user) user="$2"; shift 2 ;;
    --) shift; break ;;
    *) echo "rtkit_session.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
[ $# -gt 0 ] || { echo "rtkit_session.sh: no command given" >&2; exit 2; }

skip() { echo "SKIP: $*" >&2; exit 77; }
[ "$(id -u)" = 0 ] || skip "needs root to start rtkit-daemon (it keeps CAP_SYS_NICE and drops to user rtkit)"
command -v dbus-daemon >/dev/null || skip "dbus-daemon missing (Debian package dbus-daemon)"
rtkitd=/usr/libexec/rtkit-daemon
[ -x "$rtkitd" ] || skip "$rtkitd missing (Debian package rtkit)"
/usr/bin/python3 -c 'import dbus, gi' 2>/dev/null || skip "python3-dbus / python3-gi missing"
id "$user" >/dev/null 2>&1 || skip "no user $user"
id rtkit >/dev/null 2>&1 || skip "no user rtkit (Debian package rtkit creates it)"

dir="$(mktemp -d /tmp/vt-rtkit.XXXXXX)"
chmod 755 "$dir"
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$dir"
}
trap cleanup EXIT

cat > "$dir/bus.conf" <<CONF
<!DOCTYPE busconfig PUBLIC "-//freedesktop//DTD D-Bus Bus Configuration 1.0//EN"
 "http://www.freedesktop.org/standards/dbus/1.0/busconfig.dtd">
<busconfig>
  <type>system</type>
  <listen>unix:path=$dir/system_bus_socket</listen>
  <auth>EXTERNAL</auth>
  <policy context="default">
    <allow user="*"/>
    <allow own="*"/>
    <allow send_destination="*"/>
    <allow receive_sender="*"/>
  </policy>
</busconfig>
CONF
dbus-daemon --config-file="$dir/bus.conf" --nofork --nopidfile 2>"$dir/dbus.log" &
pids+=($!)
export DBUS_SYSTEM_BUS_ADDRESS="unix:path=$dir/system_bus_socket"
for _ in $(seq 50); do [ -S "$dir/system_bus_socket" ] && break; sleep 0.1; done
[ -S "$dir/system_bus_socket" ] || skip "private dbus-daemon did not start: $(cat "$dir/dbus.log")"

has_owner() {
  dbus-send --system --print-reply --dest=org.freedesktop.DBus /org/freedesktop/DBus \
    org.freedesktop.DBus.NameHasOwner "string:$1" 2>/dev/null | grep -q "boolean true"
}
wait_owner() {
  for _ in $(seq 50); do has_owner "$1" && return 0; sleep 0.1; done
  return 1
}
if [ "$rtkit" = 1 ]; then
  /usr/bin/python3 "$here/fake_polkit.py" 2>"$dir/polkit.log" &
  pids+=($!)
  wait_owner org.freedesktop.PolicyKit1 || skip "polkit stand-in did not start: $(cat "$dir/polkit.log")"
  # Its log goes through a pipe: the daemon limits its own file size to 0 (RLIMIT_FSIZE).
  "$rtkitd" --stderr --no-canary 2> >(cat >"$dir/rtkit.log") &
  pids+=($!)
  wait_owner org.freedesktop.RealtimeKit1 || skip "rtkit-daemon did not start: $(cat "$dir/rtkit.log")"
fi
status=0
runuser -u "$user" -- env DBUS_SYSTEM_BUS_ADDRESS="$DBUS_SYSTEM_BUS_ADDRESS" "$@" || status=$?
if [ "$rtkit" = 1 ] && [ "$status" != 0 ]; then
  echo "rtkit-daemon log:" >&2
  cat "$dir/rtkit.log" >&2
fi
exit "$status"
