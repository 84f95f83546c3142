#!/usr/bin/env bash
# The harbour frame of two `acetate` builds side by side in one run: each run is a fresh
# process per build, alternating A, B, A, B, ... so the machine's noise falls on both alike.
# Prints each build's median frame time per floor over the runs and the ratio B / A, the
# passes and pipeline barriers each recorded per frame, and the render targets each held.
#
#   A="env LD_LIBRARY_PATH=/tmp/before/lib /tmp/before/bin/acetate" B=build/host/acetate \
#       benchmarks/frame_ab.sh                   # RUNS=7 by default
#
# Every floor of the scene is rendered once per process (--floors all) after the load, with the
# plugins of ACETATE_PLUGIN_PATH (default build/plugins) loaded --allow-unvalidated, Mesa's
# shader cache and acetate's pipeline cache warm (private folders, filled by one uncounted run
# of each build). Validation layers off. Everything goes into a private temp folder.
set -euo pipefail
cd "$(dirname "$0")/.."
A=${A:?"A=<command of the first acetate>"}
B=${B:-build/host/acetate}
SCENE=${SCENE:-examples/harbour/scene.json}
RUNS=${RUNS:-7}
export ACETATE_PLUGIN_PATH=${ACETATE_PLUGIN_PATH:-$PWD/build/plugins}
work=$(mktemp -d "${TMPDIR:-/tmp}/acetate-frame-ab.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/mesa" "$work/xdg"
export ACETATE_VALIDATION=0 MESA_SHADER_CACHE_DIR="$work/mesa" XDG_CACHE_HOME="$work/xdg"

run() {  # run NAME INDEX: one process of build NAME; its stats in $work/NAME-INDEX.json
    local command=${!1}
    $command render "$SCENE" -o "$work/$1.png" --floors all --allow-unvalidated \
        --stats "$work/$1-$2.json" > "$work/$1-$2.log" 2>&1 || {
        echo "frame_ab.sh: $1 run $2 failed:" >&2; cat "$work/$1-$2.log" >&2; exit 1; }
}
run A warm; run B warm
for i in $(seq 1 "$RUNS"); do run A "$i"; run B "$i"; echo "run $i/$RUNS done" >&2; done

python3 - "$work" "$RUNS" <<'PY'
import json, statistics, sys
work, runs = sys.argv[1], int(sys.argv[2])
def frames(name):
    per_floor, counts = {}, {}
    for i in range(1, runs + 1):
        for f in json.load(open(f"{work}/{name}-{i}.json"))["frames"]:
            per_floor.setdefault(f["active_floor"], []).append(f["milliseconds"])
            # Passes and barriers are the plan's, the same in every run (absent before both
            # were counted: "-").
            counts[f["active_floor"]] = (f.get("passes", "-"), f.get("barriers", "-"))
    return {k: statistics.median(v) for k, v in sorted(per_floor.items())}, counts
(a, a_counts), (b, b_counts) = frames("A"), frames("B")
print(f"median frame (ms) over {runs} processes each, A and B alternating;"
      " passes and barriers recorded per frame")
print("| active floor | A | B | B / A | passes A, B | barriers A, B |")
print("|---|---|---|---|---|---|")
for floor in a:
    print(f"| {floor} | {a[floor]:.2f} | {b[floor]:.2f} | {b[floor] / a[floor]:.3f} "
          f"| {a_counts[floor][0]}, {b_counts[floor][0]} | {a_counts[floor][1]}, {b_counts[floor][1]} |")
def held(name):
    targets = json.load(open(f"{work}/{name}-1.json"))["render_targets"]
    return len(targets), sum(t["bytes"] for t in targets) / 2**20
for name in ("A", "B"):
    count, mib = held(name)
    print(f"render targets held by {name}: {count}, {mib:.1f} MiB")
PY
