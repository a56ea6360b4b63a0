#!/usr/bin/env bash
# run_expect.sh STATUS REGEX NEEDS -- COMMAND [ARGS...]
# Runs COMMAND, shows its output, and succeeds when it exits with STATUS (not by a signal) and a
# line of its stdout+stderr matches the extended regular expression REGEX. NEEDS is a file the
# command needs ('-' for none): when it is missing the test is skipped (exit 77).
set -u
status=$1 regex=$2 needs=$3
shift 3
[ "${1:-}" = "--" ] && shift
if [ "$needs" != "-" ] && [ ! -e "$needs" ]; then
  echo "skipped: $needs is not there"
  exit 77
fi
output=$("$@" 2>&1)
actual=$?
printf '%s\n' "$output"
if [ "$actual" -ne "$status" ]; then
  echo "run_expect: exit status $actual, expected $status"
  exit 1
fi
if ! printf '%s\n' "$output" | grep -Eq -- "$regex"; then
  echo "run_expect: no line matches: $regex"
  exit 1
fi
exit 0
