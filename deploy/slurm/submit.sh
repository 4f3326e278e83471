#!/bin/bash
# Submits a Twinlight bake, compare sweep or tune to Slurm: a job array of TASKS tasks, each
# running `twinlight ... --shard auto`, and a merge job that starts once every task has succeeded
# (sbatch --dependency=afterok). Prints the job ids.
#
#   submit.sh [--first ID] [--wait] bake    TASKS OUT_DIR SCENE...
#   submit.sh [--first ID] [--wait] compare TASKS OUT_DIR [COMPARE OPTIONS...]
#   submit.sh [--first ID] [--wait] tune    TASKS OUT_DIR [TUNE OPTIONS...]
#
# bake:    OUT_DIR/shards/bake-<id>.db per task, merged into OUT_DIR/albedo.db
# compare: OUT_DIR/shards/compare-<id>/ per task (one folder per view of the sweep it measured),
#          merged into OUT_DIR/report/ (report.json, report.html, each view's report)
# tune:    one folder, OUT_DIR/tune/, that every task shares. A stage of a tune needs the one
#          before it finished, so each stage is an array of its own after the last (twinlight
#          tune --print-stage-count says how many; it checks the options before anything is
#          queued), and the last job writes the presets, tune.json and report.html (and measures
#          whatever the arrays left, so a stage count that is off costs time, never a result).
# Logs go to OUT_DIR/logs/. --first sets the array's first task id (default 0; ids need not
# start at 0, twinlight reads SLURM_ARRAY_TASK_MIN). --wait blocks until the merge job ends
# (its state read every second) and exits 0 only if it completed: a failed task cancels the
# merge (DependencyParameters kill_invalid_depend) or leaves it pending with reason
# DependencyNeverSatisfied, and either way --wait exits 1.
# Environment: TWINLIGHT, the twinlight binary (default: twinlight on PATH);
# TWINLIGHT_SBATCH_ARGS, extra sbatch options for every job (e.g. "--partition=render
# --gres=gpu:1" on GPU nodes, "--cpus-per-task=8" for lavapipe on CPU nodes).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
usage() {
  echo "usage: submit.sh [--first ID] [--wait] bake TASKS OUT_DIR SCENE..." >&2
  echo "       submit.sh [--first ID] [--wait] compare TASKS OUT_DIR [COMPARE OPTIONS...]" >&2
  echo "       submit.sh [--first ID] [--wait] tune TASKS OUT_DIR [TUNE OPTIONS...]" >&2
  exit 2
}

first=0
wait_for_merge=0
while [ $# -gt 0 ]; do
  case $1 in
    --first) first=${2:?--first needs an id}; shift 2 ;;
    --wait) wait_for_merge=1; shift ;;
    *) break ;;
  esac
done
[ $# -ge 3 ] || usage
mode=$1 tasks=$2 out=$3
shift 3
case $mode in bake | compare | tune) ;; *) echo "submit.sh: unknown mode \`$mode' (bake, compare or tune)" >&2; exit 2 ;; esac
if ! [[ $tasks =~ ^[0-9]+$ ]] || [ "$tasks" -lt 1 ]; then
  echo "submit.sh: TASKS \`$tasks' is not a count >= 1" >&2
  exit 2
fi
[[ $first =~ ^[0-9]+$ ]] || { echo "submit.sh: --first \`$first' is not an array task id" >&2; exit 2; }
[ "$mode" = compare ] || [ $# -ge 1 ] || { echo "submit.sh: bake needs at least one scene" >&2; exit 2; }

if [ "$mode" = tune ]; then
  # twinlight knows how many stages these options make, and checks them before anything is queued.
  stages=$("${TWINLIGHT:-twinlight}" tune "$@" --print-stage-count) ||
    { echo "submit.sh: the tune's options were refused (above); nothing submitted" >&2; exit 2; }
  [[ $stages =~ ^[0-9]+$ ]] || { echo "submit.sh: \`twinlight tune --print-stage-count' printed \`$stages'" >&2; exit 2; }
fi

mkdir -p "$out/logs" "$out/shards"
out=$(cd "$out" && pwd)  # the jobs may start in another directory
read -r -a extra <<<"${TWINLIGHT_SBATCH_ARGS:-}"
last=$((first + tasks - 1))
if [ "$mode" = tune ]; then
  array=""
  for ((stage = 1; stage <= stages; ++stage)); do
    array=$(sbatch --parsable "${extra[@]}" --job-name="twinlight-tune-$stage" --array="$first-$last" \
      ${array:+--dependency="afterok:$array"} --output="$out/logs/tune-$stage-%A_%a.log" \
      "$here/task.sbatch" tune "$out" "$@")
    array=${array%%;*}
    echo "submitted tune stage $stage array job $array (tasks $first-$last)"
  done
else
  array=$(sbatch --parsable "${extra[@]}" --job-name="twinlight-$mode" --array="$first-$last" \
    --output="$out/logs/$mode-%A_%a.log" "$here/task.sbatch" "$mode" "$out" "$@")
  array=${array%%;*}  # --parsable prints "id[;cluster]"
  echo "submitted $mode array job $array (tasks $first-$last)"
fi
tune_args=()
[ "$mode" = tune ] && tune_args=("$@")
merge=$(sbatch --parsable "${extra[@]}" --job-name="twinlight-$mode-merge" \
  --dependency="afterok:$array" --output="$out/logs/$mode-merge-%j.log" \
  "$here/merge.sbatch" "$mode" "$out" "$first" "$tasks" "${tune_args[@]}")
merge=${merge%%;*}
echo "submitted $mode merge job $merge (after every task of $array succeeded)"
if [ "$wait_for_merge" = 1 ]; then
  # Watches the merge job's state every second until it ends. Not sbatch --wait, which polls
  # after 2 s, 8 s and then every 32 s (a merge that ends a moment after a poll was reported half
  # a minute late), exits 0 for a merge job that never ran, and waits for ever on one left
  # pending because a task it waited for failed (without kill_invalid_depend).
  state="" unknown=0
  while :; do
    info=$(scontrol show job -o "$merge" 2>/dev/null || true)
    state=$(grep -o 'JobState=[A-Z_]*' <<<"$info" || true)
    case "$state" in
      JobState=PENDING) if grep -q 'Reason=DependencyNeverSatisfied' <<<"$info"; then break; fi ;;
      JobState=RUNNING | JobState=CONFIGURING | JobState=COMPLETING | JobState=SUSPENDED | JobState=REQUEUED | \
        JobState=RESIZING | JobState=SIGNALING | JobState=STAGE_OUT | JobState=STOPPED) ;;
      "") # the controller did not answer (or forgot the job): a few tries before giving up
        unknown=$((unknown + 1))
        [ "$unknown" -lt 30 ] || break ;;
      *) break ;;  # COMPLETED, FAILED, CANCELLED, TIMEOUT, NODE_FAIL, OUT_OF_MEMORY, ...
    esac
    sleep 1
  done
  if [ "$state" != JobState=COMPLETED ]; then
    echo "submit.sh: the merge job $merge did not complete (${state:-its state is unknown}): see $out/logs/" >&2
    exit 1
  fi
fi
