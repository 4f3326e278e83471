#!/usr/bin/env bash
# The README's run command: set up if needed, build, then run Twinlight on the default
# scene (or the scene given as the first argument).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
exec "${TWINLIGHT_BUILD_DIR:-$root/build}/editor/twinlight" "$@"
