#include "shard.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

#include "case_batch.hpp"
#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "core/json_fields.hpp"
#include "core/strict_json.hpp"
#include "ssh_signature.hpp"
#include "validate.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Error invalid(const fs::path& file, const std::string& what) {
    return make_error(ErrorCode::InvalidInput, fmt::format("{}: {}", file.string(), what));
}

fs::path signature_file(const fs::path& result_file) {
    fs::path sig = result_file;
    sig += ".sig";
    return sig;
}

// The runner's signature over the file's exact bytes, checked before any field is believed:
// whoever can write the shared folder can write a file, but not its runner's signature.
Result<void> check_signature(const fs::path& file, const std::string& bytes,
                             const std::string& runner, const SignatureVerifier& runners) {
    const fs::path sig = signature_file(file);
    auto signature = read_input_file_if_exists(sig, kMaxSignatureBytes, "a signature");
    if (!signature) return signature.error();
    if (!signature->has_value())
        return invalid(file, fmt::format("not signed: no {} (a shard's runner signs each "
                                         "result: validate --out with --runner-key)",
                                         sig.filename().string()));
    auto verified = runners.verify(runner, bytes, **signature);
    if (!verified)
        return invalid(file, fmt::format("the runner's signature ({}) {}", sig.filename().string(),
                                         verified.error().message));
    return {};
}

Result<ShardResult> read_one(const fs::path& file, const SignatureVerifier& runners) {
    auto bytes = read_input_file(file, kMaxHarnessFileBytes, "a case result");
    if (!bytes) return bytes.error();
    auto parsed = parse_json_strict(bytes.value(), file.string());
    if (!parsed) return parsed.error();
    const json& j = parsed.value();
    auto runner = json_fields::read_json(file.string(), [&] {
        using namespace json_fields;
        expect_object(j, "",
                      {"format", "runner", "plugin", "strictness", "seed", "harness_version",
                       "stage", "spec", "result"},
                      {"shard"});
        if (text(j, "", "format") != kShardFormat)
            fail("format", fmt::format("is not \"{}\"", kShardFormat));
        return non_empty_text(j.at("runner"), "runner");
    });
    if (!runner) return runner.error();
    ACETATE_TRY(check_signature(file, bytes.value(), runner.value(), runners));
    return json_fields::read_json(file.string(), [&] {
        using namespace json_fields;
        ShardResult r;
        r.file = file;
        r.runner = runner.value();
        r.plugin = read_plugin_info(j.at("plugin"), "plugin");
        // In the range a run accepts: 0 would read as "not recorded" in the evidence, which
        // no promotion asks a waiver for.
        const int64_t strictness = integer(j, "", "strictness");
        if (strictness < kMinStrictness || strictness > kMaxStrictness)
            fail("strictness", fmt::format("{} is not a strictness a run takes ({} to {})",
                                           strictness, kMinStrictness, kMaxStrictness));
        r.strictness = int(strictness);
        r.seed = unsigned_integer(j, "", "seed");
        r.harness_version = text(j, "", "harness_version");
        // Another harness plans other cases and judges by other checks: its results are not
        // this harness's evidence.
        if (r.harness_version != kHarnessVersion)
            fail("harness_version", fmt::format("\"{}\" is not this harness (\"{}\")",
                                                r.harness_version, kHarnessVersion));
        auto stage = parse_validation_stage(text(j, "", "stage"));
        if (!stage ||
            (*stage != ValidationStage::AlphaTested && *stage != ValidationStage::Integrated))
            fail("stage", "must be ALPHA_TESTED or INTEGRATED");
        r.stage = *stage;
        if (const json* shard = optional(j, "shard")) {
            const std::string typed = text(*shard, "shard");
            auto selection = parse_shard_selection(typed, "shard");
            if (!selection)
                fail("shard",
                     fmt::format("\"{}\" is not K/N with 0 <= K < N <= {}", typed, kMaxShards));
            r.shard = selection.value();
        }
        r.spec = read_case_spec(j.at("spec"), "spec");
        r.result = read_case_result(j.at("result"), "result");
        if (r.result.id != r.spec.id)
            fail("result", fmt::format("is for case {}, spec for {}", r.result.id, r.spec.id));
        return r;
    });
}

}  // namespace

Result<void> write_shard_result(const ShardOutput& out, ValidationStage stage, const CaseSpec& spec,
                                const CaseResult& result) {
    const fs::path folder = out.folder / "results";
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec)
        return make_error(ErrorCode::Io,
                          fmt::format("{}: cannot create: {}", folder.string(), ec.message()));
    json j = {{"format", kShardFormat},
              {"runner", out.runner.name},
              {"harness_version", kHarnessVersion},
              {"plugin", to_json(out.plugin)},
              {"strictness", out.strictness},
              {"seed", out.seed},
              {"stage", to_string(stage)},
              {"spec", to_json(spec)},
              {"result", to_json(result)}};
    if (out.shard) j["shard"] = out.shard->label();
    const fs::path file = folder / (case_folder(spec.id) + ".json");
    const std::string bytes = j.dump(2) + "\n";
    auto signature = ssh_sign(out.runner.key, bytes, kCaseResultNamespace);
    if (!signature) return signature.error();
    ACETATE_TRY(write_file_atomically(signature_file(file), signature.value()));
    return write_file_atomically(file, bytes);
}

