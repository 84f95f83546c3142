#pragma once
// How one validation is cut into shards for a scheduler's job array (docs/cluster.md):
// `validate --shard K/N --out DIR` runs the cases whose position in the plan, counted from 0,
// is K modulo N, and writes the plan it cut (DIR/plan.json) so that `status --plan DIR` can show
// progress while the array runs and `merge` can say which shard owes a missing case. The plan
// file is the shards' word, used for progress only: `merge` plans again from the plugin itself.

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "case_spec.hpp"
#include "core/result.hpp"
#include "registry.hpp"

namespace acetate::harness {

inline constexpr const char* kShardPlanFormat = "acetate-shard-plan/1";
// More shards than this is a typing mistake, not a cluster: a plan at strictness 10 has a few
// hundred cases.
inline constexpr unsigned kMaxShards = 4096;

// Shard `index` of `count`: the cases at positions index, index + count, ... of the plan.
// Counted from 0, as Slurm's array task ids and Kubernetes' completion indexes are, so a job
// script passes its index as it is.
struct ShardSelection {
    unsigned index = 0;
    unsigned count = 1;
    bool owns(size_t position) const { return position % count == index; }
    std::string label() const;   // "K/N", as typed on the command line
    std::string folder() const;  // "K-of-N", the shard's own folder under DIR/shards/
    bool operator==(const ShardSelection&) const = default;
};
// "K/N" with 0 <= K < N <= kMaxShards, each read by the project's one number reader;
// `label` names the flag or field in the one-line error.
Result<ShardSelection> parse_shard_selection(std::string_view text, std::string_view label);

struct PlannedCase {
    std::string id;
    ValidationStage stage = ValidationStage::AlphaTested;
};

// One run's plan as the shards cut it.
struct ShardPlan {
    std::string plugin_id, plugin_version, binary_sha256;
    int strictness = 0;
    uint64_t seed = 0;
    unsigned shards = 1;
    std::vector<PlannedCase> cases;  // in plan order: case i belongs to shard i mod shards
};

// Every case id of a run, in the order shards cut it: the alpha stage's, then (with
// `integration`) the integration stage's as if no companion were integrated (their ids do not
// depend on companions). `validate --list-cases` prints this, `--shard` cuts it, `merge`
// checks against it.
std::vector<PlannedCase> plan_of_run(const PluginInfo& plugin, int strictness, uint64_t seed,
                                     bool integration);

// Writes DIR/plan.json atomically. Every shard of one run writes the same bytes, so shards
// starting together cannot disagree; a plan of another run already there (another plugin,
// binary, strictness, seed or number of shards) is refused: one folder holds one run.
Result<void> write_shard_plan(const std::filesystem::path& folder, const ShardPlan& plan);
// DIR/plan.json, read strictly (InvalidInput naming the file and field otherwise).
Result<ShardPlan> read_shard_plan(const std::filesystem::path& folder);

// The cases of `plan_ids` with no result in `found`, one line per shard that owes some:
// "shard 1/4: 3 cases: a, b, c"; with no shard count (results of --case runs), one line.
std::vector<std::string> missing_by_shard(const std::vector<std::string>& plan_ids,
                                          const std::set<std::string>& found,
                                          std::optional<unsigned> shards);

// `acetate-harness status --plan DIR`: the plan against the results found, a line per shard
// (results found, how many failed, whether it is complete), then the total. Results are
// counted, not verified: `merge` verifies every signature. Returns the exit status: 0, or 1
// when the folder holds no plan or a file cannot be read.
int run_shard_status(const std::filesystem::path& folder);

}  // namespace acetate::harness
