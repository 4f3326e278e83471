#!/bin/bash
# Job arrays on a real scheduler, on this one machine: a single-node Slurm from Debian's
# packages (slurmctld + slurmd, munge for authentication) configured and started here in a
# scratch folder with its own ports, key and sockets, and stopped on exit. Through
# deploy/slurm/submit.sh it runs
#   - a 4-task bake array (task ids 1-4: not from 0) and its dependent merge job, whose
#     database must hold exactly the rows of a one-process bake;
#   - a 3-task compare sweep (2 scenes x their cameras = 3 views, 3 configurations) and its
#     merge, whose report must hold exactly the figures of an unsharded run, with each view's
#     reference rendered by one task only;
#   - a tune as one 2-task array per stage, each after the last, and its closing job: between
#     them the tasks measure every compare run of the tune exactly once, and the closing job
#     measures nothing and writes the preset.
# Where the daemons cannot start (packages missing, no permission), it says why and runs the
# same task and merge scripts as local processes with the variables Slurm would set.
# Usage: cluster_slurm.sh TWINLIGHT CONTENT_DIR DEPLOY_DIR WORK_DIR
set -euo pipefail
tl=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
content=$2 deploy=$3 work=$4
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$work" && mkdir -p "$work"
work=$(cd "$work" && pwd)
export TWINLIGHT=$tl
# shellcheck source=/dev/null
source "$here/tune_logs.sh"

bake_scenes=("$content/cornell.gltf" "$content/atrium.gltf" "$content/grove.gltf" "$content/banners.gltf")
echo '[{"name": "legacy-coarse", "path": "legacy", "settings": {"legacyConeDivisor": 2}}]' >"$work/variants.json"
sweep=(--scene "$content/cornell.gltf" "$content/grove.gltf" --cameras scene --size 32x24 --spp 16 --frames 2
  --paths "direct,legacy" --settings "$work/variants.json")
# A budget every configuration meets at this size: the closing job's exit status is then the
# tune's, not the timing's.
tune=(--scene "$content/cornell.gltf" --size 32x18 --candidates 4 --rungs 1 --frames 4 --spp 8 --budget 1000ms
  --cache "$work/tune_cache")
# One job array per stage: twinlight says how many (--rungs 1: the rung and two feature stages).
stages=$("$tl" tune "${tune[@]}" --print-stage-count)
[ "$stages" = 3 ] || { echo "tune --print-stage-count printed \`$stages' for one rung (3 stages)"; exit 1; }
# Options twinlight refuses are refused before anything is queued: exit 2, no folder made.
if "$deploy/slurm/submit.sh" tune 2 "$work/tune_bad_options" "${tune[@]}" --frames 1 >"$work/tune_bad_options.log" 2>&1; then
  cat "$work/tune_bad_options.log"; echo "submit.sh accepted a tune of 1 frame"; exit 1
fi
if ! grep -q "nothing submitted" "$work/tune_bad_options.log" || [ -e "$work/tune_bad_options" ]; then
  cat "$work/tune_bad_options.log"; echo "submit.sh: no clear refusal, or a folder made for a refused tune"; exit 1
fi

# ---- the single-process results everything is compared with -----------------------------
"$tl" bake --scene "${bake_scenes[@]}" --db "$work/single.db" >"$work/single_bake.log" 2>&1
"$tl" compare "${sweep[@]}" --out "$work/single_sweep" --cache "$work/cache_single" >"$work/single_sweep.log" 2>&1
echo "one process: $(grep -c . <<<"$(sqlite3 "$work/single.db" 'SELECT key FROM baked')") keys baked, sweep of 3 views measured"

