#!/bin/bash
# Submits one validation to Slurm: a job array of ACETATE_SHARDS shards, and the merge, which
# starts when every task has ended (docs/cluster.md). Prints the two job ids and the command
# that shows progress.
#
#   deploy/slurm/submit.sh PLUGIN [STRICTNESS] [SEED]
#
# Needs, in the environment (passed on to every task):
#   ACETATE_SHARDS      the number of shards (default 4)
#   ACETATE_AT_ONCE     at most this many shards running at once (default: no limit)
#   ACETATE_RESULTS     a folder on storage every node sees; each run gets a folder in it
#   ACETATE_REGISTRY    the registry file: the shards read it, the merge writes it
#   ACETATE_RUNNER, ACETATE_RUNNER_KEY   the runner that signs each result
#   ACETATE_HARNESS     acetate-harness, when it is not on the nodes' PATH
#   ACETATE_SBATCH      more sbatch options for both jobs, e.g. "--partition=gpu --account=me"
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
[ $# -ge 1 ] && [ $# -le 3 ] || { echo "usage: submit.sh PLUGIN [STRICTNESS] [SEED]" >&2; exit 2; }
[ -f "$1" ] || { echo "submit.sh: $1: no such plugin file" >&2; exit 2; }
plugin=$(realpath "$1")
strictness=${2:-5}
seed=${3:-1}
export ACETATE_SHARDS=${ACETATE_SHARDS:-4}
for name in ACETATE_RESULTS ACETATE_REGISTRY ACETATE_RUNNER ACETATE_RUNNER_KEY; do
  [ -n "${!name:-}" ] || { echo "submit.sh: $name is not set (see the top of this file)" >&2; exit 2; }
done
[[ "$ACETATE_SHARDS" =~ ^[1-9][0-9]*$ ]] ||
  { echo "submit.sh: ACETATE_SHARDS must be a whole number of at least 1, got \"$ACETATE_SHARDS\"" >&2; exit 2; }
throttle=
if [ -n "${ACETATE_AT_ONCE:-}" ]; then
  [[ "$ACETATE_AT_ONCE" =~ ^[1-9][0-9]*$ ]] ||
    { echo "submit.sh: ACETATE_AT_ONCE must be a whole number of at least 1, got \"$ACETATE_AT_ONCE\"" >&2; exit 2; }
  throttle=%$ACETATE_AT_ONCE
fi
sha=$(sha256sum "$plugin" | cut -c1-64)
out=$ACETATE_RESULTS/$sha-s$strictness-seed$seed
mkdir -p "$out/logs"
read -r -a extra <<< "${ACETATE_SBATCH:-}"

array=$(sbatch --parsable "${extra[@]}" --array="0-$((ACETATE_SHARDS - 1))$throttle" \
  --output="$out/logs/shard-%a.log" "$here/validate-shard.sh" "$plugin" "$strictness" "$seed")
array=${array%%;*}
merge=$(sbatch --parsable "${extra[@]}" --dependency="afterany:$array" \
  --output="$out/logs/merge.log" "$here/validate-merge.sh" "$plugin" "$strictness" "$seed")
merge=${merge%%;*}
echo "array $array ($ACETATE_SHARDS shards), merge $merge"
echo "results: $out"
echo "progress: ${ACETATE_HARNESS:-acetate-harness} status --plan $out"
