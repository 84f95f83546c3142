#!/usr/bin/env bash
# overview_names_test.sh SOURCE_DIR -- docs/OVERVIEW.md names every source file.
#
# A new engineer finds any file from the overview: every C, C++ and GLSL source of the
# libraries, programs, plugins, fuzzers, benchmarks and tests must appear in docs/OVERVIEW.md by
# its path, its file name, its stem in backticks (`registry_test`), or (a source and its header
# being one unit) its stem with any extension: `atomic_file.hpp` names atomic_file.cpp too.
# A failure names each file the page does not mention; the exit status is their number.
set -u
scripts=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../scripts" && pwd)
cd "${1:?usage: overview_names_test.sh SOURCE_DIR}" || exit 2
page=docs/OVERVIEW.md
[ -f "$page" ] || { echo "overview_names: $page is missing"; exit 1; }
missing=0
checked=0
while IFS= read -r file; do
  stem=$(basename "$file")
  stem=${stem%.*}
  if ! grep -qE -- "(^|[^A-Za-z0-9_])${stem}\.(h|hpp|cpp|frag|vert|comp|glsl)|\`${stem}\`" "$page"; then
    echo "overview_names: $page does not name $file"
    missing=$((missing + 1))
  fi
  checked=$((checked + 1))
done < <(bash "$scripts/source-files.sh" . h hpp cpp frag vert comp glsl |
           grep -vE '^(tests/plugins/|tests/abi_1_0/|examples/)')
if [ "$checked" -eq 0 ]; then
  echo "overview_names: no source file found under $PWD"
  exit 1
fi
if [ "$missing" -eq 0 ]; then
  echo "overview_names: $page names every one of $checked source files"
fi
exit "$missing"
