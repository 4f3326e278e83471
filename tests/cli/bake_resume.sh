#!/usr/bin/env bash
# The albedo database survives a bake killed at any moment: SIGKILL inside a batch's
# transaction (after its rows are written, before the commit) and SIGKILL from outside at
# an arbitrary time both leave a valid database; the next bake skips what was committed and
# ends with exactly what an uninterrupted bake writes. Shards merged equal one bake.
# Usage: bake_resume.sh TWINLIGHT SCENE WORKDIR
# Every run's output goes to stdout (the test runner fails on any validation message or
# unexpected error in it) and every run but the killed ones must exit 0.
set -euo pipefail
tl=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work"

rows() { "$tl" bake --db "$1" --list | tail -n +2; }  # without the revision header

"$tl" bake --scene "$scene" --db whole.db 2>&1
rows whole.db >whole.txt
total=$(grep -c '^baked' whole.txt)
echo "uninterrupted: $total keys"

# 1. Killed inside the third batch's transaction.
set +e
TWINLIGHT_TEST_KILL_IN_BATCH=2 "$tl" bake --scene "$scene" --db killed.db --batch 2 2>&1
rc=$?
set -e
[ "$rc" -eq 137 ] || { echo "expected death by SIGKILL (137), got $rc"; exit 1; }
committed=$(rows killed.db | grep -c '^baked' || true)
[ "$committed" -eq 4 ] || { echo "expected the 2 committed batches (4 keys) after the kill, found $committed"; exit 1; }
out=$("$tl" bake --scene "$scene" --db killed.db --batch 2 2>&1)
echo "$out"
echo "$out" | grep -q "skipped 4 (up to date)" || { echo "resume did not skip the committed keys: $out"; exit 1; }
rows killed.db | diff whole.txt - || { echo "resumed database differs from the uninterrupted one"; exit 1; }
echo "killed in a transaction, resumed: identical"

# 2. Killed from outside at arbitrary moments, one key per transaction, until it finishes.
for delay in 0.5 0.6 0.65 0.7 0.75 0.8; do
  "$tl" bake --scene "$scene" --db outside.db --batch 1 2>&1 &
  pid=$!
  sleep "$delay"
  kill -9 "$pid" 2>/dev/null || true
  # Killed (137), or finished before the kill: then it must have succeeded.
  rc=0
  wait "$pid" 2>/dev/null || rc=$?
  [ "$rc" -eq 0 ] || [ "$rc" -eq 137 ] || { echo "bake killed after ${delay} s exited $rc"; exit 1; }
  if [ -e outside.db ]; then  # valid after every kill (or not created yet): --list must succeed
    listing=$(rows outside.db) || { echo "the database is not readable after a kill at ${delay} s"; exit 1; }
    echo "  killed after ${delay} s: $(grep -c '^baked' <<<"$listing" || true) keys committed"
  fi
done
"$tl" bake --scene "$scene" --db outside.db --batch 1 2>&1
rows outside.db | diff whole.txt - || { echo "database after outside kills differs"; exit 1; }
echo "killed from outside, resumed: identical"

# 3. Shards merged equal one bake.
for i in 0 1 2; do "$tl" bake --scene "$scene" --db "shard$i.db" --shard "$i/3" 2>&1; done
"$tl" bake --db merged.db --merge shard0.db shard1.db shard2.db 2>&1
rows merged.db | diff whole.txt - || { echo "merged shards differ from one bake"; exit 1; }
echo "3 shards merged: identical"
