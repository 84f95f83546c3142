#!/usr/bin/env bash
# Checks that every tracked C/C++ file is formatted as the committed .clang-format says
# (Debian 12's clang-format 14). Prints each file that differs and exits 1; exits 0 when all
# match. Fix with: git ls-files '*.cpp' '*.hpp' '*.h' '*.c' | xargs clang-format -i
# The files are listed by scripts/source-files.sh (git's list, or every file of an archive).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
command -v clang-format >/dev/null || { echo "check-format: clang-format is not installed (apt-get install clang-format)" >&2; exit 1; }
mapfile -t files < <(bash "$root/scripts/source-files.sh" "$root" cpp hpp h c)
bad=()
for f in "${files[@]}"; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if ((${#bad[@]})); then
  echo "check-format: ${#bad[@]} of ${#files[@]} C/C++ files differ from .clang-format:" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "check-format: all ${#files[@]} C/C++ files match .clang-format ($(clang-format --version | grep -oE '[0-9]+\.[0-9.]+' | head -1))"
