#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <sstream>

#include "case_batch.hpp"
#include "case_repeat.hpp"
#include "case_runner.hpp"
#include "contract_checks.hpp"
#include "core/atomic_file.hpp"
#include "core/child_process.hpp"
#include "core/input_file.hpp"
#include "core/strict_json.hpp"
#include "neighbours.hpp"
#include "plugins/plugin_loader.hpp"
#include "references.hpp"
#include "registry_location.hpp"
#include "report.hpp"
#include "report_junit.hpp"
#include "shard.hpp"
#include "ssh_signature.hpp"
#include "validate_registry.hpp"
#include "validate_support.hpp"
#include "waivers.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;
using nlohmann::json;

std::string reproduce_command(const ValidateOptions& o, const std::string& case_id) {
    std::string command = fmt::format(
        "acetate-harness validate {} --strictness {} --seed {} --timeout {} --case {} "
        "--registry {} --report {}",
        shell_word(o.plugin.string()), o.strictness, o.seed, o.timeout_seconds, shell_word(case_id),
        shell_word(o.registry.string()), shell_word(o.report_directory.string() + "-repro"));
    if (o.repeat > 1) command += fmt::format(" --repeat {}", o.repeat);
    if (o.shuffle_seed) command += fmt::format(" --shuffle-seed {}", *o.shuffle_seed);
    for (const fs::path& dir : o.plugin_paths)
        command += " --plugin-path " + shell_word(dir.string());
    return command;
}

std::string host_name() {
    char name[256] = {};
    if (gethostname(name, sizeof name - 1) != 0) return "host";
    return case_folder(name);
}

namespace {

CheckResult* find_check(CaseResult& c, const std::string& name) {
    for (CheckResult& check : c.checks)
        if (check.check == name) return &check;
    return nullptr;
}

}  // namespace

// The determinism runs compare across processes: every run's digest must match the first's
// (two fresh processes, with different poisons; one that rendered other scenes and frames
// first; one without the validation layer, as users run their hosts). A plugin that is not
// deterministic cannot be judged for state isolation (its images differ anyway), so that check is
// skipped rather than failed twice for one fault.
void compare_across_processes(std::vector<CaseResult>& results, const fs::path& report_dir) {
    CaseResult* first = nullptr;
    for (CaseResult& r : results)
        if (r.id == "determinism/run-1") first = &r;
    for (CaseResult& r : results) {
        if (!first || &r == first || r.id.rfind("determinism/", 0) != 0) continue;
        if (first->output_digest.empty() || r.output_digest.empty()) continue;
        CheckResult* check = find_check(r, "determinism");
        if (!check || first->output_digest == r.output_digest) continue;
        const bool history = r.id == "determinism/after-history";
        const bool without_layer = r.id == "determinism/without-layer";
        check->verdict = Verdict::Fail;
        check->message = fmt::format(
            "{} rendered the same case differently from a fresh process (digests {} and {}){}",
            history         ? "a process that had rendered other scenes and frames first"
            : without_layer ? "a process without the Vulkan validation layer, as users run "
                              "their hosts,"
                            : "a second process",
            first->output_digest.substr(0, 12), r.output_digest.substr(0, 12),
            history || without_layer
                ? ""
                : "; their poisons differed, so reading unwritten memory shows here");
        // Where: the first floor whose saved outputs differ.
        for (int f = 0; f < 8; ++f) {
            const auto name = fmt::format("output.floor{}.exr", f);
            auto a =
                load_image(report_dir / "cases" / case_folder(first->id) / name, ImageRole::Colour);
            auto b = load_image(report_dir / "cases" / case_folder(r.id) / name, ImageRole::Colour);
            if (!a || !b) break;
            const ImageDifference diff = compare_exact(*a, *b, f);
            if (diff.pixels == 0) continue;
            check->violations = diff.pixels;
            check->examples = diff.examples;
            check->message += fmt::format("; floor {}: {} pixels differ, first at ({}, {})", f,
                                          diff.pixels, diff.examples[0].x, diff.examples[0].y);
            break;
        }
        r.verdict = std::max(r.verdict, Verdict::Fail);
    }
    // Only a difference between fresh renders means the plugin is not deterministic; one that
    // shows after other loads and frames only is history, which state-isolation judges too,
    // and one without the layer only is the layer's.
    bool deterministic = true;
    for (const CaseResult& r : results)
        for (const CheckResult& c : r.checks)
            if (c.check == "determinism" && c.verdict == Verdict::Fail &&
                r.id != "determinism/after-history" && r.id != "determinism/without-layer")
                deterministic = false;
    if (deterministic) return;
    for (CaseResult& r : results) {
        CheckResult* state = find_check(r, "state-isolation");
        if (!state || state->verdict == Verdict::Pass) continue;
        std::printf("note: %s: state-isolation not judged: the plugin is not deterministic\n",
                    r.id.c_str());
        state->verdict = Verdict::Skip;
        state->message =
            "not judged: the plugin is not deterministic (see determinism), so its "
            "images differ between renders anyway";
        state->examples.clear();
        state->violations = 0;
        r.verdict = Verdict::Pass;
        for (const CheckResult& c : r.checks) r.verdict = std::max(r.verdict, c.verdict);
    }
}

