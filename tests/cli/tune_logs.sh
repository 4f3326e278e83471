# What a `twinlight tune` process's log says it did; sourced by the tune tests (tune_flow.sh,
# cluster_slurm.sh), which count that every compare run of a tune was measured exactly once.

# tune_runs_and_reused LOG: "RUNS REUSED" from the line a finished tune ends with ("N compare
# run(s) (M found done)"); nothing when the log has no such line.
tune_runs_and_reused() {
  sed -n 's/.*: \([0-9]*\) compare run(s) (\([0-9]*\) found done).*/\1 \2/p' "$1" | head -n 1
}

# tune_measured LOG: the compare runs this process measured: a shard that stopped at an
# unfinished stage says "tune: measured N run(s)", a tune that finished says how many of its
# runs it found done. 0 when the log says neither.
tune_measured() {
  local line runs reused
  line=$(sed -n 's/^tune: measured \([0-9]*\) run(s).*/\1/p' "$1" | head -n 1)
  if [ -n "$line" ]; then
    echo "$line"
    return
  fi
  read -r runs reused <<<"$(tune_runs_and_reused "$1")"
  echo $((${runs:-0} - ${reused:-0}))
}
