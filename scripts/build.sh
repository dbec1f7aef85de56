#!/usr/bin/env bash
# Configures and builds semchain (Release, warnings as errors) in build/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc 2>/dev/null || echo 2)"
# ROS 1's CMake files run Python and need Debian's (its catkin_pkg and ament_package): another
# python3 first on the PATH (pyenv, conda) makes them fail (cmake/SemchainRos.cmake).
python=()
if [ -x /usr/bin/python3 ]; then
  python=(-DPython3_EXECUTABLE=/usr/bin/python3)
fi
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DSEMCHAIN_WERROR=ON \
  -DBUILD_TESTING=ON -DBUILD_BENCHMARKS=ON "${python[@]}" "$@"
cmake --build "$root/build" -j "$jobs"
