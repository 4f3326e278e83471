#!/usr/bin/env bash
# Runs a command with its stdout and its stderr in two files, so a test can judge each stream
# on its own (what is a result, what is a log), then prints both (stderr last) for the test
# runner's checks and exits with the command's exit code.
# Usage: streams.sh DIR COMMAND [ARGS...]   (writes DIR/stdout and DIR/stderr)
set -uo pipefail
dir=$1
shift
mkdir -p "$dir"
"$@" >"$dir/stdout" 2>"$dir/stderr"
status=$?
cat "$dir/stdout"
cat "$dir/stderr" >&2
exit "$status"
