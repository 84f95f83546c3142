#!/usr/bin/env bash
# One floor effect's presets on one floor of examples/harbour, side by side in one run: frame
# time (median of 15 frames in one process, after one warm-up) and error against ultra (mean
# and largest absolute difference, linear light, whole frame, every channel). "none" is the
# same floor without the effect, so "effect ms" is the effect's own share of the frame. The
# floor is rendered alone with its tiles, masks, lights and sun, and its effects up to and
# including the one measured.
#
#   benchmarks/effect_presets.sh acetate.water 0       # the ground's river, pond and harbour
#   benchmarks/effect_presets.sh acetate.specular 2    # the roofs, two lights and a sun
#
# Usage: benchmarks/effect_presets.sh PLUGIN_ID FLOOR [BUILD_DIR]   (about 1 minute on 2 cores)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
plugin=${1:?plugin id, e.g. acetate.water}
floor=${2:?floor index in examples/harbour/scene.json}
build=${3:-$root/build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for preset in none low medium high ultra; do
  python3 - "$root/examples/harbour/scene.json" "$plugin" "$floor" "$preset" \
    "$work/$preset.json" <<'PY'
import json, os, sys
source, plugin, floor, preset, out = sys.argv[1:]
scene = json.load(open(source))
folder = os.path.dirname(os.path.abspath(source))
chosen = scene["floors"][int(floor)]
for tile in chosen["tiles"]:
    tile["image"] = os.path.join(folder, tile["image"])
    for kind in tile.get("masks", {}):
        tile["masks"][kind] = os.path.join(folder, tile["masks"][kind])
ids = [e["plugin"] for e in chosen["effects"]]
if plugin not in ids:
    sys.exit(f"{source}: floors[{floor}] has no effect {plugin}")
effects = chosen["effects"][: ids.index(plugin) + 1]
if preset == "none":
    effects = effects[:-1]
else:
    effects[-1]["preset"] = preset
chosen["effects"] = effects
scene["floors"] = [chosen]
scene.pop("active_floor", None)
scene.pop("global_effects", None)
json.dump(scene, open(out, "w"))
PY
done
declare -A frame_ms mean_error max_error
frames=$(printf '0,%.0s' $(seq 16))
frames=${frames%,}
for preset in ultra none low medium high; do  # ultra first: the others are compared to it
  log=$("$build/host/acetate" render "$work/$preset.json" -o "$work/$preset.exr" --floors "$frames" \
    --time 2.5 --allow-unvalidated --plugin-path "$build/plugins" 2>&1)
  frame_ms[$preset]=$(echo "$log" | grep -oE 'floor 0: [0-9.]+ ms' | awk 'NR > 1 {print $3}' |
    sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
  if [ "$preset" != none ] && [ "$preset" != ultra ]; then
    errors=$(oiiotool "$work/$preset.floor0.exr" "$work/ultra.floor0.exr" --diff 2>&1 || true)
    # Identical images print no error lines, only PASS.
    mean_error[$preset]=$(echo "$errors" | awk '/Mean error/ {e = $4} END {print e == "" ? 0 : e}')
    max_error[$preset]=$(echo "$errors" | awk '/Max error/ {e = $4} END {print e == "" ? 0 : e}')
  fi
done
echo "$plugin on floor $floor of examples/harbour ($(date -u +%Y-%m-%dT%H:%MZ), load $(cut -d' ' -f1-3 /proc/loadavg))"
printf '%-7s %9s %10s %12s %12s\n' preset "frame ms" "effect ms" "mean error" "max error"
for preset in none low medium high ultra; do
  share=-
  [ "$preset" = none ] || share=$(awk -v a="${frame_ms[$preset]}" -v b="${frame_ms[none]}" \
    'BEGIN {printf "%.2f", a - b}')
  printf '%-7s %9s %10s %12s %12s\n' "$preset" "${frame_ms[$preset]}" "$share" \
    "${mean_error[$preset]:--}" "${max_error[$preset]:--}"
done
