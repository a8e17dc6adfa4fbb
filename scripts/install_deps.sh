#!/usr/bin/env bash
# Installs every Debian 12 package partreg needs to build, test and render. Run as root.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libceres-dev libnanoflann-dev
  libpcl-dev libassimp-dev libvtk9-dev
  libcli11-dev libspdlog-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libembree-dev libtbb-dev libcairo2-dev libstb-dev libpng-dev
  libosmesa6-dev libglfw3-dev libimgui-dev python3-glad xvfb xauth
  clang-14 libclang-rt-14-dev
  parallel slurmctld slurmd slurm-client munge
  pybind11-dev python3-dev python3-pytest python3-numpy python3-open3d
)
missing=()
for package in "${packages[@]}"; do
  dpkg -s "$package" >/dev/null 2>&1 || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install_deps: installing ${missing[*]}" >&2
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
