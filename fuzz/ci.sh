#!/usr/bin/env bash
# fuzz/ci.sh BUILD_DIR SECONDS: the default suite's `fuzz.bounded` (tests/CMakeLists.txt).
# Configures a clang build of the fuzz targets (ASan + UBSan, as the `fuzz` preset) in
# BUILD_DIR, builds only them, runs each for SECONDS from its seeds and replays every input
# a fuzzer ever found (fuzz/regressions/). Passes only when nothing was found. The long runs
# are scripts/fuzz.sh's; this keeps every change to an input reader under a fuzzer in CI.
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: fuzz/ci.sh BUILD_DIR SECONDS" >&2
  exit 2
fi
build="$1"
seconds="$2"
case "$seconds" in
  '' | *[!0-9]*) echo "fuzz/ci.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2 ;;
esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
for tool in clang clang++; do
  if ! command -v "$tool" >/dev/null; then
    echo "fuzz/ci.sh: $tool not found: the fuzz targets need clang and libFuzzer (scripts/setup.sh installs clang libclang-rt-dev)" >&2
    exit 1
  fi
done

# The same compiler cache as the release preset where there is one (a fresh CI clone has an
# empty one: then it costs nothing and saves nothing).
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# Debug information only as line tables: enough for the sanitizers' stack traces, a fraction
# of -g's compile time and disk.
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  -DTWINLIGHT_FUZZ=ON -DTWINLIGHT_BUILD_TESTS=OFF -DTWINLIGHT_WERROR=ON \
  -DTWINLIGHT_FUZZ_SECONDS="$seconds" "${launcher[@]}" >/dev/null
start=$(date +%s)
cmake --build "$build" --target fuzzers
echo "fuzz/ci.sh: fuzz targets built in $(( $(date +%s) - start )) s"
cd "$build"
# Each target's own CTest (run_fuzzer.sh: niced, libFuzzer's final statistics printed) and
# its regression replay, one at a time.
status=0
ctest -L fuzz --output-on-failure --no-tests=error || status=$?
# What each target did (libFuzzer's final line, from CTest's full log of the run).
awk '/^[0-9]+\/[0-9]+ Testing: fuzz\./ { test = $3 } /^Done [0-9]+ runs in/ { print "fuzz/ci.sh: " test ": " $2 " executions in " $5 " s" }' \
  Testing/Temporary/LastTest.log || true
exit "$status"
