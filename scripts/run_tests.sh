#!/usr/bin/env bash
# Second README command: installs what is missing, builds, and runs the whole test suite, then
# the AddressSanitizer + UndefinedBehaviorSanitizer suite (scripts/test_sanitizers.sh: the
# libraries, their unit tests and the fuzz replays, built with clang at -O1 in build-asan/). CI
# (.ci/run) runs this on a fresh 2-core machine; any failure or sanitizer report fails the run.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
# No benchmark programs: no test runs them (scripts/build.sh alone still builds them).
"$root/scripts/build.sh" -DBUILD_BENCHMARKS=OFF
jobs="$(nproc 2>/dev/null || echo 2)"
(cd "$root/build" && ctest --output-on-failure -j "$jobs")
# SEMCHAIN_SANITIZERS=0 skips the sanitizer suite (a quicker local run; CI runs both).
if [ "${SEMCHAIN_SANITIZERS:-1}" != "0" ]; then
  "$root/scripts/test_sanitizers.sh"
fi
