#include "shard_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "core/json_fields.hpp"
#include "core/number_text.hpp"
#include "core/strict_json.hpp"
#include "report.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path plan_file(const fs::path& folder) {
    return folder / "plan.json";
}

json to_json(const ShardPlan& plan) {
    json cases = json::array();
    for (size_t i = 0; i < plan.cases.size(); ++i)
        cases.push_back(
            {{"id", plan.cases[i].id},
             {"stage", to_string(plan.cases[i].stage)},
             {"shard", ShardSelection{unsigned(i % plan.shards), plan.shards}.label()}});
    return {{"format", kShardPlanFormat},
            {"plugin",
             {{"id", plan.plugin_id},
              {"version", plan.plugin_version},
              {"binary_sha256", plan.binary_sha256}}},
            {"strictness", plan.strictness},
            {"seed", plan.seed},
            {"shards", plan.shards},
            {"cases", cases}};
}

// What makes two plans the same run, in words for the refusal.
std::string run_of(const ShardPlan& p) {
    return fmt::format("{} {} (SHA-256 {}), strictness {}, seed {}, {} shards", p.plugin_id,
                       p.plugin_version, p.binary_sha256.substr(0, 12), p.strictness, p.seed,
                       p.shards);
}

// One result file's case id and verdict, for counting only: `merge` verifies signatures.
Result<std::pair<std::string, Verdict>> peek_result(const fs::path& file) {
    auto bytes = read_input_file(file, kMaxHarnessFileBytes, "a case result");
    if (!bytes) return bytes.error();
    auto parsed = parse_json_strict(bytes.value(), file.string());
    if (!parsed) return parsed.error();
    return json_fields::read_json(file.string(), [&] {
        const CaseResult r =
            read_case_result(json_fields::required(*parsed, "", "result"), "result");
        return std::pair{r.id, r.verdict};
    });
}

}  // namespace

std::vector<PlannedCase> plan_of_run(const PluginInfo& plugin, int strictness, uint64_t seed,
                                     bool integration) {
    std::vector<PlannedCase> plan;
    for (const CaseSpec& c : plan_cases(plugin, strictness, seed, true, false, {}))
        plan.push_back({c.id, ValidationStage::AlphaTested});
    if (integration)
        for (const CaseSpec& c : plan_cases(plugin, strictness, seed, false, true, {}))
            plan.push_back({c.id, ValidationStage::Integrated});
    return plan;
}

std::string ShardSelection::label() const {
    return fmt::format("{}/{}", index, count);
}
std::string ShardSelection::folder() const {
    return fmt::format("{}-of-{}", index, count);
}

Result<ShardSelection> parse_shard_selection(std::string_view text, std::string_view label) {
    const size_t slash = text.find('/');
    if (slash == std::string_view::npos)
        return make_error(
            ErrorCode::InvalidInput,
            fmt::format("{}: must be K/N (shard K of N, K counted from 0), got \"{}\"", label,
                        text));
    auto count = number_text::unsigned_integer(text.substr(slash + 1), fmt::format("{}: N", label),
                                               1, kMaxShards);
    if (!count) return count.error();
    auto index = number_text::unsigned_integer(text.substr(0, slash), fmt::format("{}: K", label),
                                               0, count.value() - 1);
    if (!index) return index.error();
    return ShardSelection{unsigned(index.value()), unsigned(count.value())};
}

Result<void> write_shard_plan(const fs::path& folder, const ShardPlan& plan) {
    const fs::path file = plan_file(folder);
    auto there = read_input_file_if_exists(file, kMaxHarnessFileBytes, "a shard plan");
    if (!there) return there.error();
    if (there->has_value()) {
        auto existing = read_shard_plan(folder);
        if (!existing) return existing.error();
        if (run_of(existing.value()) != run_of(plan))
            return make_error(
                ErrorCode::InvalidInput,
                fmt::format("{}: the plan of another run ({}); this shard is of {}: give each run "
                            "its own folder",
                            file.string(), run_of(existing.value()), run_of(plan)));
    }
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec)
        return make_error(ErrorCode::Io,
                          fmt::format("{}: cannot create: {}", folder.string(), ec.message()));
    return write_file_atomically(file, to_json(plan).dump(2) + "\n");
}

