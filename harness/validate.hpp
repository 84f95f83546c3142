#pragma once
// `acetate-harness validate`: describe the plugin in a child, run the alpha stage's cases (and,
// when they pass, the integration stage's) each in its own child, compare across children
// (determinism), record evidence in the registry, write the reports. docs/harness.md.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "case_batch.hpp"
#include "case_spec.hpp"
#include "core/result.hpp"
#include "registry.hpp"
#include "shard_plan.hpp"

namespace acetate::harness {

inline constexpr const char* kHarnessVersion = "acetate-harness 0.1.0";
// The strictness a run takes (--strictness); the default is the registry's kDefaultStrictness.
inline constexpr int kMinStrictness = 1;
inline constexpr int kMaxStrictness = 10;
// The exit status of a child that could not run its case for reasons of the harness or the
// machine (an unreadable case file, no Vulkan device); any other non-zero status is the
// plugin's doing and reported as CRASH.
inline constexpr int kChildSetupFailure = 3;
// How the describe child reports its own errors (the host refused the descriptor, plugin.json
// could not be written): this exit status and a last line that starts with the marker. Both,
// since the plugin's code runs in that child and may exit with any status; every other ending
// is reported as the plugin's (describe_in_child).
inline constexpr int kDescribeFailure = 4;
inline constexpr const char* kDescribeErrorMarker = "acetate-harness describe: error: ";

struct ValidateOptions {
    std::filesystem::path plugin;
    ValidationStage up_to = ValidationStage::Integrated;  // --stage
    int strictness = 5;
    uint64_t seed = 1;
    std::filesystem::path report_directory;           // --report; default ./harness-report/<stem>
    std::optional<std::filesystem::path> json_file;   // --json
    std::optional<std::filesystem::path> junit_file;  // --junit: JUnit XML for CI
    unsigned jobs = 2;
    double timeout_seconds = 120;
    std::vector<std::string> only_cases;  // --case: run just these (no evidence is recorded)
    unsigned repeat = 1;                  // --repeat: runs per case, each in a fresh process
    // --cases-per-process: cases run one after another in one child (case_batch.hpp); 1 gives
    // each its own (as --repeat does).
    unsigned cases_per_process = kDefaultCasesPerProcess;
    std::optional<uint64_t> shuffle_seed;  // --shuffle: run every case's runs in random order
    std::filesystem::path registry;
    std::optional<std::filesystem::path> signoffs;  // committed sign-offs to import
    std::filesystem::path allowed_signers;          // the keys that verify every sign-off
    std::filesystem::path references;               // blessed images: <root>/<plugin id>/
    // Fan-out (shard.hpp, docs/cluster.md): --list-cases prints the plan and runs nothing;
    // --out DIR writes each selected case's result there (nothing recorded); `merge` judges
    // and records the results read from merge_from instead of running cases.
    bool list_cases = false;
    std::optional<std::filesystem::path> out;
    // --shard K/N (with --out): run the plan's cases at positions K, K + N, ... (shard_plan.hpp)
    // and write the plan to DIR/plan.json.
    std::optional<ShardSelection> shard;
    // With --out: who signs each result (--runner, --runner-key; shard.hpp). merge verifies
    // the signatures against the allowed signers in the case-result namespace.
    std::string runner;
    std::optional<std::filesystem::path> runner_key;
    std::vector<std::filesystem::path> merge_from;
    std::vector<std::filesystem::path> plugin_paths;  // where integrated companions are found
    std::filesystem::path self;                       // this executable, for the children
};

// Returns the exit status: 0 when no check failed, 1 when one did or the run could not start.
// A run with --out (a shard) returns 0 once every result is written, failing or not (the merge
// judges them), and 1 only when it could not run: a scheduler sees failures of its own.
int run_validate(const ValidateOptions& options);
// `validate --list-cases`: the case ids of a run of `options.plugin` at its strictness, seed
// and stage, one per line, in plan order (plan_of_run). Returns the exit status.
int run_list_cases(const ValidateOptions& options);

// What the plugin declares, read in this process (the `describe` child does this). With
// `required_sha256`, a file whose bytes hash otherwise is refused before it is loaded.
Result<PluginInfo> describe_plugin(const std::filesystem::path& file,
                                   const std::string& required_sha256 = {});
// The same in a child process, so a crashing entry point is a clean error here.
Result<PluginInfo> describe_in_child(const std::filesystem::path& self,
                                     const std::filesystem::path& plugin,
                                     const std::filesystem::path& work_directory,
                                     double timeout_seconds);

}  // namespace acetate::harness
