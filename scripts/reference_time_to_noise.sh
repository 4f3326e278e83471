#!/bin/bash
# Time to 1% noise of the reference, emitter sampling x adaptive sampling, in turns (ratios within
# one run: docs/performance.md). For each scene and each of the four settings it renders SPP
# samples a pixel and extrapolates the time to a relative standard error of 0.01 as
#   wall seconds x (RSE / 0.01)^2
# (RSE falls as 1/sqrt(samples) under either allocation once adaptive sampling's pilot has warmed
# up: docs/design/reference.md), then prints each setting's time against neither's.
#
#   scripts/reference_time_to_noise.sh [--spp N] [--size WxH] [--panel-box DIR]
#
# --panel-box: the folder scripts/cycles_panel_box.py wrote (Blender's panel box; left out if absent).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
twinlight=${TWINLIGHT:-$root/build/editor/twinlight}
spp=1024 size=64x48 panel=""
while [ $# -gt 0 ]; do
  case "$1" in
    --spp) spp=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --panel-box) panel=$2; shift 2 ;;
    *) echo "unknown argument: $1" >&2; exit 2 ;;
  esac
done
export LP_NUM_THREADS=${LP_NUM_THREADS:-2}
scenes=("cornell|--scene $root/content/cornell.gltf" "doorway_room|--scene $root/content/doorway_room.gltf --camera 0")
[ -n "$panel" ] && scenes+=("panel_box|--scene $panel/panel_box.gltf --materials diffuse --sky 0")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf "%-14s %-9s %-9s %9s %9s %12s %9s\n" scene emitters adaptive wall_s RSE time_to_1% vs_neither
for entry in "${scenes[@]}"; do
  name=${entry%%|*} args=${entry#*|}
  declare -A t1=()
  for es in false true; do
    for ad in 0 1; do
      # shellcheck disable=SC2086
      log=$("$twinlight" render --path reference --size "$size" --spp "$spp" $args \
        --set referenceEmitterSampling=$es --set referenceAdaptive=$ad --out "$out/$name.exr" 2>&1) || {
        echo "$log" >&2; exit 1; }
      wall=$(echo "$log" | sed -n 's/.* in \([0-9.]*\) s$/\1/p')
      rse=$(echo "$log" | sed -n 's/.*relative standard error \([0-9.]*\).*/\1/p')
      t1[$es$ad]=$(awk -v w="$wall" -v r="$rse" 'BEGIN { printf "%.0f", w * (r / 0.01) ^ 2 }')
      printf "%-14s %-9s %-9s %9s %9s %12s %9s\n" "$name" "$es" "$ad" "$wall" "$rse" "${t1[$es$ad]}" \
        "$(awk -v a="${t1[$es$ad]}" -v b="${t1[false0]}" 'BEGIN { printf "%.2fx", a / b }')"
    done
  done
  unset t1
done
