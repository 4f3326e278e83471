#!/usr/bin/env bash
# Runs the libFuzzer targets (fuzz/) for a long time, one after the other, through their
# CTests, each with its corpus kept in build-fuzz/fuzz/corpus/ between runs (it only grows).
#
#   scripts/fuzz.sh                    every target for 1 hour
#   scripts/fuzz.sh 14400 gltf image   the named targets for 4 hours each
#
# A finding fails that target's test; the input is in build-fuzz/fuzz/crashes/ and becomes a
# regression test. The fuzzers run niced: the machine is shared.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-3600}"
shift || true
targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then targets=(gltf image settings albedo_db); fi

cd "$root"
[ -f build-fuzz/build.ninja ] || cmake --preset fuzz
cmake --build --preset fuzz
regex="^fuzz\\.($(IFS='|'; echo "${targets[*]}"))\$"
TWINLIGHT_FUZZ_SECONDS="$seconds" ctest --test-dir build-fuzz -R "$regex" -j1 --timeout 0 --output-on-failure
