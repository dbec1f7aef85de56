#!/usr/bin/env bash
# Fuzzes semchain's parsers (fuzz/README.md): scripts/fuzz.sh [TARGET|all] [SECONDS]
# Configures and builds build-fuzz/ with clang (SEMCHAIN_FUZZ=ON) when needed, then runs each
# target (all of them, one after the other, by default) for SECONDS (default 60). New inputs go
# to build-fuzz/corpus/TARGET (outside the repository); crashes, leaks, timeouts and
# out-of-memory inputs go to fuzz/crashes/TARGET, to be fixed and then replayed by
# ctest -R fuzz_replay_TARGET. Prints executions per second and coverage per target.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="${1:-all}"
seconds="${2:-60}"
build="${SEMCHAIN_FUZZ_BUILD_DIR:-$root/build-fuzz}"
jobs="${SEMCHAIN_FUZZ_JOBS:-2}"

mapfile -t all_targets < <(sed -n 's/^ *semchain_add_fuzz_target(\([a-z_0-9]*\) .*/\1/p' \
  "$root/fuzz/CMakeLists.txt")
if [ "$target" = all ]; then
  targets=("${all_targets[@]}")
elif printf '%s\n' "${all_targets[@]}" | grep -qx "$target"; then
  targets=("$target")
else
  echo "fuzz.sh: unknown target '$target' (known: ${all_targets[*]})" >&2
  exit 2
fi

if [ ! -f "$build/CMakeCache.txt" ]; then
  python=()
  if [ -x /usr/bin/python3 ]; then python=(-DPython3_EXECUTABLE=/usr/bin/python3); fi
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSEMCHAIN_FUZZ=ON -DSEMCHAIN_WERROR=ON "${python[@]}"
fi
# bag_import exists only where ROS 1 was found: 'all' leaves out what the build lacks.
mapfile -t built < <(cmake --build "$build" --target help | sed -n 's/^\.\.\. fuzz_\([a-z_0-9]*\).*/\1/p')
available=()
for t in "${targets[@]}"; do
  if printf '%s\n' "${built[@]}" | grep -qx "$t"; then
    available+=("$t")
  elif [ "$target" = all ]; then
    echo "fuzz.sh: leaving out $t (not in this build: it needs ROS 1)" >&2
  else
    echo "fuzz.sh: $t is not in this build (it needs ROS 1: scripts/install_deps.sh)" >&2
    exit 2
  fi
done
targets=("${available[@]}")
cmake --build "$build" -j "$jobs" --target "${targets[@]/#/fuzz_}"

# The targets write each input to a scratch file (fuzz/fuzz_input.h): on tmpfs that is about 15
# times faster than on disk.
if [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi

summary=()
failed=0
for t in "${targets[@]}"; do
  work="$build/corpus/$t"
  crashes="$root/fuzz/crashes/$t"
  mkdir -p "$work" "$crashes"
  dict=()
  if [ -f "$root/fuzz/dict/$t.dict" ]; then dict=(-dict="$root/fuzz/dict/$t.dict"); fi
  log="$build/fuzz-$t.log"
  echo "== fuzz_$t for ${seconds}s (log: $log)"
  # -timeout: an input taking 10 s is a hang; -rss_limit_mb: one using 2 GB is a crash.
  status=0
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$crashes/" "${dict[@]}" \
    "$work" "$root/fuzz/corpus/$t" >"$log" 2>&1 || status=$?
  final="$(grep -E '^#[0-9]+' "$log" | tail -n 1 || true)"
  execs="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)"
  result="ok"
  if [ "$status" -ne 0 ]; then
    result="FAILED (exit $status): $(grep -m1 -E 'ERROR: |SUMMARY: |runtime error' "$log" || true)"
    failed=1
  fi
  line="$t: ${execs:-?} exec/s; final: ${final:-none}; $result"
  echo "$line"
  summary+=("$line")
done
echo "== summary"
printf '%s\n' "${summary[@]}"
exit "$failed"
