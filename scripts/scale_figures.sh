#!/bin/bash
# Scale figures: the generated 100,000-instance scene `sprawl` (tl_content_gen --sprawl, written
# to a scratch folder when measured, never committed), measured in one run:
#   - its load time (parse + upload, as `bake` reports it) and glTF size;
#   - the RT path's top-level instances for the ground-level view (camera `street`): with the
#     default GI blend distance and with Metro's 250 m (distance culling follows it);
#   - bake time per key and the database's size;
#   - the 1,000-key bake as 4 array tasks (`--shard auto` with the variables Slurm sets, run
#     one after another here and timed each) plus their merge, against one process: the
#     makespan on 4 nodes (the slowest task + the merge) and the total machine time, as ratios.
# Usage: scripts/scale_figures.sh [BUILD_DIR] [WORK_DIR] [INSTANCES] [KEYS]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build=${1:-$root/build}
work=${2:-${TMPDIR:-/tmp}/twinlight-scale}
instances=${3:-100000}
keys=${4:-1000}
tl="$build/editor/twinlight"
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
rm -rf "$work" && mkdir -p "$work"
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'; }
field() { sed -n "s/.*$1 \\([0-9.]*\\).*/\\1/p" | head -n 1; }

"$build/content/tl_content_gen" --sprawl "$work" "$instances" "$keys" >/dev/null
scene="$work/sprawl.gltf"
echo "scene: $instances instances of $keys mesh/material combinations, $(du -k "$scene" | cut -f1) KB of glTF + $(du -k "$work/sprawl.bin" | cut -f1) KB of buffers"

# The ground-level view: the default blend distance (beyond the whole scene), Metro's 250 m
# with the legacy far field beyond it, and 250 m fading to the sky.
configs=('{}' '{"rtBlendDistance": 250}' '{"rtBlendDistance": 250, "rtFarLegacy": false}')
for k in 0 1 2; do
  "$tl" bench --scene "$scene" --camera 0 --path rt --size 320x180 --frames 3 --warmup 1 --set "${configs[$k]}" \
    --json "$work/bench_$k.json" >/dev/null 2>&1
  python3 - "$work/bench_$k.json" "${configs[$k]}" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
f = r["figures"]
ms = {p["pass"]: p["median"] for p in r["passes"]}
print(f"street view {sys.argv[2]}: {int(f['tlasInstances'])} of {int(f['sceneInstances'])} instances in the TLAS "
      f"(legacy far field: {'yes' if f['farFieldLegacy'] else 'no'}); GPU ms at 320x180: accel.simplified.tlas {ms['accel.simplified.tlas']:.1f}, "
      f"rt.trace {ms['rt.trace']:.1f}, gbuffer {ms['gbuffer']:.0f}, shadow.sun {ms['shadow.sun']:.0f}, "
      f"frame {r['frame']['median']:.0f}")
EOF
done

# One process.
start=$(now)
"$tl" bake --scene "$scene" --db "$work/single.db" >"$work/single.log" 2>/dev/null
single=$(since "$start")
load=$(field "scene loaded in" <"$work/single.log")
baked=$(sed -n 's/.*: baked \([0-9]*\),.*/\1/p' "$work/single.log")
bytes=$(sed -n 's/.*overrides, \([0-9]*\) bytes/\1/p' "$work/single.log")
bake_seconds=$(sed -n 's/.*failed 0 in \([0-9.]*\) s.*/\1/p' "$work/single.log")
echo "one process: $baked keys in $single s wall (scene load $load s, bake $bake_seconds s: $(awk -v s="$bake_seconds" -v k="$baked" 'BEGIN { printf "%.1f", 1000 * s / k }') ms per key); database $bytes bytes ($(awk -v b="$bytes" -v k="$baked" 'BEGIN { printf "%.0f", b / k }') bytes per key)"

# Four array tasks, as Slurm would start them (ids 0-3), then the merge.
slowest=0 total=0
for id in 0 1 2 3; do
  start=$(now)
  SLURM_ARRAY_TASK_ID=$id SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_COUNT=4 \
    "$tl" bake --shard auto --scene "$scene" --db "$work/shard$id.db" >"$work/shard$id.log" 2>/dev/null
  t=$(since "$start")
  echo "  task $id: $(sed -n 's/.*: \([0-9]*\) keys in shard.*/\1/p' "$work/shard$id.log") keys in $t s (scene load $(field "scene loaded in" <"$work/shard$id.log") s)"
  slowest=$(awk -v a="$slowest" -v b="$t" 'BEGIN { print (b > a ? b : a) }')
  total=$(awk -v a="$total" -v b="$t" 'BEGIN { print a + b }')
done
start=$(now)
"$tl" bake --db "$work/merged.db" --merge "$work"/shard{0,1,2,3}.db >/dev/null 2>&1
merge=$(since "$start")
rows() { sqlite3 "$1" "SELECT key, printf('%!.17g %!.17g %!.17g %!.17g', r, g, b, coverage), view_coverage, label FROM baked ORDER BY key"; }
if diff <(rows "$work/single.db") <(rows "$work/merged.db") >/dev/null; then same="identical to one process"; else same="DIFFERENT from one process"; fi
echo "4 array tasks: merge $merge s, merged database $same"
awk -v single="$single" -v slowest="$slowest" -v total="$total" -v merge="$merge" 'BEGIN {
  printf "makespan on 4 nodes (slowest task + merge) %.2f s: %.2fx one process (%.2f s)\n", slowest + merge, single / (slowest + merge), single
  printf "machine time (4 tasks + merge) %.2f s: %.2fx one process\n", total + merge, (total + merge) / single }'
