#!/usr/bin/env bash
# Installs every Debian 12 package manylight needs to build, test and benchmark.
# Idempotent; run as root (or as a user with sudo).
#   ci/install-deps.sh           what the build, the tests and bench/sweep.sh need
#   ci/install-deps.sh --peers   also the peers bench/peers.sh times: f3d, and Xvfb for it
set -euo pipefail

packages=(
  build-essential cmake pkg-config ninja-build
  libosmesa6-dev libegl-dev libegl1-mesa-dev libgl-dev mesa-common-dev libgbm-dev
  libegl-mesa0 libgl1-mesa-dri
  libglm-dev glslang-tools
  libopenimageio-dev openimageio-tools
  libtinygltf-dev nlohmann-json3-dev libstb-dev libdraco-dev libmeshoptimizer-dev
  libsimdjson-dev
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev
  clang libclang-rt-14-dev clang-format pmccabe
  python3 python3-numpy python3-openimageio gnuplot-nox fonts-dejavu-core
)
case "${1:-}" in
  --peers) packages+=(f3d xvfb xauth) ;;
  "") ;;
  *) echo "usage: ci/install-deps.sh [--peers]" >&2; exit 2 ;;
esac

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps.sh: run as root or install sudo" >&2; exit 1; }
  sudo_cmd=(sudo)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps.sh: all packages present"
  exit 0
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
