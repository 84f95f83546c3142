#!/usr/bin/env bash
# The main job: set everything up, render the bundled harbour scene for each active floor,
# write the images and the debug views to an output folder, and say where they are.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${ACETATE_BUILD_DIR:-$root/build}
out=${1:-$root/out/demo}
scene=$root/examples/harbour/scene.json
bash "$root/scripts/setup.sh"

mkdir -p "$out"
floors=$(python3 -c "import json,sys; print(','.join(str(i) for i in range(len(json.load(open(sys.argv[1]))['floors']))))" "$scene")
echo "== Rendering $scene, floors $floors, into $out"
for view in normal floor-alpha accum-alpha floor-rgb violations isolation; do
  echo "-- view: $view"
  "$build/host/acetate" render "$scene" -o "$out/$view.png" --floors "$floors" --view "$view" \
    --stats "$out/$view.stats.json"
done
"$build/host/acetate" render "$scene" -o "$out/normal.exr" --floors "$floors"

# One picture to look at: every view (rows) for every floor (columns).
if command -v oiiotool >/dev/null; then
  n=$(echo "$floors" | tr ',' ' ' | wc -w)
  images=()
  for view in normal floor-alpha accum-alpha floor-rgb violations isolation; do
    for f in ${floors//,/ }; do images+=("$out/$view.floor$f.png"); done
  done
  oiiotool "${images[@]}" --mosaic:pad=4 "${n}x6" --resize 50% -o "$out/contact-sheet.png"
fi

echo
echo "Done. Images are in $out:"
echo "  normal.floorN.png      the scene seen from floor N (also normal.floorN.exr: half, linear)"
echo "  <view>.floorN.png      debug views: floor-alpha accum-alpha floor-rgb violations isolation"
echo "  <view>.stats.json      load and per-frame statistics"
[ -f "$out/contact-sheet.png" ] && echo "  contact-sheet.png      all views (rows) x floors (columns)"
