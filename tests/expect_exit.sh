#!/bin/sh
# Runs a command and passes when it exits with the expected code and its
# output (stdout and stderr) matches the expected extended regular expression.
# Usage: expect_exit.sh CODE REGEX COMMAND [ARGS...]
code=$1
pattern=$2
shift 2
output=$("$@" 2>&1)
status=$?
printf '%s\n' "$output"
if [ "$status" -ne "$code" ]; then
  echo "expected exit code $code, got $status" >&2
  exit 1
fi
if ! printf '%s\n' "$output" | grep -Eq -- "$pattern"; then
  echo "output does not match: $pattern" >&2
  exit 1
fi
