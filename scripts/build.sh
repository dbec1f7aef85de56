#!/usr/bin/env bash
# Configures and builds semchain (Release, warnings as errors) in build/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DSEMCHAIN_WERROR=ON \
  -DBUILD_TESTING=ON -DBUILD_BENCHMARKS=ON "$@"
cmake --build "$root/build" -j "$jobs"
