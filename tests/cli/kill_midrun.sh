#!/usr/bin/env bash
# Crash safety: SIGKILL a command mid-run and check that its previous output is intact, that the
# next run succeeds, and that no half-written file shows inside the output.
#   kill_midrun.sh SEMCHAIN WORLD WORK_DIR
set -euo pipefail
semchain="$1"
world="$2"
work="$3"
rm -rf "$work"
mkdir -p "$work"
cd "$work"

checksums() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 sha256sum); }

# kill_and_check NAME OUT DELAY KILLED_COMMAND... -- NEXT_COMMAND...
# Runs the killed command (whose output is $out), kills it after $delay seconds, checks $out,
# then runs the next command (a shorter run to the same $out) and checks what it leaves.
kill_and_check() {
  local name="$1" out="$2" delay="$3"
  shift 3
  local killed=() next=()
  while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
    killed+=("$1")
    shift
  done
  shift
  next=("$@")
  local before
  before="$(checksums "$out")"
  "${killed[@]}" >/dev/null 2>&1 &
  local pid=$!
  sleep "$delay"
  if ! kill -0 "$pid" 2>/dev/null; then
    echo "FAIL: $name finished within ${delay} s; it must still run to be killed"
    exit 1
  fi
  kill -KILL "$pid"
  wait "$pid" 2>/dev/null || true
  if [ "$(checksums "$out")" != "$before" ]; then
    echo "FAIL: $name: the previous output changed after SIGKILL"
    exit 1
  fi
  # The next run neither trips over the leftovers nor shows them inside its output.
  if ! "${next[@]}" >/dev/null 2>err.txt; then
    echo "FAIL: $name: the run after the kill failed:"
    cat err.txt
    exit 1
  fi
  if find "$out" -name '*.tmp.*' -o -name '*.partial.*' | grep -q .; then
    echo "FAIL: $name: leftovers inside $out"
    exit 1
  fi
  if ls -d "$out".partial.* "$out".old.* >/dev/null 2>&1; then
    echo "FAIL: $name: the killed run's staging beside $out was not cleaned up"
    exit 1
  fi
  echo "ok: $name"
}

# The killed runs are long enough to be killed mid-run; the runs after them are short.
"$semchain" simulate --world "$world" --out run --seed 5 >/dev/null
kill_and_check simulate run 1 "$semchain" simulate --world "$world" --out run --seed 6 \
  -- "$semchain" simulate --world "$world" --out run --seed 5
"$semchain" slam --log run/log.clf --out map --particles 8 >/dev/null 2>&1
kill_and_check slam map 1 "$semchain" slam --log run/log.clf --out map --particles 60 \
  -- "$semchain" slam --log run/log.clf --out map --particles 8
"$semchain" semantic --run run --map map --out map >/dev/null
kill_and_check semantic map 0.3 "$semchain" semantic --run run --map map --out map \
  -- "$semchain" semantic --run run --map map --out map
"$semchain" dataset --out dataset --images 20 --seed 1 --threads 1 >/dev/null
kill_and_check dataset dataset 1 "$semchain" dataset --out dataset --images 400 --seed 2 \
  --threads 1 -- "$semchain" dataset --out dataset --images 20 --seed 2 --threads 1
