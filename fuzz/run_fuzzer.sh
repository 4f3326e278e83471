#!/usr/bin/env bash
# run_fuzzer.sh DEFAULT_SECONDS FUZZER [LIBFUZZER ARGS...]: the CTest of a fuzz target. It
# runs for $TWINLIGHT_FUZZ_SECONDS when set (scripts/fuzz.sh), else DEFAULT_SECONDS, niced
# (the machine is shared), and passes only when libFuzzer found nothing. With
# TWINLIGHT_FUZZ_RUNS=N it stops after N executions instead (a goal counted in executions; the
# time a count takes depends on the machine's load): `TWINLIGHT_FUZZ_SECONDS=0` then lifts the
# time limit. TWINLIGHT_FUZZ_TIMEOUT overrides the per-input timeout (10 s) for loaded machines.
set -u
seconds="${TWINLIGHT_FUZZ_SECONDS:-$1}"
fuzzer="$2"
shift 2
# Leaks inside the system's libraries (OpenImageIO keeps an error string per failed open) are
# theirs, listed in tests/sanitizer/lsan.supp; a leak of Twinlight's own stops the run.
export LSAN_OPTIONS="suppressions=$(cd "$(dirname "$0")/.." && pwd)/tests/sanitizer/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
limits=(-max_total_time="$seconds")
if [ -n "${TWINLIGHT_FUZZ_RUNS:-}" ]; then limits+=(-runs="$TWINLIGHT_FUZZ_RUNS"); fi
# libFuzzer takes the last of a repeated flag: this one wins over the CTest's -timeout=10.
if [ -n "${TWINLIGHT_FUZZ_TIMEOUT:-}" ]; then set -- "$@" -timeout="$TWINLIGHT_FUZZ_TIMEOUT"; fi
exec nice -n 19 "$fuzzer" "${limits[@]}" "$@"
