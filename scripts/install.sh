#!/usr/bin/env bash
# Installs partreg on a fresh Debian 12 machine (as root): its packages, a Release build, then
# `cmake --install` into /usr/local (or the prefix given: scripts/install.sh /opt/partreg): libraries, headers,
# the CMake package, partreg.pc, partreg and partreg-gui, the Python module and the docs.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix=${1:-/usr/local}
bash scripts/install_deps.sh
bash scripts/build.sh -DCMAKE_INSTALL_PREFIX="$prefix"
cmake --install build
echo "installed partreg into $prefix" >&2