Result<std::vector<ShardResult>> read_shard_results(const std::vector<fs::path>& folders,
                                                    const SignatureVerifier& runners) {
    std::vector<ShardResult> all;
    std::map<std::string, fs::path> seen;
    for (const fs::path& folder : folders) {
        std::error_code ec;
        const fs::path results = folder / "results";
        if (!fs::is_directory(results, ec))
            return invalid(folder,
                           "no results/ folder (write one with validate --case ID --out "
                           "DIR)");
        std::vector<fs::path> files;
        for (const auto& item : fs::directory_iterator(results, ec))
            if (item.path().extension() == ".json") files.push_back(item.path());
        std::sort(files.begin(), files.end());
        if (files.empty()) return invalid(results, "holds no case result");
        for (const fs::path& file : files) {
            auto r = read_one(file, runners);
            if (!r) return r.error();
            if (!all.empty()) {
                const ShardResult& first = all.front();
                auto differs = [&](const char* what, const std::string& here,
                                   const std::string& there) -> Result<void> {
                    if (here == there) return {};
                    return invalid(file, fmt::format("from another {} ({} here, {} in {})", what,
                                                     here, there, first.file.string()));
                };
                ACETATE_TRY(differs("plugin", r->plugin.id + " " + r->plugin.version,
                                    first.plugin.id + " " + first.plugin.version));
                ACETATE_TRY(differs("binary", "SHA-256 " + r->plugin.binary_sha256.substr(0, 12),
                                    "SHA-256 " + first.plugin.binary_sha256.substr(0, 12)));
                ACETATE_TRY(differs("source", r->plugin.source_digest.substr(0, 12),
                                    first.plugin.source_digest.substr(0, 12)));
                ACETATE_TRY(differs("seed", std::to_string(r->seed), std::to_string(first.seed)));
                ACETATE_TRY(differs("strictness", std::to_string(r->strictness),
                                    std::to_string(first.strictness)));
                ACETATE_TRY(differs("harness", r->harness_version, first.harness_version));
            }
            if (auto [it, fresh] = seen.emplace(r->spec.id, file); !fresh)
                return invalid(file, fmt::format("case {} again (also in {})", r->spec.id,
                                                 it->second.string()));
            all.push_back(std::move(r.value()));
        }
    }
    return all;
}

Result<ValidationStage> merged_run_goal(const std::vector<ShardResult>& results,
                                        const std::vector<fs::path>& folders) {
    ValidationStage goal = ValidationStage::AlphaTested;
    for (const ShardResult& r : results)
        if (r.stage == ValidationStage::Integrated) goal = ValidationStage::Integrated;
    for (const fs::path& folder : folders) {
        std::error_code ec;
        if (!fs::exists(folder / "plan.json", ec)) continue;  // results of --case runs
        auto plan = read_shard_plan(folder);
        if (!plan) return plan.error();
        const ShardResult& first = results.front();
        if (plan->binary_sha256 != first.plugin.binary_sha256 ||
            plan->strictness != first.strictness || plan->seed != first.seed)
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: the plan of another run (its plugin binary, "
                                          "strictness or seed differ from the results')",
                                          (folder / "plan.json").string()));
        for (const PlannedCase& c : plan->cases)
            if (c.stage == ValidationStage::Integrated) goal = ValidationStage::Integrated;
    }
    return goal;
}

std::optional<std::string> missing_results(const std::vector<PlannedCase>& plan,
                                           const std::vector<ShardResult>& results,
                                           const fs::path& folder) {
    std::set<std::string> found;
    std::optional<unsigned> shard_count;  // none when the results came from --case runs
    for (const ShardResult& r : results) {
        found.insert(r.spec.id);
        if (r.shard && !shard_count) shard_count = r.shard->count;
    }
    std::vector<std::string> ids;
    for (const PlannedCase& c : plan) ids.push_back(c.id);
    const std::vector<std::string> owed = missing_by_shard(ids, found, shard_count);
    if (owed.empty()) return std::nullopt;
    const size_t missing = size_t(
        std::count_if(ids.begin(), ids.end(), [&](const auto& id) { return !found.count(id); }));
    return fmt::format(
        "merge: {} of the plan's {} cases have no result in {}:\n  {}\n"
        "run {} again (validate --shard K/N --out DIR), then merge again",
        missing, ids.size(), folder.string(), fmt::join(owed, "\n  "),
        shard_count ? "those shards" : "those cases");
}

}  // namespace acetate::harness
