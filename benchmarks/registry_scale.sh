#!/usr/bin/env bash
# How the registry scales (docs/performance.md, "Registries that grow"): `acetate-harness
# status` and the start-up of `acetate render` (a one-plugin scene whose plugin the registry
# holds VALIDATED) with registries of 1, 1,000 and 10,000 entries, every sign-off a genuine
# SSH signature. Each command is a fresh process; the sizes alternate run by run, so the
# machine's noise falls on all of them alike; medians are printed with the ratio to 1 entry.
#
#   benchmarks/registry_scale.sh            # RUNS=5, SIZES="1 1000 10000"
#
# Signing 22,000 sign-offs takes a few minutes (ssh-keygen, 4 at a time); the registries are
# kept in $KEEP (default a temp folder removed at the end).
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${RUNS:-5}
SIZES=${SIZES:-"1 1000 10000"}
HARNESS=${HARNESS:-build/harness/acetate-harness}
ACETATE=${ACETATE:-build/host/acetate}
PLUGIN=${PLUGIN:-build/plugins/lighting.so}
SCENE=${SCENE:-validation/references/acetate.lighting/scenes/quay.json}
work=${KEEP:-$(mktemp -d "${TMPDIR:-/tmp}/acetate-registry-scale.XXXXXX")}
[ -n "${KEEP:-}" ] || trap 'rm -rf "$work"' EXIT
mkdir -p "$work/mesa" "$work/xdg"
export ACETATE_VALIDATION=0 MESA_SHADER_CACHE_DIR="$work/mesa" XDG_CACHE_HOME="$work/xdg"

[ -f "$work/key" ] || ssh-keygen -q -t ed25519 -N '' -C 'registry scale' -f "$work/key"
printf 'bench@example.org namespaces="acetate-signoff" %s\n' \
    "$(cut -d' ' -f1,2 "$work/key.pub")" > "$work/allowed_signers"
"$HARNESS" describe "$PLUGIN" --out "$work/plugin.json" >/dev/null

# The registries: entry 0 is the plugin itself (the one a render verifies); the others are
# versions 0.0.N of made-up plugins, each reviewed, evidenced and promoted, all signed.
[ -f "$work/registries-$(echo $SIZES | tr ' ' '-')" ] || python3 - "$work" "$PLUGIN" $SIZES <<'PY'
import concurrent.futures, hashlib, json, os, subprocess, sys
work, plugin_file, sizes = sys.argv[1], sys.argv[2], [int(s) for s in sys.argv[3:]]
info = json.load(open(f"{work}/plugin.json"))
binary = hashlib.sha256(open(plugin_file, "rb").read()).hexdigest()
at = "2026-11-27T12:00:00Z"

def statement(pid, version, stage, source):
    # sign_off_statement (registry/registry_trust.cpp): ordered, compact, one line.
    return json.dumps({"format": "acetate-signoff/1", "plugin": pid, "version": version,
                       "stage": stage, "source_digest": source, "by": "bench@example.org",
                       "at": at, "notes": "scale"}, separators=(",", ":")) + "\n"

def sign(text):
    return subprocess.run(["ssh-keygen", "-q", "-Y", "sign", "-f", f"{work}/key", "-n",
                           "acetate-signoff"], input=text.encode(), capture_output=True,
                          check=True).stdout.decode()

def entry(i):
    pid, version = (info["id"], info["version"]) if i == 0 else (f"org.scale.p{i}", "0.0.1")
    source = info["source_digest"] if i == 0 else hashlib.sha256(f"source {i}".encode()).hexdigest()
    sha = binary if i == 0 else hashlib.sha256(f"binary {i}".encode()).hexdigest()
    evidence = {"at": at, "harness_version": "acetate-harness 0.1.0", "summary": "scale",
                "counts": {"PASS": 1}, "report": "", "binary_sha256": sha}
    sign_off = lambda stage: {"by": "bench@example.org", "at": at, "notes": "scale",
                              "source_digest": source,
                              "signature": sign(statement(pid, version, stage, source))}
    return {"id": pid, "version": version, "stage": "VALIDATED", "binary_sha256": sha,
            "source_digest": source, "review": sign_off("REVIEWED"), "alpha_tested": evidence,
            "integrated": evidence, "promotion": sign_off("VALIDATED")}

with concurrent.futures.ThreadPoolExecutor(4) as pool:
    entries = list(pool.map(entry, range(max(sizes))))
for n in sizes:
    with open(f"{work}/registry-{n}.json", "w") as f:
        json.dump({"format": "acetate-registry/1", "plugins": entries[:n]}, f, indent=2)
open(f"{work}/registries-" + "-".join(map(str, sizes)), "w").close()  # kept with KEEP=DIR
PY

now() { date +%s.%N; }
: > "$work/times"
for run in $(seq 0 "$RUNS"); do  # run 0 warms the caches and is not counted
  for n in $SIZES; do
    t0=$(now)
    "$HARNESS" --registry "$work/registry-$n.json" --allowed-signers "$work/allowed_signers" \
        status > "$work/status-$n.txt"
    t1=$(now)
    "$ACETATE" render "$SCENE" -o "$work/out-$n.png" --registry "$work/registry-$n.json" \
        --allowed-signers "$work/allowed_signers" --plugin-path "$(dirname "$PLUGIN")" \
        > "$work/render-$n.txt" 2>&1
    t2=$(now)
    # Every entry trusted: the signatures were really checked, not skipped.
    [ "$(grep -c " VALIDATED " "$work/status-$n.txt")" -eq "$n" ]
    [ "$run" -gt 0 ] && echo "$n $t0 $t1 $t2" >> "$work/times"
  done
  [ "$run" -gt 0 ] && echo "run $run/$RUNS done" >&2
done
python3 - "$work/times" "$RUNS" $SIZES <<'PY'
import statistics, sys
runs, sizes = sys.argv[2], sys.argv[3:]
status, render = {n: [] for n in sizes}, {n: [] for n in sizes}
for line in open(sys.argv[1]):
    n, t0, t1, t2 = line.split()
    status[n].append(float(t1) - float(t0))
    render[n].append(float(t2) - float(t1))
base_s, base_r = statistics.median(status[sizes[0]]), statistics.median(render[sizes[0]])
print(f"{'entries':>8} {'status s':>9} {'x':>6} {'render s':>9} {'x':>6}   (medians of {runs} runs)")
for n in sizes:
    s, r = statistics.median(status[n]), statistics.median(render[n])
    print(f"{n:>8} {s:9.3f} {s / base_s:6.2f} {r:9.3f} {r / base_r:6.2f}")
PY
