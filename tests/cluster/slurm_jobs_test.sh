#!/usr/bin/env bash
# The committed Slurm job files (deploy/slurm/), submitted to a real Slurm (slurm.sh) exactly
# as docs/cluster.md shows them. One scenario per run:
#   same-as-one-run      4 shards of a shipped plugin sharing one folder, 2 running at once:
#                        the merge gives one `validate`'s verdicts, digests, checks and
#                        registry entry
#   failing-plugin       every shard exits 0; the merge job fails, with its report and JUnit
#   resubmit             a cancelled task, submitted again alone, completes the merge
#   undescribable        a plugin that cannot be described fails its tasks
#
#   slurm_jobs_test.sh SCENARIO ENV_FILE SOURCE_DIR HARNESS PLUGIN_DIR TEST_PLUGIN_DIR WORK_DIR
set -euo pipefail
[ $# -eq 7 ] || { echo "usage: slurm_jobs_test.sh SCENARIO ENV_FILE SOURCE_DIR HARNESS PLUGIN_DIR TEST_PLUGIN_DIR WORK_DIR" >&2; exit 2; }
scenario=$1 env_file=$2 source_dir=$3 harness=$4 plugin_dir=$5 test_plugin_dir=$6 work=$7
fail() { echo "FAIL ($scenario): $*" >&2; exit 1; }
[ -f "$env_file" ] || fail "no Slurm: $env_file is missing (the slurm fixture did not start)"
set -a; . "$env_file"; set +a

rm -rf "$work"
mkdir -p "$work/plugins" "$work/results"
cd "$work"
# A maintainer (reviews) and a runner (signs results), listed as docs/cluster.md says.
ssh-keygen -q -t ed25519 -N '' -C maintainer -f maintainer </dev/null
ssh-keygen -q -t ed25519 -N '' -C runner -f runner </dev/null
{
  cat "$source_dir/validation/allowed_signers"
  echo "maintainer@cluster.test namespaces=\"acetate-signoff\" $(cut -d' ' -f1,2 maintainer.pub)"
  echo "runner@cluster.test namespaces=\"acetate-case-result\" $(cut -d' ' -f1,2 runner.pub)"
} > allowed_signers
export ACETATE_ALLOWED_SIGNERS=$work/allowed_signers ACETATE_SIGNING_KEY=$work/maintainer
export ACETATE_RUNNER=runner@cluster.test ACETATE_RUNNER_KEY=$work/runner
export ACETATE_RESULTS=$work/results ACETATE_REGISTRY=$work/registry.json
export ACETATE_HARNESS=$harness
# Two shards at once on this node (validate-shard.sh asks for 2 CPUs each by default).
export ACETATE_SBATCH="--cpus-per-task=1"
submit=$source_dir/deploy/slurm/submit.sh

review() {  # review PLUGIN REGISTRY
  "$harness" --registry "$2" review "$1" --reviewer maintainer@cluster.test --notes "read it" >/dev/null
}
# Waits for job $1 (every task of an array) to end; prints the highest number of its tasks
# seen running at once.
wait_job() {
  local most=0 running
  for _ in $(seq 3000); do
    running=$(squeue -h -j "$1" -t RUNNING 2>/dev/null | wc -l)
    [ "$running" -gt "$most" ] && most=$running
    if ! scontrol show job "$1" -o 2>/dev/null | grep -qE 'JobState=(PENDING|RUNNING|CONFIGURING|COMPLETING)'; then
      echo "$most"; return 0
    fi
    sleep 0.2
  done
  fail "job $1 did not end in 10 minutes: $(scontrol show job "$1" -o)"
}
# Each task's "JobState ExitCode", one line per task.
states() { scontrol show job "$1" -o | sed -E 's/.*JobState=([A-Z_]+).* ExitCode=([0-9:]+).*/\1 \2/'; }
job_ids() {  # from submit.sh's first line: "array A (N shards), merge M"
  sed -nE 's/^array ([0-9]+) .*merge ([0-9]+)$/\1 \2/p' <<< "$1"
}
run_folder() { echo "$ACETATE_RESULTS/$(sha256sum "$1" | cut -c1-64)-s$2-seed$3"; }

case $scenario in
same-as-one-run)
  plugin=$work/plugins/lighting.so
  cp "$plugin_dir/lighting.so" "$plugin"
  review "$plugin" single.json
  review "$plugin" registry.json
  started=$(date +%s%N)
  "$harness" --registry single.json validate "$plugin" --strictness 1 --seed 3 --report one >one.log ||
    fail "the single run failed: $(tail -n 3 one.log)"
  single_ms=$(( ($(date +%s%N) - started) / 1000000 ))
  started=$(date +%s%N)
  out=$(ACETATE_SHARDS=4 ACETATE_AT_ONCE=2 "$submit" "$plugin" 1 3)
  echo "$out"
  read -r array merge <<< "$(job_ids "$out")"
  most=$(wait_job "$array")
  wait_job "$merge" >/dev/null
  array_ms=$(( ($(date +%s%N) - started) / 1000000 ))
  echo "one validate (--jobs 2): $single_ms ms; the array (4 shards, 2 at once, --jobs 1) and its merge, from submit to the merge's end: $array_ms ms"
  echo "array tasks: $(states "$array" | tr '\n' ';') most running at once: $most"
  [ "$most" -eq 2 ] || fail "expected 2 shards running at once, saw at most $most"
  [ "$(states "$array" | grep -vc '^COMPLETED 0:0$')" -eq 0 ] || fail "a task did not complete"
  [ "$(states "$merge")" = "COMPLETED 0:0" ] || fail "the merge: $(states "$merge"); $(tail -n 5 "$(run_folder "$plugin" 1 3)/logs/merge.log")"
  python3 - one/report.json "$(run_folder "$plugin" 1 3)/report.json" single.json registry.json <<'PY' || fail "the array's result differs from one run's"
