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
# Fifty files per clang-format, one clang-format per core (a process per file took a minute).
# Each file that differs is named in an "error: code should be clang-formatted" line; any other
# failure (an unreadable file, a broken .clang-format) fails with clang-format's own words.
status=0
messages=$(printf '%s\0' "${files[@]}" |
  xargs -0 -n 50 -P "$(nproc)" clang-format --dry-run --Werror 2>&1 >/dev/null) || status=$?
mapfile -t bad < <(grep -E ': error: code should be clang-formatted' <<<"$messages" |
  sed -E 's/:[0-9]+:[0-9]+: error: .*//' | sort -u)
if [ "$status" -ne 0 ] && ((${#bad[@]} == 0)); then
  echo "check-format: clang-format failed (exit $status):" >&2
  head -n 20 <<<"$messages" >&2
  exit 1
fi
if ((${#bad[@]})); then
  echo "check-format: ${#bad[@]} of ${#files[@]} C/C++ files differ from .clang-format:" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "check-format: all ${#files[@]} C/C++ files match .clang-format ($(clang-format --version | grep -oE '[0-9]+\.[0-9.]+' | head -1))"
