#pragma once
// One validation split across processes or machines (docs/cluster.md): `validate --shard K/N
// --out DIR` (or `--case ID... --out DIR`) runs its cases and writes each result, as the case
// finishes, to DIR/results/<case>.json with what it was run on (the binary's SHA-256, the
// strictness, the seed, the harness, the shard); `merge DIR...` reads them back and judges and
// records the stages exactly as one run would (validate.cpp). Nothing here schedules anything:
// the cluster's own scheduler starts the shards.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "case_spec.hpp"
#include "core/result.hpp"
#include "registry.hpp"
#include "report.hpp"
#include "shard_plan.hpp"
#include "ssh_signature.hpp"

namespace acetate::harness {

inline constexpr const char* kShardFormat = "acetate-case-result/3";

// Who signs a shard's results: a name the allowed signers list for a key that may sign in the
// namespace kCaseResultNamespace, and that key's file (docs/cluster.md, "Runner keys").
struct Runner {
    std::string name;
    std::filesystem::path key;
};

struct ShardResult {
    PluginInfo plugin;
    int strictness = 0;
    uint64_t seed = 0;
    std::string harness_version;
    std::string runner;                                    // who ran it and signed the file
    std::optional<ShardSelection> shard;                   // --shard K/N, when it ran as one
    ValidationStage stage = ValidationStage::AlphaTested;  // the stage the case belongs to
    CaseSpec spec;
    CaseResult result;
    std::filesystem::path file;  // where it was read from
};

// What every result of one shard says it ran on, and where it goes.
struct ShardOutput {
    std::filesystem::path folder;  // --out
    PluginInfo plugin;
    int strictness = 0;
    uint64_t seed = 0;
    Runner runner;
    std::optional<ShardSelection> shard;
};

// Writes one case's file under `out.folder`/results/, atomically, and beside it its runner's
// SSH signature over the file's exact bytes (`<case>.json.sig`, written first, so a result
// file never stands without one). Called as each case finishes: a shard killed later keeps it.
Result<void> write_shard_result(const ShardOutput& out, ValidationStage stage, const CaseSpec& spec,
                                const CaseResult& result);

// Every result under each folder's results/, checked to belong to one run: each signed by the
// runner it names, with a key `runners` allows in kCaseResultNamespace, over its exact bytes;
// the same plugin binary and source, strictness, seed and harness; each case once.
// InvalidInput naming the file and what is wrong otherwise (or naming the folder when it
// holds no result).
Result<std::vector<ShardResult>> read_shard_results(
    const std::vector<std::filesystem::path>& folders, const SignatureVerifier& runners);

// For a merge: the stage the shards' run was asked to reach. INTEGRATED when a result is of
// that stage, or when the plan a shard left in one of `folders` (plan.json) has an integration
// case: a run's few integration cases may all belong to a shard that has not run yet, and the
// merge must then name them as owed rather than judge the alpha stage alone. A plan.json that
// is there but cannot be read, or is another run's, is an error naming it.
Result<ValidationStage> merged_run_goal(const std::vector<ShardResult>& results,
                                        const std::vector<std::filesystem::path>& folders);

// For a merge: every case of `plan` with no result in `results` (read from `folder`), named in
// one error by the shard that owes it (shard_plan.hpp, missing_by_shard), so that one
// re-submission completes the run; nothing when every case has one.
std::optional<std::string> missing_results(const std::vector<PlannedCase>& plan,
                                           const std::vector<ShardResult>& results,
                                           const std::filesystem::path& folder);

}  // namespace acetate::harness
