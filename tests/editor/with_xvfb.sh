#!/usr/bin/env bash
# Runs a command on its own Xvfb server (1600x900, 24 bits) and exits with the command's
# exit code. xvfb-run is not used: it replaces the command's exit code with 5 when removing
# its temporary directory fails after the command ended (seen here), so a test could not
# tell the editor's exit code from its own clean-up.
# Usage: with_xvfb.sh COMMAND [ARGS...]
set -uo pipefail
work=$(mktemp -d)
Xvfb -displayfd 3 -screen 0 1600x900x24 -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
xvfb=$!
stop() {
  kill "$xvfb" 2>/dev/null
  wait "$xvfb" 2>/dev/null
  rm -rf "$work"
}
trap stop EXIT
# Xvfb writes its display number once it accepts connections.
for _ in $(seq 300); do
  [ -s "$work/display" ] && break
  kill -0 "$xvfb" 2>/dev/null || break
  sleep 0.1
done
if [ ! -s "$work/display" ]; then
  echo "with_xvfb.sh: Xvfb did not start:" >&2
  cat "$work/xvfb.log" >&2
  exit 1
fi
DISPLAY=":$(head -n 1 "$work/display")" "$@"
