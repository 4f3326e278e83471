#!/usr/bin/env bash
# The README's test command: set up if needed, build, run the suite with CTest. GPU tests run
# on lavapipe (or TWINLIGHT_DEVICE) with the Vulkan validation layers on.
#
#   scripts/test.sh            everything (CI's .ci/run): unit, GPU, command-line and editor
#                              tests, the slow ones (the GPU suite's long tests, the cluster and
#                              packaging tests) and the bounded fuzz runs
#   scripts/test.sh --quick    the development loop: the unit tests (one process), the GPU suite
#                              without its slow tests and the command-line tests without the
#                              cluster and packaging ones (labels unit, gpu, cli; not `slow`);
#                              no editor tests, and the fuzz targets are not built
#
# Further arguments go to ctest (e.g. -R compare, --repeat until-fail:3).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tier=()
setup=()
if [ "${1:-}" = "--quick" ]; then
  shift
  tier=(-L "^(unit|gpu|cli)$" -LE slow)
  setup=(--no-fuzz)
fi
"$root/scripts/setup.sh" "${setup[@]}"
# llvmpipe: one worker per core (measured: more gains nothing, see docs/performance.md).
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
cd "${TWINLIGHT_BUILD_DIR:-$root/build}"
# One test per core at a time: each renders on lavapipe's own LP_NUM_THREADS workers, and the
# long ones (the GPU suite's process, the fuzzers) overlap the short ones.
ctest --output-on-failure --timeout 900 -j "$(nproc)" "${tier[@]}" "$@"
