#pragma once
// One validation split across processes or machines (docs/cluster.md): `validate --list-cases`
// prints the plan; `validate --case ID... --out DIR` runs those cases and writes each result
// to DIR/results/<case>.json with what it was run on (the binary's SHA-256, the strictness,
// the seed, the harness); `merge DIR...` reads them back and judges and records the stages
// exactly as one run would (validate.cpp). Nothing here schedules anything: the cluster's own
// scheduler starts the shards.

#include <filesystem>
#include <string>
#include <vector>

#include "case_spec.hpp"
#include "core/result.hpp"
#include "registry.hpp"
#include "report.hpp"

namespace acetate::harness {

inline constexpr const char* kShardFormat = "acetate-case-result/1";

struct ShardResult {
    PluginInfo plugin;
    int strictness = 0;
    uint64_t seed = 0;
    std::string harness_version;
    ValidationStage stage = ValidationStage::AlphaTested;  // the stage the case belongs to
    CaseSpec spec;
    CaseResult result;
    std::filesystem::path file;  // where it was read from
};

// Writes one file per case under `out`/results/, each atomically.
Result<void> write_shard_results(const std::filesystem::path& out, const PluginInfo& plugin,
                                 int strictness, uint64_t seed, ValidationStage stage,
                                 const std::vector<CaseSpec>& cases,
                                 const std::vector<CaseResult>& results);

// Every result under each folder's results/, checked to belong to one run: the same plugin
// binary and source, strictness, seed and harness, and each case once. InvalidInput naming
// the file and what differs otherwise (or naming the folder when it holds no result).
Result<std::vector<ShardResult>> read_shard_results(
    const std::vector<std::filesystem::path>& folders);

}  // namespace acetate::harness
