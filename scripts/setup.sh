#!/usr/bin/env bash
# Installs the Debian packages Acetate needs (if missing), then configures and builds it:
# everything, or only the CMake targets named as arguments (demo.sh builds `acetate-demo`).
# Used by demo.sh and test.sh; safe to run again (only missing packages are installed and the
# build is incremental).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${ACETATE_BUILD_DIR:-$root/build}

bash "$root/scripts/install-packages.sh"

echo "== Configuring and building in $build"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo ${ACETATE_CMAKE_ARGS:-} >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