import json, sys
def cases(path):
    r = json.load(open(path))
    return {c["id"]: (c["verdict"], c.get("output_digest"),
                      sorted((k["check"], k["verdict"]) for k in c["checks"])) for c in r["cases"]}
def entry(path):
    e = json.load(open(path))["plugins"][0]
    e.pop("review", None)
    for stage in ("alpha_tested", "integrated"):
        e.get(stage, {}).pop("at", None)
        e.get(stage, {}).pop("report", None)
    return e
one, array = cases(sys.argv[1]), cases(sys.argv[2])
differ = sorted(k for k in one.keys() | array.keys() if one.get(k) != array.get(k))
for k in differ:
    print(f"{k}: one run {one.get(k)}, array {array.get(k)}")
if entry(sys.argv[3]) != entry(sys.argv[4]):
    print("registry entries differ:", entry(sys.argv[3]), entry(sys.argv[4]))
    sys.exit(1)
print(f"{len(one)} cases: same verdicts, digests and checks; registry entry the same "
      f"({entry(sys.argv[4])['stage']})")
sys.exit(1 if differ or entry(sys.argv[4])["stage"] != "INTEGRATED" else 0)
PY
  ;;
failing-plugin)
  plugin=$work/plugins/colour_at_zero.so
  cp "$test_plugin_dir/colour_at_zero.so" "$plugin"
  review "$plugin" registry.json
  out=$(ACETATE_SHARDS=2 "$submit" "$plugin" 1 3)
  read -r array merge <<< "$(job_ids "$out")"
  wait_job "$array" >/dev/null
  wait_job "$merge" >/dev/null
  folder=$(run_folder "$plugin" 1 3)
  [ "$(states "$array" | grep -vc '^COMPLETED 0:0$')" -eq 0 ] ||
    fail "a shard of a failing plugin did not exit 0: $(states "$array" | tr '\n' ';')"
  [ "$(states "$merge")" = "FAILED 1:0" ] || fail "the merge: $(states "$merge")"
  grep -q '"stage_after": "REVIEWED"' "$folder/report.json" || fail "report.json: not left REVIEWED"
  grep -q '<failure' "$folder/junit.xml" || fail "junit.xml has no failure"
  grep -q 'FAILED' "$folder/logs/merge.log" || fail "the merge's log does not say FAILED"
  echo "every shard exited 0; the merge failed the plugin, with report.json and junit.xml"
  ;;
resubmit)
  plugin=$work/plugins/well_behaved.so
  cp "$test_plugin_dir/well_behaved.so" "$plugin"
  review "$plugin" registry.json
  # One task at a time, so task 3 is still pending when it is cancelled.
  out=$(ACETATE_SHARDS=4 ACETATE_AT_ONCE=1 "$submit" "$plugin" 1 5)
  read -r array merge <<< "$(job_ids "$out")"
  scancel "${array}_3"
  wait_job "$array" >/dev/null
  wait_job "$merge" >/dev/null
  folder=$(run_folder "$plugin" 1 5)
  [ "$(states "$merge")" = "FAILED 1:0" ] || fail "the merge without task 3: $(states "$merge")"
  grep -q '^  shard 3/4: ' "$folder/logs/merge.log" ||
    fail "the merge does not name shard 3/4: $(cat "$folder/logs/merge.log")"
  "$harness" status --plan "$folder"
  # Task 3 again, alone, then the merge: as the comment of validate-merge.sh shows.
  again=$(ACETATE_SHARDS=4 sbatch --parsable --cpus-per-task=1 --array=3 \
    "$source_dir/deploy/slurm/validate-shard.sh" "$plugin" 1 5)
  again=${again%%;*}
  merge_again=$(sbatch --parsable --dependency="afterok:$again" \
    "$source_dir/deploy/slurm/validate-merge.sh" "$plugin" 1 5)
  merge_again=${merge_again%%;*}
  wait_job "$again" >/dev/null
  wait_job "$merge_again" >/dev/null
  [ "$(states "$merge_again")" = "COMPLETED 0:0" ] || fail "the second merge: $(states "$merge_again")"
  grep -q '"stage": "INTEGRATED"' registry.json || fail "the registry does not hold INTEGRATED"
  echo "the merge named shard 3/4; run again alone, it completed the merge (INTEGRATED)"
  ;;
undescribable)
  plugin=$work/plugins/not_a_plugin.so
  echo "text, not a library" > "$plugin"
  out=$(ACETATE_SHARDS=2 "$submit" "$plugin" 1 3)
  read -r array merge <<< "$(job_ids "$out")"
  wait_job "$array" >/dev/null
  wait_job "$merge" >/dev/null
  folder=$(run_folder "$plugin" 1 3)
  [ "$(states "$array" | grep -c '^FAILED 1:0$')" -eq 2 ] ||
    fail "the tasks did not fail: $(states "$array" | tr '\n' ';')"
  grep -q 'cannot describe the plugin' "$folder/logs/shard-0.log" ||
    fail "shard 0's log does not say why: $(cat "$folder/logs/shard-0.log")"
  echo "both tasks FAILED: $(grep -m1 "cannot describe" "$folder/logs/shard-0.log")"
  ;;
*) fail "no such scenario" ;;
esac
echo "PASS ($scenario)"
