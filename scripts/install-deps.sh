#!/usr/bin/env bash
# Installs the Debian 12 packages RockDEM needs to build, test and run (idempotent).
set -euo pipefail
PKGS=(
  build-essential cmake ninja-build pkg-config git
  paraview paraview-dev python3-paraview
  qtbase5-dev qttools5-dev libqt5svg5-dev libqt5opengl5-dev qtxmlpatterns5-dev-tools
  libopenmpi-dev
  libdouble-conversion-dev liblz4-dev libutfcpp-dev libexpat1-dev liblzma-dev zlib1g-dev
  libfreetype-dev libglew-dev libgl2ps-dev libjpeg-dev libpng-dev libtiff-dev libxml2-dev
  libx11-dev libgl-dev libtheora-dev libnetcdf-dev libjsoncpp-dev libpugixml-dev libprotobuf-dev
  libeigen3-dev libhdf5-dev
  libvulkan-dev glslc mesa-vulkan-drivers
  libgtest-dev
  clang libclang-rt-14-dev
  xvfb xauth python3-numpy python3-matplotlib
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PKGS[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
