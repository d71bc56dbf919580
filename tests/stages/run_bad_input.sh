#!/usr/bin/env bash
# run_bad_input.sh CODE PATTERN OUTPUT COMMAND [ARGS...]
# One case of the bad-input corpus: empties OUTPUT's folder, runs COMMAND (which writes to OUTPUT),
# and passes only when it exits with CODE, its combined output matches the extended regular
# expression PATTERN, and nothing at all was left in OUTPUT's folder (no artefact, no partial
# file, no probe table).
set -u
expected_code="$1"; pattern="$2"; output="$3"; shift 3
folder="$(dirname "$output")"
rm -rf "$folder"
output_text="$("$@" 2>&1)"; code=$?
printf '%s\n' "$output_text"
if [ "$code" != "$expected_code" ]; then
  echo "run_bad_input: exit code $code, expected $expected_code" >&2; exit 1
fi
if ! printf '%s\n' "$output_text" | grep -Eq -- "$pattern"; then
  echo "run_bad_input: output does not match: $pattern" >&2; exit 1
fi
if [ -d "$folder" ] && [ -n "$(ls -A "$folder")" ]; then
  echo "run_bad_input: the refused run left files in $folder:" >&2; ls -lA "$folder" >&2; exit 1
fi
echo "run_bad_input: exit code $code, message as expected, nothing written under $folder"
