#!/usr/bin/env bash
# The main job: set everything up, validate the shipped plugins with acetate-harness (so the
# registry has them VALIDATED for exactly these binaries), render the bundled harbour scene
# for each active floor with validated plugins only, write the images and the debug views to
# an output folder, and say where the images and the validation reports are.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${ACETATE_BUILD_DIR:-$root/build}
out=${1:-$root/out/demo}
scene=$root/examples/harbour/scene.json
start=$SECONDS
# Only what the demo runs: the CLI, the harness and the shipped plugins (not the test suites).
bash "$root/scripts/setup.sh" acetate-demo

mkdir -p "$out"
# The committed sign-offs (validation/signoffs.json) are imported by validate; the automated
# stages re-run on the binaries just built, which then reach VALIDATED in the build tree's
# registry ($build/validation/registry.json), the one `acetate render` reads.
for plugin in lighting bloom water specular fire; do
  echo "== Validating $plugin (acetate-harness, every case in its own process)"
  ACETATE_VALIDATION=1 "$build/harness/acetate-harness" validate "$build/plugins/$plugin.so" \
    --report "$out/validation/$plugin"
done
"$build/harness/acetate-harness" status

echo "== Rendering $scene, every floor, into $out"
rm -f "$out"/normal.floor*.png
for view in normal floor-alpha accum-alpha floor-rgb violations isolation; do
  echo "-- view: $view"
  "$build/host/acetate" render "$scene" -o "$out/$view.png" --floors all --view "$view" \
    --stats "$out/$view.stats.json"
done
"$build/host/acetate" render "$scene" -o "$out/normal.exr" --floors all

# A second of the ground floor in 12 steps of 1/12 s: the fire, the water and the embers move
# (every frame is a pure function of its time, so any step renders directly).
echo "== Animation: floor 0, t = 0 .. 11/12 s, into $out/animation/"
# One process renders all twelve (--times), so the device and the scene load once.
mkdir -p "$out/animation"
"$build/host/acetate" render "$scene" -o "$out/animation/frame.png" --floor 0 \
  --times 0:11/12:1/12 >/dev/null
# What each preset costs and what it gets wrong: every plugin x preset x format of the scene
# against ultra at rgba32f, and the same flattening by oiiotool (about 1.5 minutes).
echo "== Speed against error: acetate-bench, report in $out/bench/index.html"
mkdir -p "$out/bench"
"$build/bench/acetate-bench" "$scene" --frames 5 --html "$out/bench" --json "$out/bench/bench.json" \
  >"$out/bench/bench.txt"
tail -n 6 "$out/bench/bench.txt"

floors=$(cd "$out" && ls normal.floor*.png | sed -E 's/normal\.floor([0-9]+)\.png/\1/' | sort -n | tr '\n' ' ')

# One picture to look at: every view (rows) for every floor (columns).
if command -v oiiotool >/dev/null; then
  n=$(echo "$floors" | wc -w)
  images=()
  for view in normal floor-alpha accum-alpha floor-rgb violations isolation; do
    for f in $floors; do images+=("$out/$view.floor$f.png"); done
  done
  oiiotool "${images[@]}" --mosaic:pad=4 "${n}x6" --resize 50% -o "$out/contact-sheet.png"
fi

echo
echo "Done in $((SECONDS - start)) s. Images are in $out:"
echo "  normal.floorN.png      the scene seen from floor N (also normal.floorN.exr: half, linear)"
echo "  <view>.floorN.png      debug views: floor-alpha accum-alpha floor-rgb violations isolation"
echo "  <view>.stats.json      load and per-frame statistics"
echo "  animation/frame.frameNNNN.png  floor 0 over one second, 12 frames"
echo "  validation/<plugin>/index.html   the harness's reports (report.json beside each)"
echo "  bench/index.html       speed against error: each plugin's presets (bench.json, bench.txt)"
echo "Registry: $build/validation/VALIDATION-REGISTRY.md"
if [ -f "$out/contact-sheet.png" ]; then
  echo "  contact-sheet.png      all views (rows) x floors (columns)"
fi
