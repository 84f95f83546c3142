#!/usr/bin/env bash
# include_layers_test.sh SOURCE_DIR -- every #include goes down the layers, never up or sideways.
#
# The layers, lowest first (docs/OVERVIEW.md, "Layers"): the SDK; host/core (small things
# everything uses, no Vulkan); the registry (built on core only); the rest of the host library
# (vulkan, scene, plugins, render, api); the tools' libraries (compare, harness, bench); the
# programs in apps/. Plugins and examples see only the SDK (an embedding example, the installed
# host API too). Each include is resolved as the compiler would (the including file's folder,
# then the include roots) and the folder it lands in must be one the including folder may use.
# A failure names the file, the include and the rule; the exit status is the number of them.
set -u
scripts=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../scripts" && pwd)
cd "${1:?usage: include_layers_test.sh SOURCE_DIR}" || exit 2

# The layer of a file, by its folder, into $layer. Everything in this loop is a bash builtin:
# a subprocess per include line (sed, realpath, a $(...) subshell) made the test take a minute.
layer_of() {
  case "$1" in
    sdk/*) layer=sdk ;;
    host/core/*) layer=core ;;
    registry/*) layer=registry ;;
    host/vulkan/*) layer=vulkan ;;
    host/scene/*) layer=scene ;;
    host/plugins/*) layer=loader ;;
    host/render/*) layer=render ;;
    host/include/*) layer=host-api ;;
    host/api/*) layer=api ;;
    compare/*) layer=compare ;;
    harness/*) layer=harness ;;
    bench/*) layer=bench ;;
    apps/*) layer=apps ;;
    examples/embedding-host/*) layer=embedder ;;
    plugins/* | examples/*) layer=plugin ;;
    *) layer=unchecked ;;  # tests, fuzz, benchmarks: at the top, may use anything
  esac
}

# What each layer may include besides itself.
declare -A may_use=(
  [sdk]=""
  [core]=""
  [registry]="core"
  [vulkan]="core"
  [scene]="core vulkan"
  [loader]="core sdk scene vulkan"
  [render]="core sdk vulkan scene loader"
  [host-api]=""
  [api]="core sdk registry vulkan scene loader render host-api"
  [compare]="core scene"
  [harness]="core sdk registry vulkan scene loader render host-api compare"
  [bench]="core sdk registry vulkan scene loader render host-api compare"
  [apps]="core sdk registry vulkan scene loader render host-api api compare harness bench"
  [plugin]="sdk"
  [embedder]="sdk host-api"
)
# Layers that include no Vulkan header: core and the registry link no Vulkan, and the installed
# host API needs nothing but the standard library.
no_vulkan=" sdk core registry host-api compare plugin embedder "

roots=(host registry compare harness bench apps sdk/include host/include)
failures=0
checked=0
fail() {
  echo "include_layers: $1"
  failures=$((failures + 1))
}

# A relative path with its "." and ".." folders resolved, into $normal ("a/b/../c" -> "a/c").
normalize() {
  local -a out=() parts=()
  local part IFS=/
  read -ra parts <<<"$1"
  for part in "${parts[@]}"; do
    case "$part" in
      "" | .) ;;
      ..) ((${#out[@]})) && unset 'out[${#out[@]}-1]' || out+=(..) ;;
      *) out+=("$part") ;;
    esac
  done
  normal="${out[*]}"
}

include_pattern='^[[:space:]]*#[[:space:]]*include[[:space:]]*["<]([^">]+)[">]'
while IFS= read -r file; do
  layer_of "$file"
  from=$layer
  [ "$from" = unchecked ] && continue
  dir=${file%/*}
  while IFS= read -r line; do
    [[ "$line" =~ $include_pattern ]] || continue
    name=${BASH_REMATCH[1]}
    if [[ "$line" =~ \< ]]; then
      if [[ "$name" == vulkan/* && "$no_vulkan" == *" $from "* ]]; then
        fail "$file includes <$name>, but $from includes no Vulkan header"
      fi
      if [ "$from" = host-api ] && [[ "$name" == */* ]] && [[ "$name" != acetate/host/* ]]; then
        fail "$file includes <$name>; the installed host API uses the standard library only"
      fi
    fi
    target=""
    if [ -f "$dir/$name" ]; then
      normalize "$dir/$name"
      target=$normal
    else
      for root in "${roots[@]}"; do
        if [ -f "$root/$name" ]; then
          target="$root/$name"
          break
        fi
      done
    fi
    [ -z "$target" ] && continue  # a system or generated header
    layer_of "$target"
    to=$layer
    [ "$to" = "$from" ] && continue
    if [[ " ${may_use[$from]} " != *" $to "* ]]; then
      fail "$file includes \"$name\" ($to), which $from may not use (it may use: ${may_use[$from]:-nothing else})"
    fi
  done < <(grep -E '^[[:space:]]*#[[:space:]]*include[[:space:]]*["<]' "$file")
  checked=$((checked + 1))
done < <(bash "$scripts/source-files.sh" . h hpp cpp)

if [ "$checked" -eq 0 ]; then
  echo "include_layers: no source file found under $PWD"
  exit 1
fi
if [ "$failures" -eq 0 ]; then
  echo "include_layers: every include of $checked files goes down the layers"
fi
exit "$failures"
