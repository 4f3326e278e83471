#!/usr/bin/env bash
# `twinlight tune --stop-with-parent` (how the editor starts its tunes) stops when the process
# that started it ends: a parent starts a tune and exits 3 s later; the tune must end within
# 30 s, say why, and leave its folder to resume. Prints "tune stops with its parent: ok".
#
#   tune_stops_with_parent.sh TWINLIGHT SCENE OUT
set -euo pipefail
tl="$1" scene="$2" out="$3"
rm -rf "$out"
mkdir -p "$out"
fail() { echo "tune stops with its parent: $*" >&2; [ -f "$out/tune.log" ] && tail -n 5 "$out/tune.log" >&2; exit 1; }

# Far more work than 3 s: the parent ends while it runs.
bash -c '"$1" tune --scene "$2" --size 64x36 --candidates 32 --rungs 2 --frames 32 --spp 64 --budget 1000ms \
           --out "$3/tune" --cache "$3/cache" --stop-with-parent >"$3/tune.log" 2>&1 &
         echo $! >"$3/pid"
         sleep 3' parent "$tl" "$scene" "$out"
pid=$(cat "$out/pid")
for _ in $(seq 60); do
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.5
done
if kill -0 "$pid" 2>/dev/null; then
  kill "$pid"
  fail "still running 30 s after its parent ended"
fi
grep -q "the process that started this tune (pid [0-9]*) has ended: stopped" "$out/tune.log" || fail "no word of why it stopped"
[ -f "$out/tune/tune-plan.json" ] || fail "no folder left to resume"
[ ! -f "$out/tune/tune.json" ] || fail "it finished instead of stopping: the check proves nothing"
echo "tune stops with its parent: ok"
