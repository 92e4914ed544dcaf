#!/bin/sh
# usage: expect_failure.sh PATTERN... -- COMMAND [ARGS...]
# Passes when COMMAND exits non-zero without crashing (no signal) and prints exactly one stderr
# line containing every PATTERN.
patterns=""
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
  patterns="$patterns
$1"
  shift
done
[ "$1" = "--" ] || { echo "expect_failure.sh: missing -- before the command" >&2; exit 2; }
shift
err=$(mktemp)
trap 'rm -f "$err"' EXIT
"$@" >/dev/null 2>"$err"
status=$?
cat "$err"
if [ "$status" -eq 0 ]; then echo "FAIL: expected a non-zero exit" >&2; exit 1; fi
if [ "$status" -gt 128 ]; then echo "FAIL: killed by signal $((status - 128))" >&2; exit 1; fi
lines=$(wc -l <"$err")
if [ "$lines" -ne 1 ]; then echo "FAIL: expected one stderr line, got $lines" >&2; exit 1; fi
echo "$patterns" | while IFS= read -r p; do
  [ -z "$p" ] && continue
  grep -qF -- "$p" "$err" || { echo "FAIL: stderr lacks '$p'" >&2; exit 1; }
done || exit 1
echo "ok: exit $status"
