# Sourced by the CLI test scripts: prints the ADDR:PORT a `vtouching serve --bind 127.0.0.1:0`
# reported in its log (it binds port 0, so parallel tests never clash), waiting up to 10 s.
# Usage: address=$(server_address LOG) || ...
server_address() {
  local address
  for _ in $(seq 100); do
    address=$(sed -n 's/^serving .* on \([0-9.]*:[0-9]*\|\[[0-9a-f:.]*\]:[0-9]*\) .*/\1/p' "$1")
    [ -n "$address" ] && { echo "$address"; return 0; }
    sleep 0.1
  done
  return 1
}