# ---- a private single-node Slurm ------------------------------------------------------------
# Unix socket paths are short (108 bytes): the daemons' scratch lives under /tmp.
scratch=$(mktemp -d "${TMPDIR:-/tmp}/tl-slurm.XXXXXX")
slurm_up=0
stop_slurm() {
  if [ "$slurm_up" = 1 ]; then
    scancel --quiet --user="$(id -un)" 2>/dev/null || true
    for _ in $(seq 20); do [ -z "$(squeue -h 2>/dev/null)" ] && break; sleep 0.5; done
    scontrol shutdown 2>/dev/null || true
  fi
  # Whatever did not stop by itself, by the pid it recorded (only the daemons started here).
  for pidfile in "$scratch/slurmctld.pid" "$scratch/slurmd.pid" "$scratch/munge/munged.pid"; do
    [ -f "$pidfile" ] || continue
    pid=$(cat "$pidfile")
    for _ in $(seq 20); do kill -0 "$pid" 2>/dev/null || break; sleep 0.5; done
    kill "$pid" 2>/dev/null || true
  done
  rm -rf "$scratch"
}
trap stop_slurm EXIT

# A TCP port nothing listens on (from /proc, no tools needed).
port_in_use() {
  local hex
  hex=$(printf '%04X' "$1")
  awk -v p=":$hex" '$4 == "0A" && substr($2, length($2) - 4) == p { found = 1 } END { exit !found }' \
    /proc/net/tcp /proc/net/tcp6 2>/dev/null
}
free_port_pair() {
  local p
  for _ in $(seq 50); do
    p=$((20000 + RANDOM % 40000))
    if ! port_in_use "$p" && ! port_in_use $((p + 1)); then echo "$p"; return 0; fi
  done
  return 1
}

# Starts munged, slurmctld and slurmd; on failure sets `reason` and returns 1.
reason=""
start_slurm() {
  local cmd
  for cmd in munged munge slurmctld slurmd sbatch scontrol squeue sinfo scancel; do
    command -v "$cmd" >/dev/null || { reason="\`$cmd' is not installed (scripts/setup.sh installs slurm-wlm and munge)"; return 1; }
  done
  local user port cpus memory
  user=$(id -un)
  port=$(free_port_pair) || { reason="no free TCP port pair found"; return 1; }
  mkdir -p "$scratch/munge" "$scratch/state" "$scratch/spool" "$scratch/log"
  chmod 755 "$scratch" "$scratch/munge"  # munged wants its socket folder reachable by all
  head -c 1024 /dev/urandom >"$scratch/munge/munge.key"
  chmod 400 "$scratch/munge/munge.key"
  if ! munged --socket="$scratch/munge/munge.socket" --key-file="$scratch/munge/munge.key" \
      --pid-file="$scratch/munge/munged.pid" --log-file="$scratch/munge/munged.log" \
      --seed-file="$scratch/munge/munged.seed" >"$scratch/munge/start.log" 2>&1; then
    reason="munged did not start: $(tail -n 2 "$scratch/munge/start.log" "$scratch/munge/munged.log" 2>/dev/null | tr '\n' ' ')"
    return 1
  fi
  if ! munge -n -S "$scratch/munge/munge.socket" | unmunge -S "$scratch/munge/munge.socket" >/dev/null 2>&1; then
    reason="munge cannot encode and decode a credential"
    return 1
  fi
  # The node as slurmd sees it (it drains a node configured with more than it has).
  cpus=$(nproc)
  memory=$(awk '/MemTotal/ { print int($2 / 1024 / 2) }' /proc/meminfo)
  cat >"$scratch/slurm.conf" <<EOF
ClusterName=twinlight-test
SlurmctldHost=localhost
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$scratch/munge/munge.socket
StateSaveLocation=$scratch/state
SlurmdSpoolDir=$scratch/spool
SlurmctldPidFile=$scratch/slurmctld.pid
SlurmdPidFile=$scratch/slurmd.pid
SlurmctldLogFile=$scratch/log/slurmctld.log
SlurmdLogFile=$scratch/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
DependencyParameters=kill_invalid_depend
ReturnToService=2
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=30 State=UP
EOF
  export SLURM_CONF="$scratch/slurm.conf"
  if ! slurmctld -f "$SLURM_CONF" >"$scratch/log/slurmctld.start" 2>&1; then
    reason="slurmctld did not start: $(tail -n 3 "$scratch/log/slurmctld.start" "$scratch/log/slurmctld.log" 2>/dev/null | tr '\n' ' ')"
    return 1
  fi
  slurm_up=1
  if ! slurmd -f "$SLURM_CONF" -N localhost >"$scratch/log/slurmd.start" 2>&1; then
    reason="slurmd did not start: $(tail -n 3 "$scratch/log/slurmd.start" "$scratch/log/slurmd.log" 2>/dev/null | tr '\n' ' ')"
    return 1
  fi
  local state=""
  for _ in $(seq 60); do
    state=$(sinfo -h -n localhost -o %T 2>/dev/null || true)
    [ "$state" = idle ] && return 0
    sleep 0.5
  done
  reason="the node did not become idle in 30 s (state \`$state'): $(tail -n 3 "$scratch/log/slurmd.log" 2>/dev/null | tr '\n' ' ')"
  return 1
}

