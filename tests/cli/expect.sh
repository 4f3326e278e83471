#!/usr/bin/env bash
# expect.sh EXIT REGEX [--file FILE REGEX]... -- COMMAND...
# Runs COMMAND and passes when its exit status is EXIT and its output (stdout and stderr) matches
# the extended regular expression REGEX; each --file FILE REGEX also needs FILE to exist and
# match. Says what differed otherwise.
set -uo pipefail
expected_exit="$1" pattern="$2"
shift 2
files=()
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
  [ "$1" = "--file" ] || { echo "expect.sh: unexpected argument $1" >&2; exit 2; }
  files+=("$2" "$3")
  shift 3
done
shift  # --
output="$("$@" 2>&1)"
status=$?
printf '%s\n' "$output"
fail=0
if [ "$status" -ne "$expected_exit" ]; then
  echo "expect.sh: exit status $status, expected $expected_exit" >&2
  fail=1
fi
if ! grep -Eq -- "$pattern" <<<"$output"; then
  echo "expect.sh: output does not match /$pattern/" >&2
  fail=1
fi
for ((i = 0; i < ${#files[@]}; i += 2)); do
  file="${files[i]}" regex="${files[i + 1]}"
  if [ ! -f "$file" ]; then
    echo "expect.sh: $file was not written" >&2
    fail=1
  elif ! grep -Eq -- "$regex" "$file"; then
    echo "expect.sh: $file does not match /$regex/" >&2
    fail=1
  fi
done
exit "$fail"
