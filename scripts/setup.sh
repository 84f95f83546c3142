#!/usr/bin/env bash
# Installs the Debian packages Acetate needs (if missing), then configures and builds it:
# everything, or only the CMake targets named as arguments (demo.sh builds `acetate-demo`).
# Used by demo.sh and test.sh; safe to run again (only missing packages are installed and the
# build is incremental).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${ACETATE_BUILD_DIR:-$root/build}

# Build: compilers, CMake, the libraries. Tests: GoogleTest, Benchmark, clang-format (the
# format check), git and debootstrap (scripts/fresh-machine.sh's own tests).
packages=(
  cmake g++ make pkg-config git
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-dev glslang-tools
  libopenimageio-dev openimageio-tools libimath-dev
  libboost-dev libboost-filesystem-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev libglm-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev clang-format debootstrap
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "== Installing Debian packages: ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi

echo "== Configuring and building in $build"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo ${ACETATE_CMAKE_ARGS:-} >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