if start_slurm; then
  echo "slurm: single-node cluster up ($(slurmctld -V), node localhost: $(nproc) CPUs)"
  # The scheduler's limit is the job's; this one keeps a stuck job from holding the suite.
  timeout 900 "$deploy/slurm/submit.sh" --first 1 --wait bake 4 "$work/bake" "${bake_scenes[@]}" ||
    { tail -n 20 "$work"/bake/logs/*.log; echo "the bake array or its merge failed"; exit 1; }
  timeout 900 "$deploy/slurm/submit.sh" --wait compare 3 "$work/sweep" "${sweep[@]}" --cache "$work/cache_shards" ||
    { tail -n 20 "$work"/sweep/logs/*.log; echo "the compare array or its merge failed"; exit 1; }
  timeout 900 "$deploy/slurm/submit.sh" --wait tune 2 "$work/tune" "${tune[@]}" ||
    { tail -n 20 "$work"/tune/logs/*.log; echo "the tune's arrays or its closing job failed"; exit 1; }
  # A task that fails cancels what waits for it, and --wait says so (it reads the merge job's
  # state: a job cancelled before it ran did not complete).
  if timeout 300 "$deploy/slurm/submit.sh" --wait tune 2 "$work/tune_refused" "${tune[@]}" --scene "$work/no_such_scene.gltf" \
      >"$work/tune_refused.log" 2>&1; then
    cat "$work/tune_refused.log"; echo "submit.sh --wait exited 0 although every task failed"; exit 1
  fi
  grep -q "did not complete" "$work/tune_refused.log" || { cat "$work/tune_refused.log"; echo "no word of the cancelled merge"; exit 1; }
  ran="on Slurm"
else
  echo "slurm: cannot start a local cluster here: $reason"
  echo "slurm: running the same task and merge scripts as local processes instead"
  unset SLURM_CONF
  # What Slurm sets for task ID of an array FIRST..LAST.
  run_array() {  # FIRST LAST MODE OUT ARGS...
    local first=$1 last=$2 mode=$3 out=$4 id pids=() status=0
    shift 4
    mkdir -p "$out/logs" "$out/shards"
    for ((id = first; id <= last; ++id)); do
      SLURM_ARRAY_TASK_ID=$id SLURM_ARRAY_TASK_MIN=$first SLURM_ARRAY_TASK_MAX=$last SLURM_ARRAY_TASK_STEP=1 \
        SLURM_ARRAY_TASK_COUNT=$((last - first + 1)) \
        "$deploy/slurm/task.sbatch" "$mode" "$out" "$@" >"$out/logs/$mode-local_$id.log" 2>&1 &
      pids+=($!)
    done
    for pid in "${pids[@]}"; do wait "$pid" || status=1; done
    [ "$status" = 0 ] || { cat "$out"/logs/*.log; echo "an array task failed"; return 1; }
    "$deploy/slurm/merge.sbatch" "$mode" "$out" "$first" $((last - first + 1)) >"$out/logs/$mode-merge-local.log" 2>&1 ||
      { cat "$out/logs/$mode-merge-local.log"; return 1; }
  }
  run_array 1 4 bake "$work/bake" "${bake_scenes[@]}"
  run_array 0 2 compare "$work/sweep" "${sweep[@]}" --cache "$work/cache_shards"
  # The tune: its stages one array after another, then the closing job.
  mkdir -p "$work/tune/logs"
  for ((stage = 1; stage <= stages; ++stage)); do
    pids=()
    for id in 0 1; do
      SLURM_ARRAY_TASK_ID=$id SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=1 SLURM_ARRAY_TASK_STEP=1 SLURM_ARRAY_TASK_COUNT=2 \
        "$deploy/slurm/task.sbatch" tune "$work/tune" "${tune[@]}" >"$work/tune/logs/tune-$stage-local_$id.log" 2>&1 &
      pids+=($!)
    done
    for pid in "${pids[@]}"; do wait "$pid" || { cat "$work"/tune/logs/*.log; echo "a tune task failed"; exit 1; }; done
  done
  "$deploy/slurm/merge.sbatch" tune "$work/tune" 0 2 "${tune[@]}" >"$work/tune/logs/tune-merge-local.log" 2>&1 ||
    { cat "$work/tune/logs/tune-merge-local.log"; echo "the tune's closing job failed"; exit 1; }
  ran="as local processes"
fi

# ---- the bake: the merged database holds exactly the one-process bake's rows --------------
rows() {
  sqlite3 "$1" "SELECT key, printf('%!.17g|%!.17g|%!.17g|%!.17g', r, g, b, coverage), view_coverage,
                printf('%!.17g', view_variance), baker_version, label FROM baked ORDER BY key;
                SELECT key, r, g, b, label FROM overrides ORDER BY key;"
}
for id in 1 2 3 4; do
  grep -q "shard $((id - 1))/4: Slurm array task $id (ids from 1 in steps of 1, 4 tasks)" "$work"/bake/logs/bake-*_"$id".log ||
    { cat "$work"/bake/logs/bake-*_"$id".log; echo "task $id did not bake shard $((id - 1))/4"; exit 1; }
done
[ -f "$work/bake/albedo.db" ] || { cat "$work"/bake/logs/*merge*.log; echo "the merge job wrote no database"; exit 1; }
rows "$work/single.db" >"$work/single_rows.txt"
rows "$work/bake/albedo.db" >"$work/merged_rows.txt"
[ -s "$work/single_rows.txt" ] || { echo "the one-process bake baked nothing"; exit 1; }
diff "$work/single_rows.txt" "$work/merged_rows.txt" || { echo "the merged database differs from one bake"; exit 1; }
echo "bake: 4 array tasks $ran, merged: $(wc -l <"$work/merged_rows.txt") rows identical to one process"

# ---- the sweep: one report, figure for figure the unsharded one's -------------------------
[ -f "$work/sweep/report/report.json" ] || { cat "$work"/sweep/logs/*.log; echo "the merge job wrote no report"; exit 1; }
/usr/bin/env python3 "$here/compare_figures.py" "$work/single_sweep" "$work/sweep/report"
# Each view's reference was rendered (not read from the shared cache) by exactly one task.
rendered=$(cat "$work"/sweep/logs/compare-*_[0-9]*.log | grep -c 'reference: 16 spp$' || true)
[ "$rendered" = 3 ] || { echo "expected 3 references rendered by the tasks, found $rendered"; exit 1; }
echo "compare: 3 array tasks $ran, merged: figures identical to one process, each reference rendered once"

# ---- the tune: every run measured once, by the arrays; the closing job only writes ---------
for f in tune.json report.html preset-rt-1000ms.json; do
  [ -s "$work/tune/tune/$f" ] || { cat "$work"/tune/logs/*.log; echo "the tune wrote no $f"; exit 1; }
done
closing=$(cat "$work"/tune/logs/tune-merge-*.log)
read -r runs done_before <<<"$(tune_runs_and_reused <(echo "$closing"))"
if [ -z "${runs:-}" ] || [ "$runs" != "$done_before" ]; then
  echo "$closing"
  echo "the closing job measured $((${runs:-0} - ${done_before:-0})) run(s) the arrays should have"
  exit 1
fi
measured=0
for log in "$work"/tune/logs/tune-[0-9]-*.log; do
  measured=$((measured + $(tune_measured "$log")))
done
[ "$measured" = "$runs" ] || { echo "the tune's tasks measured $measured run(s) between them, for $runs"; exit 1; }
echo "tune: $runs compare runs over $stages stages of 2 array tasks $ran, each measured once, and the closing job wrote the preset"