bool all_pass(const std::vector<CaseResult>& results) {
    for (const CaseResult& r : results) {
        if (is_failing(r.verdict)) return false;
        for (const CheckResult& c : r.checks)
            if (is_failing(c.verdict)) return false;
    }
    return true;
}

std::vector<CompanionPlugin> find_companions(const Registry& registry, const PluginInfo& plugin,
                                             const std::vector<fs::path>& extra_paths,
                                             std::vector<std::string>& notes) {
    std::vector<CompanionPlugin> out;
    const auto directories = PluginLoader::default_directories(extra_paths);
    for (const RegistryEntry& e : registry.entries()) {
        if (e.id == plugin.id || e.stage() < ValidationStage::Integrated) continue;
        const std::string last = e.id.substr(e.id.rfind('.') + 1);
        bool found = false;
        for (const fs::path& dir : directories) {
            for (const fs::path& file : {dir / (e.id + ".so"), dir / (last + ".so")}) {
                std::error_code ec;
                if (found || !fs::is_regular_file(file, ec)) continue;
                auto sha = file_sha256(file);
                if (!sha || sha.value() != e.binary_sha256) continue;
                // Integrated, so trusted to load in-process: only the very bytes the registry
                // recorded (a file rewritten since the hash above is refused, not loaded).
                auto info = describe_plugin(file, e.binary_sha256);
                if (!info) continue;
                out.push_back(
                    {e.id, fs::absolute(file).string(), info->scope, info->binary_sha256});
                found = true;
            }
        }
        if (!found)
            notes.push_back(
                fmt::format("{} {} is {} but its recorded binary was not found on "
                            "the plugin search path; left out",
                            e.id, e.version, to_string(e.stage())));
    }
    return out;
}

void print_summary(const ValidationReport& report) {
    std::printf("\n%-26s %-8s %s\n", "check", "verdict", "cases");
    for (const CheckSummary& s : summarize_checks(report)) {
        std::string counts;
        for (const auto& [verdict, n] : s.cases)
            counts += fmt::format("{}{} {}", counts.empty() ? "" : ", ", n, to_string(verdict));
        std::printf("%-26s %-8s %s\n", s.check.c_str(), to_string(s.verdict), counts.c_str());
        if (!s.first_failure.empty() && s.verdict != Verdict::Pass)
            std::printf("    %s\n", s.first_failure.c_str());
    }
}

int run_list_cases(const ValidateOptions& o) {
    std::string scratch = (fs::temp_directory_path() / "acetate-harness-list-XXXXXX").string();
    if (!mkdtemp(scratch.data())) {
        std::fprintf(stderr, "acetate-harness: %s: cannot create a temporary folder\n",
                     scratch.c_str());
        return 1;
    }
    auto described = describe_in_child(o.self, o.plugin, scratch, o.timeout_seconds);
    std::error_code ec;
    fs::remove_all(scratch, ec);
    if (!described) {
        std::fprintf(stderr, "acetate-harness: %s\n", described.error().message.c_str());
        return 1;
    }
    auto scenes = find_reference_scenes(o.references, described->id);
    if (!scenes) {
        std::fprintf(stderr, "acetate-harness: %s\n", scenes.error().message.c_str());
        return 1;
    }
    described->reference_scenes = std::move(scenes.value());
    for (const PlannedCase& c :
         plan_of_run(*described, o.strictness, o.seed, o.up_to >= ValidationStage::Integrated))
        std::printf("%s\n", c.id.c_str());
    return 0;
}

}  // namespace acetate::harness
