#!/usr/bin/env bash
# expect_error.sh STATUS REGEX [--fifo PATH]... -- COMMAND [ARGS...]
# Passes when COMMAND exits with STATUS and writes exactly one error line to stderr, that line
# starts with "twinlight: error: " and matches the extended regular expression REGEX.
# --fifo PATH creates a FIFO (nobody writes to it) before the command runs.
set -u
status="$1"
regex="$2"
shift 2
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
  case "$1" in
    --fifo) rm -f "$2"; mkfifo "$2" || exit 1; shift 2 ;;
    *) echo "expect_error.sh: unknown option $1" >&2; exit 1 ;;
  esac
done
shift  # --
err="$(mktemp)"
trap 'rm -f "$err"' EXIT
"$@" 2>"$err" >/dev/null
got=$?
cat "$err" >&2
errors="$(grep -c '^twinlight: error: ' "$err")"
if [ "$got" -ne "$status" ]; then
  echo "expect_error.sh: exit status $got, expected $status" >&2
  exit 1
fi
if [ "$errors" -ne 1 ]; then
  echo "expect_error.sh: $errors lines start with 'twinlight: error: ', expected exactly one" >&2
  exit 1
fi
if ! grep '^twinlight: error: ' "$err" | grep -Eq -- "$regex"; then
  echo "expect_error.sh: the error line does not match: $regex" >&2
  exit 1
fi
echo "expect_error.sh: exit status $got and the expected error line"
