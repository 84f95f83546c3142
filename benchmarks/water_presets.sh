#!/usr/bin/env bash
# acetate.water's presets on the harbour's ground floor (1280x720, river, pond and harbour):
# frame time (median of 15 frames in one process, after one warm-up) and error against ultra
# (mean and largest absolute difference, linear light, over the whole frame), side by side in
# one run. "none" is the same floor without the water effect: the difference is the water's
# own cost. Usage: benchmarks/water_presets.sh [BUILD_DIR]  (about 1 minute on 2 cores)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for preset in none low medium high ultra; do
  python3 - "$root/examples/harbour/scene.json" "$preset" "$work/$preset.json" <<'PY'
import json, os, sys
source, preset, out = sys.argv[1:]
scene = json.load(open(source))
folder = os.path.dirname(os.path.abspath(source))
ground = scene["floors"][0]
for tile in ground["tiles"]:
    tile["image"] = os.path.join(folder, tile["image"])
    for kind in tile.get("masks", {}):
        tile["masks"][kind] = os.path.join(folder, tile["masks"][kind])
effects = [e for e in ground["effects"] if e["plugin"] != "acetate.water" or preset != "none"]
for e in effects:
    if e["plugin"] == "acetate.water":
        e["preset"] = preset
ground["effects"] = effects
scene["floors"] = [ground]
scene.pop("active_floor", None)
scene.pop("global_effects", None)
json.dump(scene, open(out, "w"))
PY
done
declare -A frame_ms mean_error max_error
for preset in ultra none low medium high; do  # ultra first: the others are compared to it
  frames=$(printf '0,%.0s' $(seq 16)); frames=${frames%,}
  log=$("$build/host/acetate" render "$work/$preset.json" -o "$work/$preset.exr" --floors "$frames" \
    --time 2.5 --allow-unvalidated --plugin-path "$build/plugins" 2>&1)
  frame_ms[$preset]=$(echo "$log" | grep -oE 'floor 0: [0-9.]+ ms' | awk 'NR > 1 {print $3}' |
    sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
  if [ "$preset" != none ] && [ "$preset" != ultra ]; then
    errors=$(oiiotool "$work/$preset.floor0.exr" "$work/ultra.floor0.exr" --diff 2>&1 || true)
    mean_error[$preset]=$(echo "$errors" | awk '/Mean error/ {print $4}')
    max_error[$preset]=$(echo "$errors" | awk '/Max error/ {print $4}')
  fi
done
printf '%-7s %9s %9s %12s %12s\n' preset "frame ms" "water ms" "mean error" "max error"
for preset in none low medium high ultra; do
  water=-
  [ "$preset" = none ] || water=$(awk -v a="${frame_ms[$preset]}" -v b="${frame_ms[none]}" \
    'BEGIN {printf "%.2f", a - b}')
  printf '%-7s %9s %9s %12s %12s\n' "$preset" "${frame_ms[$preset]}" "$water" \
    "${mean_error[$preset]:--}" "${max_error[$preset]:--}"
done
