#!/usr/bin/env bash
# The sanitizer stage of CI: builds the unit and CLI suites (and the `acetate` they drive, the
# plugins they load) and the fuzzers with clang, AddressSanitizer and UndefinedBehaviorSanitizer
# in build-sanitize/, runs both suites (any sanitizer report fails them), then runs the fuzzers
# of our own parsers (scene, registry, pipeline cache) for ACETATE_FUZZ_SECONDS each (default
# 60, seed 1, so a run is repeatable; one fuzzer per core at a time) from the committed seed
# corpus in fuzz/corpus/. The image fuzzer, whose decoding is OpenImageIO's behind our own
# checks (the input reader, the EXR header check, size limits), runs for
# ACETATE_FUZZ_IMAGE_SECONDS (default 30). A failing input is written to
# build-sanitize/fuzz-findings/ and fails the stage: add it to the corpus with a regression
# test, then fix the reader.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${ACETATE_SANITIZE_BUILD_DIR:-$root/build-sanitize}
seconds=${ACETATE_FUZZ_SECONDS:-60}
start=$SECONDS

bash "$root/scripts/install-packages.sh" clang libclang-rt-14-dev

echo "== Configuring and building the sanitizer build in $build (clang, ASan + UBSan)"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DACETATE_WERROR=ON -DACETATE_LINE_TABLES_ONLY=ON -DACETATE_SANITIZE=ON -DACETATE_BUILD_FUZZERS=ON -DACETATE_BUILD_BENCHMARKS=OFF >/dev/null
fuzzers=(scene registry pipeline_cache image)
targets=(acetate_unit_tests acetate_cli_tests lighting bloom water specular fire)
for f in "${fuzzers[@]}"; do targets+=("fuzz_$f"); done
cmake --build "$build" -j"$(nproc)" $(printf -- '--target %s ' "${targets[@]}")

# Every report is an error; leaks of the Vulkan driver and layers are theirs, not ours.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:check_initialization_order=1
export LSAN_OPTIONS=suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export ACETATE_VALIDATION=1
mkdir -p "$build/test-cache/mesa" "$build/test-cache/xdg"
export MESA_SHADER_CACHE_DIR=$build/test-cache/mesa XDG_CACHE_HOME=$build/test-cache/xdg

echo "== acetate_unit_tests under ASan (leaks included) + UBSan"
"$build/tests/acetate_unit_tests" --gtest_brief=1
# The CLI suite runs `acetate` end to end on lavapipe, whose JIT-compiled shaders allocate
# memory that LeakSanitizer cannot attribute (the stack ends in code with no module), so leaks
# are not judged there; every memory error and all undefined behaviour still are.
# Its tests run programs and wait on them, so it runs as one shard per core (gtest's own
# sharding: every test in exactly one shard); each shard's output is shown when it has ended.
cli_shards=$(nproc)
echo "== acetate_cli_tests under ASan (no leak check) + UBSan, $cli_shards shards at once"
for ((i = 0; i < cli_shards; i++)); do
  ASAN_OPTIONS=${ASAN_OPTIONS/detect_leaks=1/detect_leaks=0} GTEST_TOTAL_SHARDS=$cli_shards \
    GTEST_SHARD_INDEX=$i "$build/tests/acetate_cli_tests" --gtest_brief=1 \
    >"$build/cli-shard-$i.log" 2>&1 &
done
cli_status=0
for ((i = 0; i < cli_shards; i++)); do wait -n || cli_status=1; done
cat "$build"/cli-shard-*.log
if [ "$cli_status" -ne 0 ]; then
  echo "sanitize: acetate_cli_tests failed under the sanitizers (the shards' output is above)" >&2
  exit 1
fi

findings=$build/fuzz-findings
mkdir -p "$findings"
# One fuzzer: from a copy of its seed corpus, for its time budget; its log and exit status go to
# $findings/<name>.log and .status.
fuzz_one() {
  local f=$1 work leaks=1 status
  work=$(mktemp -d)
  cp "$root/fuzz/corpus/$f/"* "$work/"
  local budget=(-max_total_time="$seconds" -seed=1)
  # A PNG with a damaged ancillary chunk (fuzz/corpus/image/png-bad-oFFs-chunk.bin, this
  # fuzzer's first finding) leaks one string: its stack ends in libstdc++ with no frame of ours,
  # on OpenImageIO's libpng error path. Leaks are therefore not judged for the image fuzzer;
  # memory errors and undefined behaviour still are.
  # OpenEXR allocating what a header attribute declares (2 GB for a 141-byte file) is stopped
  # by host/scene/exr_header_check.cpp before OpenImageIO reads the file.
  if [ "$f" = image ]; then
    leaks=0
    budget=(-max_total_time="${ACETATE_FUZZ_IMAGE_SECONDS:-30}" -seed=1)
  fi
  ASAN_OPTIONS=${ASAN_OPTIONS/detect_leaks=1/detect_leaks=$leaks} \
    "$build/fuzz/fuzz_$f" "${budget[@]}" -max_len=65536 -timeout=10 -rss_limit_mb=4096 \
    -detect_leaks=$leaks \
    -artifact_prefix="$findings/$f-" -print_final_stats=1 "$work" >"$findings/$f.log" 2>&1 \
    && status=0 || status=$?
  rm -rf "$work"
  echo "$status" >"$findings/$f.status"
}
# A fuzzer is one process on one core, so they run one per core (ACETATE_FUZZ_JOBS, default
# nproc): with 2 cores the four take 2 minutes instead of 3.5, the same inputs each.
fuzz_jobs=${ACETATE_FUZZ_JOBS:-$(nproc)}
echo "== fuzzers: ${fuzzers[*]} ($fuzz_jobs at a time)"
running=0
for f in "${fuzzers[@]}"; do
  fuzz_one "$f" &
  running=$((running + 1))
  if [ "$running" -ge "$fuzz_jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait
for f in "${fuzzers[@]}"; do
  echo "== fuzz_$f"
  grep -E '^(Done|stat::number_of_executed_units|stat::new_units_added)|ERROR|SUMMARY' \
    "$findings/$f.log" || true
  status=$(cat "$findings/$f.status" 2>/dev/null || echo "no status")
  if [ "$status" != 0 ]; then
    tail -n 40 "$findings/$f.log"
    echo "sanitize: fuzz_$f found a failing input (exit $status); see $findings" >&2
    exit 1
  fi
done
echo "sanitize: clean in $((SECONDS - start)) s"
