#!/usr/bin/env bash
# Installs the Debian 12 packages semchain needs; packages already installed are skipped.
# --no-ros leaves out ROS 1 (then src/ros and `semchain bag` are not built).
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libopencv-dev libceres-dev libyaml-cpp-dev nlohmann-json3-dev
  libcli11-dev libspdlog-dev libgtest-dev libgmock-dev libbenchmark-dev zlib1g-dev
  # src/detection reads and rewrites ONNX models (onnx::ModelProto) before OpenCV DNN runs them.
  libonnx-dev libprotobuf-dev
  clang-format
  # scripts/test_sanitizers.sh (run by run_tests.sh) and scripts/fuzz.sh: clang, its sanitizer
  # runtimes and llvm-symbolizer (reports with function names).
  clang libclang-rt-14-dev llvm-14
  # train/: the detector's training package and its tests (Debian's PyTorch 1.13, CPU).
  python3-torch python3-onnx python3-opencv python3-numpy python3-yaml python3-tqdm python3-pytest
)
# ROS 1 from Debian: roscpp, rosbag, tf2 and the message headers of DESIGN.md section 5.7, and
# the command-line tools (rosbag, rostopic, rosservice, roslaunch) to use them on a robot.
ros_packages=(
  ros-core-dev librosbag-dev libtf2-ros-dev libtf2-msgs-dev libsensor-msgs-dev
  # bag_structure.cc decompresses chunks with rosbag's own libraries (also rosbag's dependencies).
  libbz2-dev libroslz4-dev
  libnav-msgs-dev libgeometry-msgs-dev libvisualization-msgs-dev libstd-srvs-dev
  python3-rosbag python3-rostopic python3-rosservice python3-roslaunch
  # The node tests' checkers (tests/ros/node_checker.py, mapping_checker.py) are rospy nodes.
  python3-rospy python3-std-msgs python3-std-srvs python3-geometry-msgs python3-sensor-msgs
  python3-nav-msgs python3-tf2-msgs python3-rosgraph-msgs python3-visualization-msgs
)
if [ "${1:-}" != "--no-ros" ]; then
  packages+=("${ros_packages[@]}")
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  sudo="sudo"
fi
echo "install_deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
