#!/usr/bin/env bash
# Builds the libraries, their unit tests and the fuzz replays with AddressSanitizer and
# UndefinedBehaviorSanitizer in build-asan/ (SEMCHAIN_SANITIZE=ON: no app, no end-to-end tests,
# no benchmarks, no ROS) and runs them; any sanitizer report fails the run. scripts/run_tests.sh
# runs it after the Release suite.
#   scripts/test_sanitizers.sh [CMAKE_ARGS...]
# SEMCHAIN_ASAN_JOBS sets the parallel compile and test jobs (default: one per core).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${SEMCHAIN_ASAN_JOBS:-$(nproc 2>/dev/null || echo 2)}"
build="$root/build-asan"
if ! command -v clang++ >/dev/null; then
  echo "test_sanitizers: clang++ not found (scripts/install_deps.sh installs it)" >&2
  exit 1
fi
# The cheapest build that still checks everything the tests run: clang (without GCC 12's false
# -Wmaybe-uninitialized inside std::regex and std::function when instrumenting), -O1 from the
# sanitizer flags, no debug information, and Debug's assertions (assert() and Eigen's) on. Warnings are not errors here: the Release build (scripts/build.sh)
# holds the code to -Werror.
cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG=-g0 -DSEMCHAIN_SANITIZE=ON -DSEMCHAIN_WERROR=OFF "$@"
cmake --build "$build" -j "$jobs"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# Reports name functions only when a symbolizer is found (Debian's llvm-14 names it with its
# version).
for symbolizer in llvm-symbolizer llvm-symbolizer-14; do
  if command -v "$symbolizer" >/dev/null; then
    export ASAN_SYMBOLIZER_PATH="$(command -v "$symbolizer")"
    break
  fi
done
# One test is left to the Release suite: it runs nine whole two-lap SLAM runs (four seeds with
# and without the pose graph, and one in the background), over ten minutes under the
# sanitizers; the code it runs, LoopClosureTest's other cases run too.
ctest --test-dir "$build" --output-on-failure -j "$jobs" \
  -E '^LoopClosureTest\.OnlineTheParticlesFollowTheClosedLoop$'
