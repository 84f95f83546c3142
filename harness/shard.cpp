#include "shard.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "case_batch.hpp"
#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "core/json_fields.hpp"
#include "core/strict_json.hpp"
#include "validate.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Error invalid(const fs::path& file, const std::string& what) {
    return make_error(ErrorCode::InvalidInput, fmt::format("{}: {}", file.string(), what));
}

Result<ShardResult> read_one(const fs::path& file) {
    auto parsed = read_json_file(file, kMaxHarnessFileBytes, "a case result");
    if (!parsed) return parsed.error();
    const json& j = parsed.value();
    return json_fields::read_json(file.string(), [&] {
        using namespace json_fields;
        expect_object(j, "",
                      {"format", "plugin", "strictness", "seed", "harness_version", "stage", "spec",
                       "result"});
        if (text(j, "", "format") != kShardFormat)
            fail("format", fmt::format("is not \"{}\"", kShardFormat));
        ShardResult r;
        r.file = file;
        r.plugin = read_plugin_info(j.at("plugin"), "plugin");
        r.strictness = int(integer(j, "", "strictness"));
        r.seed = unsigned_integer(j, "", "seed");
        r.harness_version = text(j, "", "harness_version");
        auto stage = parse_validation_stage(text(j, "", "stage"));
        if (!stage ||
            (*stage != ValidationStage::AlphaTested && *stage != ValidationStage::Integrated))
            fail("stage", "must be ALPHA_TESTED or INTEGRATED");
        r.stage = *stage;
        r.spec = read_case_spec(j.at("spec"), "spec");
        r.result = read_case_result(j.at("result"), "result");
        if (r.result.id != r.spec.id)
            fail("result", fmt::format("is for case {}, spec for {}", r.result.id, r.spec.id));
        return r;
    });
}

}  // namespace

Result<void> write_shard_results(const fs::path& out, const PluginInfo& plugin, int strictness,
                                 uint64_t seed, ValidationStage stage,
                                 const std::vector<CaseSpec>& cases,
                                 const std::vector<CaseResult>& results) {
    const fs::path folder = out / "results";
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec)
        return make_error(ErrorCode::Io,
                          fmt::format("{}: cannot create: {}", folder.string(), ec.message()));
    for (size_t i = 0; i < cases.size() && i < results.size(); ++i) {
        const json j = {{"format", kShardFormat},
                        {"harness_version", kHarnessVersion},
                        {"plugin", to_json(plugin)},
                        {"strictness", strictness},
                        {"seed", seed},
                        {"stage", to_string(stage)},
                        {"spec", to_json(cases[i])},
                        {"result", to_json(results[i])}};
        ACETATE_TRY(
            write_file_atomically(folder / (case_folder(cases[i].id) + ".json"), j.dump(2) + "\n"));
    }
    return {};
}

Result<std::vector<ShardResult>> read_shard_results(const std::vector<fs::path>& folders) {
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
            auto r = read_one(file);
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

}  // namespace acetate::harness
