#!/usr/bin/env bash
# First README command: installs the Debian packages, builds Release, runs the end-to-end demo.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh"
"$root/scripts/demo.sh" "$root/demo"
