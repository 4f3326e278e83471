#!/usr/bin/env bash
# `twinlight tune` end to end on a small view: it finishes with a preset per budget that
# `render --settings` loads, resumes a finished folder without measuring again (and reaches the
# same choice), refuses another tune's folder, and two shards sharing a folder measure each run
# once between them. Prints "tune flow: ok" when every check holds.
#
#   tune_flow.sh TWINLIGHT SCENE OUT
set -euo pipefail
tl="$1" scene="$2" out="$3"
rm -rf "$out"
mkdir -p "$out"
fail() { echo "tune flow: $*" >&2; exit 1; }
# shellcheck source=/dev/null
source "$(dirname "$0")/tune_logs.sh"

small=(--scene "$scene" --size 48x27 --candidates 4 --rungs 2 --frames 4 --spp 16 --cache "$out/cache")

# Two rungs, then the two feature stages: a job array each on a cluster.
stages=$("$tl" tune "${small[@]}" --print-stage-count) || fail "--print-stage-count failed"
[ "$stages" = 4 ] || fail "--print-stage-count printed \`$stages' for two rungs (4 stages)"
"$tl" tune "${small[@]}" --budget 1.5x-legacy --budget 1000ms --out "$out/one" > "$out/one.log" 2>&1 \
  || { cat "$out/one.log"; fail "the tune failed"; }
cat "$out/one.log"
for f in tune.json report.html preset-rt-1.5x-legacy.json preset-rt-1000ms.json; do
  [ -s "$out/one/$f" ] || fail "no $f"
done
grep -q "budget 1.5x-legacy: c[0-9]* at" "$out/one.log" || fail "no choice printed for 1.5x-legacy"
# What the chosen point does not need is listed, with a verdict each.
grep -Eq "^    rt[A-Za-z]+: (no effect here: off|not needed here: off|needed: the error rises without it|kept: it saves time)" \
  "$out/one.log" || fail "no feature verdicts"

# The preset renders as it is.
"$tl" render --scene "$scene" --path rt --size 48x27 --settings "$out/one/preset-rt-1.5x-legacy.json" \
  --out "$out/preset.png" > "$out/render.log" 2>&1 || { cat "$out/render.log"; fail "the preset does not render"; }

# A finished folder resumes: nothing measured again, the same choice.
"$tl" tune "${small[@]}" --budget 1.5x-legacy --budget 1000ms --out "$out/one" > "$out/again.log" 2>&1 \
  || { cat "$out/again.log"; fail "the resumed tune failed"; }
read -r runs reused <<<"$(tune_runs_and_reused "$out/again.log")"
[ -n "${runs:-}" ] || fail "no run count"
[ "$runs" = "$reused" ] || fail "the resumed tune measured again ($runs runs, $reused found done)"
diff <(grep "budget" "$out/one.log") <(grep "budget" "$out/again.log") || fail "the resumed tune chose differently"

# Merged into another folder, the finished runs resume there: nothing measured again; a folder
# of another tune is refused.
"$tl" tune --merge "$out/one" --out "$out/merged" > "$out/merge.log" 2>&1 || { cat "$out/merge.log"; fail "the merge failed"; }
grep -q "merged [1-9][0-9]* measurement(s) from 1 folder(s)" "$out/merge.log" || { cat "$out/merge.log"; fail "nothing merged"; }
"$tl" tune "${small[@]}" --budget 1.5x-legacy --budget 1000ms --out "$out/merged" > "$out/merged_run.log" 2>&1 \
  || { cat "$out/merged_run.log"; fail "the tune in the merged folder failed"; }
read -r runs reused <<<"$(tune_runs_and_reused "$out/merged_run.log")"
[ -n "${runs:-}" ] || { cat "$out/merged_run.log"; fail "no run count"; }
[ "$runs" = "$reused" ] || fail "the merged folder measured $((runs - reused)) run(s) again"
mkdir -p "$out/other" && echo '{"other": true}' > "$out/other/tune-plan.json"
if "$tl" tune --merge "$out/one" --out "$out/other" > "$out/merge_other.log" 2>&1; then fail "merged into another tune's folder"; fi
grep -q "the plan of another tune" "$out/merge_other.log" || { cat "$out/merge_other.log"; fail "no clear refusal of the merge"; }

# Another tune's options into the same folder: refused, nothing lost.
if "$tl" tune "${small[@]}" --seed 2 --out "$out/one" > "$out/other.log" 2>&1; then fail "another tune's folder accepted"; fi
grep -q "another tune's folder" "$out/other.log" || { cat "$out/other.log"; fail "no clear refusal"; }

# Two shards sharing a folder, run in turns until the tune is finished: between them they measure
# each compare run exactly once, and the unsharded run that follows measures nothing.
measured=0
for _ in 1 2 3 4 5 6; do
  for i in 0 1; do
    [ -f "$out/shared/tune.json" ] && break
    "$tl" tune "${small[@]}" --chunk 2 --shard "$i/2" --out "$out/shared" > "$out/shard$i.log" 2>&1 \
      || { cat "$out/shard$i.log"; fail "shard $i failed"; }
    measured=$((measured + $(tune_measured "$out/shard$i.log")))
  done
done
[ -f "$out/shared/tune.json" ] || fail "the shards never finished"
"$tl" tune "${small[@]}" --chunk 2 --out "$out/shared" > "$out/after.log" 2>&1 || { cat "$out/after.log"; fail "the run after the shards failed"; }
read -r runs reused <<<"$(tune_runs_and_reused "$out/after.log")"
[ -n "${runs:-}" ] || { cat "$out/after.log"; fail "no run count"; }
[ "$runs" = "$reused" ] || fail "after the shards, $((runs - reused)) run(s) were measured again"
[ "$measured" = "$runs" ] || fail "the shards measured $measured runs for a tune of $runs"
echo "tune flow: ok ($runs compare runs, each measured once by the shards)"
