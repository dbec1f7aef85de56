#!/usr/bin/env bash
# Builds the libraries, their unit tests and the fuzz replays with AddressSanitizer and
# UndefinedBehaviorSanitizer in build-asan/ (SEMCHAIN_SANITIZE=ON: no app, no end-to-end tests,
# no benchmarks, no ROS) and runs them; any sanitizer report fails the run.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc 2>/dev/null || echo 2)"
build="$root/build-asan"
python=()
if [ -x /usr/bin/python3 ]; then python=(-DPython3_EXECUTABLE=/usr/bin/python3); fi
# Debug keeps assert() and Eigen's assertions on; the sanitizer flags add -O1. Warnings are not
# errors here: GCC 12 reports false -Wmaybe-uninitialized inside std::regex and std::function
# when instrumenting; the Release build (scripts/build.sh) holds the code to -Werror.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Debug -DSEMCHAIN_SANITIZE=ON \
  -DSEMCHAIN_WERROR=OFF "${python[@]}" "$@"
cmake --build "$build" -j "$jobs"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
ctest --test-dir "$build" --output-on-failure -j "$jobs"
