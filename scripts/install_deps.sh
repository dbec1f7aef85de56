#!/usr/bin/env bash
# Installs the Debian 12 packages semchain needs; packages already installed are skipped.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libopencv-dev libceres-dev libyaml-cpp-dev nlohmann-json3-dev
  libcli11-dev libspdlog-dev libgtest-dev libgmock-dev libbenchmark-dev zlib1g-dev
  clang-format
)

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
