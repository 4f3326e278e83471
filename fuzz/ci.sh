#!/usr/bin/env bash
# The fuzz targets in the default suite, in two steps:
#
#   fuzz/ci.sh build BUILD_DIR         scripts/setup.sh: configure a clang build of the fuzz
#                                      targets (ASan + UBSan, as the `fuzz` preset) in BUILD_DIR
#                                      and build only them (the first time: minutes)
#   fuzz/ci.sh run BUILD_DIR SECONDS   the suite's `fuzz.bounded` (tests/CMakeLists.txt): run
#                                      each target for SECONDS from its seeds and replay every
#                                      input a fuzzer ever found (fuzz/regressions/)
#
# `run` builds nothing: a tree that is missing or older than the sources is one clear error
# naming the command that builds it, so the suite's time is the fuzzers', not a compiler's.
# Passes only when nothing was found. The long runs are scripts/fuzz.sh's; this keeps every
# change to an input reader under a fuzzer in CI.
set -euo pipefail
usage() {
  echo "usage: fuzz/ci.sh build BUILD_DIR | fuzz/ci.sh run BUILD_DIR SECONDS" >&2
  exit 2
}
[ $# -ge 2 ] || usage
mode="$1"
build="$2"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

configure() {
  local seconds="$1"
  for tool in clang clang++; do
    if ! command -v "$tool" >/dev/null; then
      echo "fuzz/ci.sh: $tool not found: the fuzz targets need clang and libFuzzer (scripts/setup.sh installs clang libclang-rt-dev)" >&2
      exit 1
    fi
  done
  # The same compiler cache as the release preset where there is one (a fresh CI clone has an
  # empty one: then it costs nothing and saves nothing).
  local launcher=()
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
}

case "$mode" in
  build)
    [ $# -eq 2 ] || usage
    configure 30
    start=$(date +%s)
    cmake --build "$build" --target fuzzers
    echo "fuzz/ci.sh: fuzz targets built in $(( $(date +%s) - start )) s"
    ;;
  run)
    [ $# -eq 3 ] || usage
    seconds="$3"
    case "$seconds" in
      '' | *[!0-9]*) echo "fuzz/ci.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2 ;;
    esac
    if [ ! -f "$build/build.ninja" ]; then
      echo "fuzz/ci.sh: no fuzz build in $build: scripts/setup.sh builds it (or: fuzz/ci.sh build $build)" >&2
      exit 1
    fi
    # Up to date, or nothing runs: ninja's dry run lists what it would rebuild.
    stale="$(cmake --build "$build" --target fuzzers -- -n | grep -c -E '(Building|Linking) ' || true)"
    if [ "$stale" != "0" ]; then
      echo "fuzz/ci.sh: the fuzz build in $build is older than the sources ($stale steps): scripts/setup.sh rebuilds it (or: fuzz/ci.sh build $build)" >&2
      exit 1
    fi
    configure "$seconds"  # the seconds are the tests' argument: no object depends on them
    cd "$build"
    # Each target's own CTest (run_fuzzer.sh: niced, libFuzzer's final statistics printed) and
    # its regression replay, one at a time.
    status=0
    ctest -L fuzz --output-on-failure --no-tests=error || status=$?
    # What each target did (libFuzzer's final line, from CTest's full log of the run).
    awk '/^[0-9]+\/[0-9]+ Testing: fuzz\./ { test = $3 } /^Done [0-9]+ runs in/ { print "fuzz/ci.sh: " test ": " $2 " executions in " $5 " s" }' \
      Testing/Temporary/LastTest.log || true
    exit "$status"
    ;;
  *) usage ;;
esac
