#!/usr/bin/env bash
# The randomized interior corpus (content/generator/corpus.h): draws interiors from a seed —
# a fresh one each run unless --seed is given, printed first so a run can be repeated — and
# measures every path against the reference on each of their views with `twinlight compare`,
# which prints one table: per view and path the mean ratio and relMSE_norm, and the share of
# views that meet each accuracy goal (docs/accuracy.md). Exit 3 when a goal is missed.
#
#   scripts/corpus.sh [--seed N] [--count N] [--first N] [--size WxH] [--frames N] [--spp N]
#                     [--paths rt,legacy] [--out DIR] [--shard i/N] [-- extra compare options]
#
# On a cluster, run it once per shard with the same --seed (`--shard i/N`, or `--shard auto`
# in a Slurm array) and merge the folders with `twinlight compare --merge` (docs/cluster.md).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TWINLIGHT_BUILD_DIR:-$root/build}"
seed="" count=64 first=0 size=96x54 frames=64 spp=1024 paths=rt,legacy out="" shard=""
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seed) seed="$2"; shift 2 ;;
    --count) count="$2"; shift 2 ;;
    --first) first="$2"; shift 2 ;;
    --size) size="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --spp) spp="$2"; shift 2 ;;
    --paths) paths="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --shard) shard="$2"; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,13p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "corpus.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
if [ -z "$seed" ]; then seed="$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')"; fi
case "$seed" in ''|*[!0-9]*) echo "corpus.sh: --seed takes a whole number, not $seed" >&2; exit 2 ;; esac
out="${out:-$root/out/corpus/$seed}"
echo "corpus seed $seed: interiors $first..$((first + count - 1)) into $out"

gen="$build/content/tl_content_gen"
tl="$build/editor/twinlight"
if [ ! -x "$gen" ] || [ ! -x "$tl" ]; then
  echo "corpus.sh: build the project first (scripts/setup.sh): $gen or $tl is missing" >&2
  exit 1
fi
"$gen" --corpus "$out/scenes" "$seed" "$first" "$count"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
args=(compare --scene "$out"/scenes/interior_*.gltf --cameras scene --paths "$paths" --materials diffuse
      --size "$size" --frames "$frames" --spp "$spp" --goals --out "$out/report")
if [ -n "$shard" ]; then args+=(--shard "$shard"); fi
set +e
"$tl" "${args[@]}" "${extra[@]}"
status=$?
set -e
echo "corpus seed $seed: report in $out/report/report.html (exit $status)"
exit $status
