#!/usr/bin/env bash
# run_expect.sh CODE PATTERN COMMAND [ARGS...]
# Runs COMMAND and passes only when it exits with CODE and its combined output matches the
# extended regular expression PATTERN (empty PATTERN: any output).
set -u
expected_code="$1"; pattern="$2"; shift 2
output="$("$@" 2>&1)"; code=$?
printf '%s\n' "$output"
if [ "$code" != "$expected_code" ]; then
  echo "run_expect: exit code $code, expected $expected_code" >&2; exit 1
fi
if [ -n "$pattern" ] && ! printf '%s\n' "$output" | grep -Eq -- "$pattern"; then
  echo "run_expect: output does not match: $pattern" >&2; exit 1
fi
echo "run_expect: exit code $code and output as expected"
