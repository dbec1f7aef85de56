#!/usr/bin/env bash
# Runs a semchain command that must fail on bad input and checks how it fails:
#   expect_error.sh PATTERN OUTPUT_PATH -- COMMAND ARGS...
# Passes when the command exits non-zero, prints exactly one line on stderr matching the
# extended regular expression PATTERN, and leaves nothing at OUTPUT_PATH ("-" skips that check).
set -u
pattern="$1"
output="$2"
shift 3
if [ "$output" != "-" ]; then
  rm -rf "$output" 2>/dev/null
fi
stderr_file="$(mktemp)"
trap 'rm -f "$stderr_file"' EXIT
"$@" >/dev/null 2>"$stderr_file" </dev/null
status=$?
if [ "$status" -eq 0 ]; then
  echo "FAIL: exit status 0 for: $*"
  exit 1
fi
if [ "$status" -ge 128 ]; then
  echo "FAIL: killed by signal $((status - 128)) (a crash) for: $*"
  cat "$stderr_file"
  exit 1
fi
lines="$(wc -l <"$stderr_file")"
if [ "$lines" -ne 1 ]; then
  echo "FAIL: expected one line on stderr, got $lines:"
  cat "$stderr_file"
  exit 1
fi
if ! grep -Eq -- "$pattern" "$stderr_file"; then
  echo "FAIL: stderr does not match '$pattern':"
  cat "$stderr_file"
  exit 1
fi
if [ "$output" != "-" ] && [ -e "$output" ]; then
  echo "FAIL: '$output' was written although the command failed"
  exit 1
fi
echo "ok: $(cat "$stderr_file")"
