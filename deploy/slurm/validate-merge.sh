#!/bin/bash
# The merge of one validation's shards (docs/cluster.md): judges and records the stages as one
# run would, and writes report.json, index.html and junit.xml into the run's folder. submit.sh
# starts it once every array task has ended, whatever their exit (afterany): a missing case is
# then named with the shard that owes it, and re-running that shard and this job completes it:
#   ACETATE_SHARDS=4 sbatch --array=2 deploy/slurm/validate-shard.sh PLUGIN STRICTNESS SEED
#   sbatch deploy/slurm/validate-merge.sh PLUGIN STRICTNESS SEED
# Exits 0 when every check passed, 1 when one failed or the merge was refused.
#SBATCH --job-name=acetate-merge
#SBATCH --cpus-per-task=1
#SBATCH --time=00:30:00
set -euo pipefail
usage="usage: sbatch validate-merge.sh PLUGIN [STRICTNESS] [SEED]"
plugin=${1:?$usage}
strictness=${2:-5}
seed=${3:-1}
: "${ACETATE_RESULTS:?the shared folder the shards wrote into}"
: "${ACETATE_REGISTRY:?the registry file the merge records the stages in}"
harness=${ACETATE_HARNESS:-acetate-harness}

sha=$(sha256sum "$plugin" | cut -c1-64)
out=$ACETATE_RESULTS/$sha-s$strictness-seed$seed
exec "$harness" --registry "$ACETATE_REGISTRY" merge "$out" --junit "$out/junit.xml"
