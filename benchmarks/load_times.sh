#!/usr/bin/env bash
# Load time and first-frame time of `acetate render` on the bundled harbour scene, with Mesa's
# shader disk cache off ("cold") and with a private cache that an earlier run filled ("warm").
# Prints each run and the medians (docs/performance.md).
#
#   benchmarks/load_times.sh            # 5 cold + 5 warm runs
#   RUNS=9 ACETATE=build-x/host/acetate benchmarks/load_times.sh
#
# Each run is a fresh process: instance + device creation, scene parse, image decode and upload,
# shader compile, pipeline creation and warm-up draws (the load), then one frame, read back and
# written as PNG. Validation layers are off. Nothing outside a private temp folder is touched.
# The plugins are loaded with --allow-unvalidated (the build's plugins need not be in the
# registry); the policy check (hashing each plugin file) is part of the load time.
set -euo pipefail

cd "$(dirname "$0")/.."
ACETATE=${ACETATE:-build/host/acetate}
SCENE=${SCENE:-examples/harbour/scene.json}
RUNS=${RUNS:-5}

if [[ ! -x $ACETATE ]]; then
    echo "load_times.sh: $ACETATE not found; build it first (cmake --build build --target acetate)" >&2
    exit 1
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/acetate-load-times.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/xdg-warm" "$work/mesa-warm"

# run_once MODE INDEX: one render; its --stats file lands in $work/MODE-INDEX.json and the
# process wall time (ms) in $work/MODE-INDEX.wall.
run_once() {
    local mode=$1 index=$2
    local -a env=(ACETATE_VALIDATION=0)
    if [[ $mode == cold ]]; then
        # No Mesa disk cache, and a fresh XDG cache folder (so no acetate pipeline-cache file).
        mkdir -p "$work/xdg-cold-$index"
        env+=(MESA_SHADER_CACHE_DISABLE=true XDG_CACHE_HOME="$work/xdg-cold-$index")
    else
        # Mesa's disk cache and acetate's pipeline-cache file as an earlier run left them.
        env+=(MESA_SHADER_CACHE_DISABLE=false MESA_SHADER_CACHE_DIR="$work/mesa-warm"
              XDG_CACHE_HOME="$work/xdg-warm")
    fi
    local start end
    start=$(date +%s%N)
    env "${env[@]}" "$ACETATE" render "$SCENE" -o "$work/x.png" --allow-unvalidated \
        --stats "$work/$mode-$index.json" > "$work/$mode-$index.log" 2>&1 || {
        echo "load_times.sh: $mode run $index failed:" >&2
        cat "$work/$mode-$index.log" >&2
        exit 1
    }
    end=$(date +%s%N)
    echo $(( (end - start) / 1000000 )) > "$work/$mode-$index.wall"
}

echo "acetate:  $ACETATE"
echo "scene:    $SCENE"
echo "runs:     $RUNS cold (MESA_SHADER_CACHE_DISABLE=true), $RUNS warm (private MESA_SHADER_CACHE_DIR and XDG_CACHE_HOME)"
echo "nproc:    $(nproc)"

for i in $(seq 1 "$RUNS"); do run_once cold "$i"; done
run_once warm 0  # fills the private cache; not counted
for i in $(seq 1 "$RUNS"); do run_once warm "$i"; done

# For comparison, the steady-state frame: one warm process renders the scene's active floor five
# times (frames 2..5 count).
active=$(python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); print(s.get("active_floor", len(s["floors"]) - 1))' "$SCENE")
env ACETATE_VALIDATION=0 MESA_SHADER_CACHE_DIR="$work/mesa-warm" XDG_CACHE_HOME="$work/xdg-warm" \
    "$ACETATE" render "$SCENE" -o "$work/steady.png" --floors "$active,$active,$active,$active,$active" \
    --allow-unvalidated --stats "$work/steady.json" > "$work/steady.log" 2>&1 || { cat "$work/steady.log" >&2; exit 1; }

python3 - "$work" "$RUNS" <<'EOF'
import json, statistics, sys
work, runs = sys.argv[1], int(sys.argv[2])
def rows(mode):
    out = []
    for i in range(1, runs + 1):
        with open(f"{work}/{mode}-{i}.json") as f:
            s = json.load(f)
        with open(f"{work}/{mode}-{i}.wall") as f:
            wall = float(f.read())
        out.append((s["load_milliseconds"], s["frames"][0]["milliseconds"], wall, s["device"],
                    s.get("plugins_loaded"), s["load"], s["frames"][0]))
    return out
cold, warm = rows("cold"), rows("warm")
print(f"device:   {cold[0][3]}")
print(f"plugins:  {cold[0][4]}")
f = cold[0][6]
print(f"frame:    {f['passes']} passes, {f['pixels_shaded']} pixels shaded")
for mode, r in (("cold", cold), ("warm", warm)):
    l = r[0][5]
    print(f"{mode} load: " + ", ".join(f"{k} {v}" for k, v in l.items() if k != "milliseconds"))
print()
for mode, r in (("cold", cold), ("warm", warm)):
    print(f"{mode}: load ms   " + "  ".join(f"{x[0]:7.1f}" for x in r))
    print(f"{mode}: frame ms  " + "  ".join(f"{x[1]:7.1f}" for x in r))
    print(f"{mode}: process ms" + "  ".join(f"{x[2]:7.0f}" for x in r))
print()
print("| Mesa shader cache | runs | median load ms | median first-frame ms | median process wall ms |")
print("|---|---|---|---|---|")
for mode, label, r in (("cold", "off (MESA_SHADER_CACHE_DISABLE=true)", cold),
                       ("warm", "warm (private MESA_SHADER_CACHE_DIR, filled by an earlier run)", warm)):
    med = lambda k: statistics.median(x[k] for x in r)
    print(f"| {label} | {len(r)} | {med(0):.1f} | {med(1):.2f} | {med(2):.0f} |")
with open(f"{work}/steady.json") as f:
    frames = [x["milliseconds"] for x in json.load(f)["frames"]]
print()
print("steady-state frame (one warm process, frames 2..5): median "
      f"{statistics.median(frames[1:]):.2f} ms (" + ", ".join(f"{x:.1f}" for x in frames) + " ms)")
EOF
