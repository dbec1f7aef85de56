#!/usr/bin/env bash
# Second README command: installs what is missing, builds, and runs the whole test suite. CI
# (.ci/run) runs this on a fresh 2-core machine. The AddressSanitizer + UBSan build of the
# libraries and unit tests is scripts/test_sanitizers.sh: it runs clean (453 tests), but adds
# 10-14 minutes on CI's 2 cores (mostly building) to a Release run of 17-21 minutes, which does
# not fit CI's time budget (README, Development; issue 24).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
# No benchmark programs: no test runs them (scripts/build.sh alone still builds them).
"$root/scripts/build.sh" -DBUILD_BENCHMARKS=OFF
jobs="$(nproc 2>/dev/null || echo 2)"
cd "$root/build"
ctest --output-on-failure -j "$jobs"
