#!/usr/bin/env bash
# The test command: set everything up from nothing, build, and run the whole suite with ctest
# (Vulkan validation layers on; any validation message fails a test).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${ACETATE_BUILD_DIR:-$root/build}
# Warnings are errors here (and in CI, which runs this): none of the project's own lands. Debug
# information is line tables only: backtraces keep their lines, and the build is a fifth faster.
ACETATE_CMAKE_ARGS="-DACETATE_WERROR=ON -DACETATE_LINE_TABLES_ONLY=ON ${ACETATE_CMAKE_ARGS:-}" \
  bash "$root/scripts/setup.sh"
echo "== Running the tests"
cd "$build"
ctest --output-on-failure -j"$(nproc)" "$@"