Result<ShardPlan> read_shard_plan(const fs::path& folder) {
    const fs::path file = plan_file(folder);
    auto bytes = read_input_file(file, kMaxHarnessFileBytes, "a shard plan");
    if (!bytes) return bytes.error();
    auto parsed = parse_json_strict(bytes.value(), file.string());
    if (!parsed) return parsed.error();
    const json& j = parsed.value();
    return json_fields::read_json(file.string(), [&] {
        using namespace json_fields;
        expect_object(j, "", {"format", "plugin", "strictness", "seed", "shards", "cases"});
        if (text(j, "", "format") != kShardPlanFormat)
            fail("format", fmt::format("is not \"{}\"", kShardPlanFormat));
        ShardPlan plan;
        const json& plugin = j.at("plugin");
        expect_object(plugin, "plugin", {"id", "version", "binary_sha256"});
        plan.plugin_id = text(plugin, "plugin", "id");
        plan.plugin_version = text(plugin, "plugin", "version");
        plan.binary_sha256 = text(plugin, "plugin", "binary_sha256");
        plan.strictness = int(unsigned_integer(j, "", "strictness", 1000));
        plan.seed = unsigned_integer(j, "", "seed");
        plan.shards = unsigned(unsigned_integer(j, "", "shards", kMaxShards));
        if (plan.shards == 0) fail("shards", "must be at least 1");
        const json& cases = array(j.at("cases"), "cases");
        for (size_t i = 0; i < cases.size(); ++i) {
            const std::string path = fmt::format("cases[{}]", i);
            expect_object(cases[i], path, {"id", "stage", "shard"});
            PlannedCase c;
            c.id = non_empty_text(cases[i].at("id"), path + ".id");
            auto stage = parse_validation_stage(text(cases[i], path, "stage"));
            if (!stage) fail(path + ".stage", "must be ALPHA_TESTED or INTEGRATED");
            c.stage = *stage;
            plan.cases.push_back(std::move(c));
        }
        return plan;
    });
}

std::vector<std::string> missing_by_shard(const std::vector<std::string>& plan_ids,
                                          const std::set<std::string>& found,
                                          std::optional<unsigned> shards) {
    std::map<unsigned, std::vector<std::string>> owed;  // by shard index
    for (size_t i = 0; i < plan_ids.size(); ++i)
        if (!found.count(plan_ids[i]))
            owed[shards ? unsigned(i % *shards) : 0].push_back(plan_ids[i]);
    std::vector<std::string> lines;
    for (const auto& [index, ids] : owed)
        lines.push_back(fmt::format(
            "{}{} case{}: {}",
            shards ? fmt::format("shard {}: ", ShardSelection{index, *shards}.label()) : "",
            ids.size(), ids.size() == 1 ? "" : "s", fmt::join(ids, ", ")));
    return lines;
}

int run_shard_status(const fs::path& folder) {
    auto plan = read_shard_plan(folder);
    if (!plan) {
        std::fprintf(stderr, "acetate-harness: %s\n", plan.error().message.c_str());
        return 1;
    }
    const ShardPlan& p = plan.value();
    std::map<std::string, Verdict> found;
    std::error_code ec;
    for (const auto& item : fs::directory_iterator(folder / "results", ec)) {
        if (item.path().extension() != ".json") continue;
        auto peeked = peek_result(item.path());
        if (!peeked) {
            std::fprintf(stderr, "acetate-harness: %s\n", peeked.error().message.c_str());
            return 1;
        }
        found[peeked->first] = peeked->second;
    }
    std::printf("%s: %s %s, strictness %d, seed %llu: %zu cases in %u shards\n",
                plan_file(folder).string().c_str(), p.plugin_id.c_str(), p.plugin_version.c_str(),
                p.strictness, (unsigned long long)p.seed, p.cases.size(), p.shards);
    size_t total_found = 0, total_failed = 0;
    for (unsigned k = 0; k < p.shards; ++k) {
        size_t owned = 0, have = 0, failed = 0;
        for (size_t i = k; i < p.cases.size(); i += p.shards) {
            ++owned;
            auto it = found.find(p.cases[i].id);
            if (it == found.end()) continue;
            ++have;
            if (is_failing(it->second)) ++failed;
        }
        total_found += have;
        total_failed += failed;
        std::printf("  shard %-9s %3zu of %3zu results%s%s\n",
                    ShardSelection{k, p.shards}.label().c_str(), have, owned,
                    failed ? fmt::format(", {} failing", failed).c_str() : "",
                    have == owned ? "  (complete)" : "");
    }
    std::printf("%zu of %zu results%s; %s\n", total_found, p.cases.size(),
                total_failed ? fmt::format(", {} failing", total_failed).c_str() : "",
                total_found == p.cases.size() ? "ready to merge" : "not complete");
    return 0;
}

}  // namespace acetate::harness
