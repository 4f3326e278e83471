#!/bin/bash
# Runs a command as a user would and checks what the user would see: the exit code, that the
# output (stdout and stderr together) matches PASS, that it does not match FAIL (optional; an
# empty FAIL checks nothing), and that no Vulkan validation message and, for an expected
# success, no `twinlight: error` appeared. Regular expressions are POSIX extended; `.` spans
# lines. CTest's PASS_REGULAR_EXPRESSION ignores the exit code: this does not.
#   expect_exit.sh EXPECTED_EXIT_CODE PASS [FAIL] -- COMMAND [ARGS...]
set -u
expected=$1
pass=$2
fail=""
shift 2
if [ "$1" != "--" ]; then
  fail=$1
  shift
fi
shift  # --
output=$("$@" 2>&1)
code=$?
printf '%s\n' "$output"
status=0
if [ "$code" != "$expected" ]; then
  echo "expect_exit: exit code $code, expected $expected"
  status=1
fi
if ! [[ $output =~ $pass ]]; then
  echo "expect_exit: the output does not match: $pass"
  status=1
fi
if [ -n "$fail" ] && [[ $output =~ $fail ]]; then
  echo "expect_exit: the output matches what it must not: $fail"
  status=1
fi
if [[ $output == *"validation: "* || $output == *"Vulkan validation error"* ]]; then
  echo "expect_exit: Vulkan validation reported messages"
  status=1
fi
if [ "$expected" = 0 ] && [[ $output == *"twinlight: error"* ]]; then
  echo "expect_exit: an error was reported"
  status=1
fi
exit $status
