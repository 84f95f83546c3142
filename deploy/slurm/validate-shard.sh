#!/bin/bash
# One task of a Slurm job array: shard $SLURM_ARRAY_TASK_ID of $ACETATE_SHARDS of one
# validation (docs/cluster.md). submit.sh submits it with its merge; to run one shard again:
#   ACETATE_SHARDS=4 sbatch --array=2 deploy/slurm/validate-shard.sh PLUGIN [STRICTNESS] [SEED]
# The harness cuts the shard's cases from the plan itself (--shard K/N) and writes each result
# as its case finishes. It exits 0 once its results are written, even when a check failed (the
# merge judges them), and non-zero only when it could not run: then the task is FAILED.
#SBATCH --job-name=acetate-shard
#SBATCH --cpus-per-task=2
#SBATCH --time=01:00:00
set -euo pipefail
usage="usage: ACETATE_SHARDS=N sbatch --array=0-<N-1> validate-shard.sh PLUGIN [STRICTNESS] [SEED]"
plugin=${1:?$usage}
strictness=${2:-5}
seed=${3:-1}
# Every variable the task needs, each named when it is missing (sbatch passes the submitting
# shell's environment on by default: --export=ALL).
: "${ACETATE_SHARDS:?the number of shards N: the array task ids are 0 to N-1}"
: "${ACETATE_RESULTS:?a folder every node sees (shared storage); each run gets a folder in it}"
: "${ACETATE_REGISTRY:?the registry file every node reads (only the merge writes it)}"
: "${ACETATE_RUNNER:?the runner name the allowed signers list for ACETATE_RUNNER_KEY}"
: "${ACETATE_RUNNER_KEY:?the runner key that signs each result (docs/cluster.md, Runner keys)}"
: "${SLURM_ARRAY_TASK_ID:?not an array task: submit with sbatch --array=0-<N-1>}"
harness=${ACETATE_HARNESS:-acetate-harness}

# One folder per run: the binary, the strictness and the seed make it one.
sha=$(sha256sum "$plugin" | cut -c1-64)
exec "$harness" --registry "$ACETATE_REGISTRY" validate "$plugin" \
  --strictness "$strictness" --seed "$seed" --jobs "${SLURM_CPUS_PER_TASK:-1}" \
  --shard "$SLURM_ARRAY_TASK_ID/$ACETATE_SHARDS" \
  --out "$ACETATE_RESULTS/$sha-s$strictness-seed$seed"
