#!/bin/bash
# Runs a bake or a compare sweep on Kubernetes: applies the Indexed Job, waits until it is
# complete (or failed: then stops, the merge never runs), applies the merge Job and waits for
# it, and prints its log. Kubernetes has no job dependencies: this script is the dependency.
#   run.sh bake|compare [KUBECTL OPTIONS...]     e.g. run.sh bake --namespace render
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mode=${1:?usage: run.sh bake|compare [KUBECTL OPTIONS...]}
shift
case $mode in bake | compare) ;; *) echo "run.sh: unknown mode \`$mode' (bake or compare)" >&2; exit 2 ;; esac

# Waits for a Job to end; returns 0 when it completed, 1 when it failed.
#   wait_job JOB [KUBECTL OPTIONS...]
wait_job() {
  local job=$1 state
  shift
  while true; do
    state=$(kubectl "$@" get "job/$job" -o jsonpath='{.status.conditions[?(@.status=="True")].type}')
    case " $state " in
      *" Complete "*) return 0 ;;
      *" Failed "*) echo "job $job failed" >&2; return 1 ;;
    esac
    sleep 10
  done
}

kubectl "$@" delete --ignore-not-found "job/twinlight-$mode" "job/twinlight-$mode-merge"
kubectl "$@" apply -f "$here/$mode-job.yaml"
wait_job "twinlight-$mode" "$@"
kubectl "$@" apply -f "$here/$mode-merge-job.yaml"
status=0
wait_job "twinlight-$mode-merge" "$@" || status=1
kubectl "$@" logs "job/twinlight-$mode-merge"
exit "$status"
