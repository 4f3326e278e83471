#!/usr/bin/env bash
# The README's test command: set up if needed, build, run the whole suite with CTest.
# GPU tests run on lavapipe (or TWINLIGHT_DEVICE) with the Vulkan validation layers on.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
# llvmpipe: one worker per core (measured: more gains nothing, see docs/performance.md).
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
cd "${TWINLIGHT_BUILD_DIR:-$root/build}"
ctest --output-on-failure --timeout 900 "$@"
