#!/usr/bin/env bash
# Second README command: installs what is missing, builds, and runs the whole test suite; then
# builds the libraries and unit tests again with AddressSanitizer and UndefinedBehaviorSanitizer
# and runs those (scripts/test_sanitizers.sh). CI (.ci/run) runs this on a fresh 2-core machine.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
# No benchmark programs: no test runs them, and they cost CI minutes that the sanitizer build
# needs (scripts/build.sh alone still builds them).
"$root/scripts/build.sh" -DBUILD_BENCHMARKS=OFF
jobs="$(nproc 2>/dev/null || echo 2)"
(cd "$root/build" && ctest --output-on-failure -j "$jobs")
"$root/scripts/test_sanitizers.sh"
