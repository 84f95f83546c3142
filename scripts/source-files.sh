#!/usr/bin/env bash
# source-files.sh ROOT EXT... -- the project's files with these extensions, one path a line,
# relative to ROOT, sorted. In a git checkout: the files git tracks. In a tree without git
# metadata (CI runs on `git archive`, scripts/fresh-machine.sh): every such file under ROOT but
# the build outputs (build/, build-*/, out/). The format check and the hygiene tests list files
# through this one place, so they check the same files wherever they run.
set -euo pipefail
root=${1:?usage: source-files.sh ROOT EXT...}
shift
cd "$root"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  patterns=()
  for ext in "$@"; do patterns+=("*.$ext"); done
  git ls-files -- "${patterns[@]}" | sort
else
  names=()
  for ext in "$@"; do
    ((${#names[@]})) && names+=(-o)
    names+=(-name "*.$ext")
  done
  find . \( -path ./build -o -path './build-*' -o -path ./out -o -path ./.git \) -prune -o \
    -type f \( "${names[@]}" \) -print | sed 's|^\./||' | sort
fi
