#!/usr/bin/env bash
# Runs a semchain command that must succeed and checks that it wrote its outputs:
#   expect_success.sh OUTPUT_PATH... -- COMMAND ARGS...
# Stale outputs are removed and their directories made first, so the test passes or fails the
# same when it runs alone.
set -u
outputs=()
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
  outputs+=("$1")
  shift
done
shift
for output in "${outputs[@]}"; do
  rm -rf "$output"
  mkdir -p "$(dirname "$output")"
done
if ! "$@" </dev/null; then
  echo "FAIL: non-zero exit for: $*"
  exit 1
fi
for output in "${outputs[@]}"; do
  if [ ! -s "$output" ]; then
    echo "FAIL: $output was not written by: $*"
    exit 1
  fi
done
