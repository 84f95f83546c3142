#!/bin/bash
# Runs one validation on Kubernetes (docs/cluster.md): copies the plugin onto the shared
# volume, starts the Indexed Job of ACETATE_SHARDS shards, waits for it to end (completed or
# failed), runs the merge Job, and copies the report, the JUnit and the registry back.
#
#   deploy/kubernetes/submit.sh [--print] PLUGIN [STRICTNESS] [SEED]
#
# --print writes the manifests it would apply, filled in, and runs nothing.
# Needs, once per cluster (docs/cluster.md, "Kubernetes"): the image (deploy/image/), the
# Secret acetate-runner-key (the runner's key) and the ConfigMap acetate-allowed-signers.
# Environment:
#   ACETATE_IMAGE      the image every pod runs (required)
#   ACETATE_RUNNER     the runner's name in the allowed signers (required)
#   ACETATE_REGISTRY   the registry file here: copied onto the volume before the run (the
#                      shards read it) and back after it (the merge records in it) (required)
#   ACETATE_SHARDS     the number of shards (default 4)
#   ACETATE_AT_ONCE    at most this many shards running at once (default: all of them)
#   ACETATE_BACK       where the report, JUnit and registry come back (default ./acetate-results)
#   ACETATE_WAIT       seconds to wait for each Job (default 7200)
#   KUBECTL            kubectl, with its options (default kubectl)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
print=0
[ "${1:-}" = --print ] && { print=1; shift; }
[ $# -ge 1 ] && [ $# -le 3 ] || { echo "usage: submit.sh [--print] PLUGIN [STRICTNESS] [SEED]" >&2; exit 2; }
[ -f "$1" ] || { echo "submit.sh: $1: no such plugin file" >&2; exit 2; }
plugin=$1 strictness=${2:-5} seed=${3:-1}
shards=${ACETATE_SHARDS:-4}
at_once=${ACETATE_AT_ONCE:-$shards}
for name in ACETATE_IMAGE ACETATE_RUNNER ACETATE_REGISTRY; do
  [ -n "${!name:-}" ] || { echo "submit.sh: $name is not set (see the top of this file)" >&2; exit 2; }
done
for pair in "STRICTNESS:$strictness" "SEED:$seed" "ACETATE_SHARDS:$shards" "ACETATE_AT_ONCE:$at_once"; do
  [[ "${pair#*:}" =~ ^[0-9]+$ ]] ||
    { echo "submit.sh: ${pair%%:*} must be a whole number, got \"${pair#*:}\"" >&2; exit 2; }
done
sha=$(sha256sum "$plugin" | cut -c1-64)
# Kubernetes names: lower-case letters, digits and '-', at most 63 characters.
run=${sha:0:16}-s$strictness-seed$seed
file=$(basename "$plugin")
render() {
  sed -e "s|@RUN@|$run|g" -e "s|@SHARDS@|$shards|g" -e "s|@AT_ONCE@|$at_once|g" \
    -e "s|@IMAGE@|$ACETATE_IMAGE|g" -e "s|@RUNNER@|$ACETATE_RUNNER|g" \
    -e "s|@PLUGIN_FILE@|$file|g" -e "s|@STRICTNESS@|$strictness|g" -e "s|@SEED@|$seed|g" "$1"
}
if [ "$print" = 1 ]; then
  for manifest in volume-claim transfer-pod validate-job merge-job; do
    echo "---"
    render "$here/$manifest.yaml"
  done
  exit 0
fi

read -r -a kubectl <<< "${KUBECTL:-kubectl}"
wait_s=${ACETATE_WAIT:-7200}
# Waits for a Job to end, completed or failed (kubectl wait takes one condition only);
# prints which.
wait_job() {
  local state
  for _ in $(seq "$((wait_s / 5))"); do
    state=$("${kubectl[@]}" get job "$1" -o 'jsonpath={.status.conditions[?(@.status=="True")].type}')
    case $state in *Complete*) echo Complete; return 0 ;; *Failed*) echo Failed; return 0 ;; esac
    sleep 5
  done
  echo "submit.sh: job $1 did not end in $wait_s s" >&2
  exit 1
}
render "$here/volume-claim.yaml" | "${kubectl[@]}" apply -f -
render "$here/transfer-pod.yaml" | "${kubectl[@]}" apply -f -
"${kubectl[@]}" wait --for=condition=Ready pod/acetate-transfer --timeout=600s
"${kubectl[@]}" exec acetate-transfer -- mkdir -p /validation/plugins /validation/results
"${kubectl[@]}" cp "$plugin" "acetate-transfer:/validation/plugins/$file"
if [ -f "$ACETATE_REGISTRY" ]; then
  "${kubectl[@]}" cp "$ACETATE_REGISTRY" acetate-transfer:/validation/registry.json
fi
render "$here/validate-job.yaml" | "${kubectl[@]}" apply -f -
echo "shards: $(wait_job "acetate-validate-$run")"
render "$here/merge-job.yaml" | "${kubectl[@]}" apply -f -
merged=$(wait_job "acetate-merge-$run")
"${kubectl[@]}" logs "job/acetate-merge-$run" || true
back=${ACETATE_BACK:-acetate-results}/$run
mkdir -p "$back"
for f in "results/$run/report.json" "results/$run/index.html" "results/$run/junit.xml" registry.json; do
  "${kubectl[@]}" cp "acetate-transfer:/validation/$f" "$back/$(basename "$f")" || echo "submit.sh: no $f" >&2
done
cp "$back/registry.json" "$ACETATE_REGISTRY" 2>/dev/null || true
echo "merge: $merged; report, JUnit and registry in $back (the registry also in $ACETATE_REGISTRY)"
[ "$merged" = Complete ]
