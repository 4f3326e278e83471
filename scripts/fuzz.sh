#!/usr/bin/env bash
# Runs the libFuzzer targets (fuzz/) for a long time, one after the other, in the `fuzz-fast`
# build (UBSan without ASan: several times the executions per second, fuzz/README.md), each
# with its corpus kept in build-fuzz-fast/fuzz/corpus/ between runs (it only grows). Then the `fuzz` build
# (ASan + UBSan) replays every input of that corpus once, so whatever the fast runs reached is
# also checked for memory errors.
#
#   scripts/fuzz.sh                    every target for 1 hour
#   scripts/fuzz.sh 14400 gltf image   the named targets for 4 hours each
#   TWINLIGHT_FUZZ_RUNS=1000000 TWINLIGHT_FUZZ_TIMEOUT=60 scripts/fuzz.sh 0 gltf
#                                      1,000,000 executions, however long they take (the
#                                      goal's count), 60 s per input on a loaded machine
#
# A finding fails that target's test (or the replay); the input is in
# build-fuzz-fast/fuzz/crashes/ and becomes a regression test. The fuzzers run niced: the
# machine is shared.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-3600}"
shift || true
targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then targets=(gltf image settings albedo_db); fi

cd "$root"
for preset in fuzz-fast fuzz; do
  [ -f "build-$preset/build.ninja" ] || nice -n 19 cmake --preset "$preset"
  nice -n 19 cmake --build --preset "$preset"
done
regex="^fuzz\\.($(IFS='|'; echo "${targets[*]}"))\$"
TWINLIGHT_FUZZ_SECONDS="$seconds" ctest --test-dir build-fuzz-fast -R "$regex" -j1 --timeout 0 --output-on-failure

export LSAN_OPTIONS="suppressions=$root/tests/sanitizer/lsan.supp:print_suppressions=0"
for target in "${targets[@]}"; do
  echo "replaying build-fuzz-fast/fuzz/corpus/$target under ASan"
  # -runs=0: run every input of the corpus once, mutate nothing.
  nice -n 19 "build-fuzz/fuzz/fuzz_$target" -runs=0 -timeout=30 -rss_limit_mb=4096 \
    -artifact_prefix="build-fuzz/fuzz/crashes/$target-" "build-fuzz-fast/fuzz/corpus/$target"
done
