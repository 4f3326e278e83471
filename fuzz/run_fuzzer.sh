#!/usr/bin/env bash
# run_fuzzer.sh DEFAULT_SECONDS FUZZER [LIBFUZZER ARGS...]: the CTest of a fuzz target. It
# runs for $TWINLIGHT_FUZZ_SECONDS when set (scripts/fuzz.sh), else DEFAULT_SECONDS, niced
# (the machine is shared), and passes only when libFuzzer found nothing.
set -u
seconds="${TWINLIGHT_FUZZ_SECONDS:-$1}"
fuzzer="$2"
shift 2
# Leaks inside the system's libraries (OpenImageIO keeps an error string per failed open) are
# theirs, listed in tests/sanitizer/lsan.supp; a leak of Twinlight's own stops the run.
export LSAN_OPTIONS="suppressions=$(cd "$(dirname "$0")/.." && pwd)/tests/sanitizer/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
exec nice -n 19 "$fuzzer" -max_total_time="$seconds" "$@"
