// The `acetate-harness` command line. Subcommands and flags are binding: other tools call them
// (docs/harness.md). validate / review / promote / status for people; describe and run-case are
// what validate starts its child processes with.

#include <fmt/format.h>
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <thread>

#include "case_runner.hpp"
#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "core/strict_json.hpp"
#include "fuzz.hpp"
#include "registry.hpp"
#include "registry_location.hpp"
#include "validate.hpp"

namespace {

namespace fs = std::filesystem;
using namespace acetate;
using namespace acetate::harness;

int fail(const std::string& message) {
    std::fprintf(stderr, "acetate-harness: %s\n", message.c_str());
    return 1;
}

// Children are started from /proc/self/exe: this very binary, even if the file on disk is
// rebuilt while a run goes on.
fs::path self_path() {
    return "/proc/self/exe";
}

// A child dies with its parent: a harness killed (Ctrl-C, a closed pipe) leaves no case
// running on without its time limit.
bool tie_to_parent() {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    return getppid() != 1;  // the parent may already be gone
}

// A private folder for a describe child's files.
Result<fs::path> scratch_directory() {
    std::string name = (fs::temp_directory_path() / "acetate-harness-XXXXXX").string();
    if (!mkdtemp(name.data()))
        return make_error(ErrorCode::Io, fmt::format("{}: cannot create a temporary folder: {}",
                                                     name, std::strerror(errno)));
    return fs::path(name);
}

Result<PluginInfo> describe(const fs::path& plugin) {
    auto scratch = scratch_directory();
    if (!scratch) return scratch.error();
    auto info = describe_in_child(self_path(), plugin, *scratch, 60);
    std::error_code ec;
    fs::remove_all(*scratch, ec);
    return info;
}

int run_review(const fs::path& plugin, const fs::path& registry, const std::string& reviewer,
               const std::string& notes) {
    auto info = describe(plugin);
    if (!info) return fail(info.error().message);
    auto updated = Registry::update(
        registry,
        [&](Registry& r) {
            return r.record_review(info->id, info->version, info->binary_sha256,
                                   info->source_digest, reviewer, notes);
        },
        registry_markdown_path(registry));
    if (!updated) return fail(updated.error().message);
    auto loaded = Registry::load(registry);
    const ValidationStage stage =
        loaded ? loaded->effective_stage(info->id, info->version, info->binary_sha256,
                                         info->source_digest)
               : ValidationStage::Reviewed;
    std::printf("%s %s: review by %s recorded for source %s; now %s (registry %s)\n",
                info->id.c_str(), info->version.c_str(), reviewer.c_str(),
                info->source_digest.substr(0, 12).c_str(), to_string(stage),
                registry.string().c_str());
    return 0;
}

int run_promote(const fs::path& plugin, const fs::path& registry, const std::string& by,
                const std::string& notes) {
    auto info = describe(plugin);
    if (!info) return fail(info.error().message);
    auto updated = Registry::update(
        registry,
        [&](Registry& r) -> Result<void> {
            // The promotion vouches for this file: it must be the binary the evidence is for.
            const ValidationStage stage = r.effective_stage(
                info->id, info->version, info->binary_sha256, info->source_digest);
            if (stage == ValidationStage::Validated) return {};  // nothing to do; said below
            if (stage != ValidationStage::Integrated)
                return make_error(
                    ErrorCode::InvalidInput,
                    fmt::format("{} {}: this binary (SHA-256 {}) is {}, not INTEGRATED: run "
                                "acetate-harness validate {} first",
                                info->id, info->version, info->binary_sha256.substr(0, 12),
                                to_string(stage), plugin.string()));
            return r.promote(info->id, info->version, by, notes);
        },
        registry_markdown_path(registry));
    if (!updated) return fail(updated.error().message);
    auto after = Registry::load(registry);
    const RegistryEntry* entry = after ? after->find(info->id, info->version) : nullptr;
    if (entry && entry->promotion && entry->promotion->by != by)
        std::printf(
            "%s %s: already VALIDATED for this binary (promoted by %s at %s); nothing "
            "recorded\n",
            info->id.c_str(), info->version.c_str(), entry->promotion->by.c_str(),
            entry->promotion->at.c_str());
    else
        std::printf("%s %s: promoted to VALIDATED by %s (registry %s)\n", info->id.c_str(),
                    info->version.c_str(), by.c_str(), registry.string().c_str());
    return 0;
}

int run_status(const fs::path& registry_file, bool as_json) {
    auto registry = Registry::load(registry_file);
    if (!registry) return fail(registry.error().message);
    if (as_json) {
        auto j = nlohmann::json::parse(registry->to_json());
        j["registry"] = registry_file.string();
        for (auto& entry : j["plugins"]) {
            const RegistryEntry* e =
                registry->find(entry["id"].get<std::string>(), entry["version"].get<std::string>());
            if (e) entry["stage"] = to_string(e->stage());
        }
        std::printf("%s\n", j.dump(2).c_str());
        return 0;
    }
    std::printf("registry %s\n", registry_file.string().c_str());
    if (registry->entries().empty()) {
        std::printf("no plugins recorded yet\n");
        return 0;
    }
    std::printf("%-26s %-8s %-13s %-12s %-12s %s\n", "plugin", "version", "stage", "binary",
                "source", "records");
    for (const RegistryEntry& e : registry->entries()) {
        std::string records;
        auto add = [&](const std::string& text) {
            records += (records.empty() ? "" : "; ") + text;
        };
        if (e.review) add(fmt::format("reviewed by {} {}", e.review->by, e.review->at));
        if (e.alpha_tested) add(fmt::format("alpha-tested {}", e.alpha_tested->at));
        if (e.integrated) add(fmt::format("integrated {}", e.integrated->at));
        if (e.promotion) add(fmt::format("promoted by {} {}", e.promotion->by, e.promotion->at));
        std::printf("%-26s %-8s %-13s %-12s %-12s %s\n", e.id.c_str(), e.version.c_str(),
                    to_string(e.stage()), e.binary_sha256.substr(0, 12).c_str(),
                    e.source_digest.substr(0, 12).c_str(), records.c_str());
    }
    std::printf("readable copy: %s\n", registry_markdown_path(registry_file).string().c_str());
    return 0;
}

// Child: what the plugin declares, as JSON. Its own errors end with kDescribeFailure and one
// line starting with kDescribeErrorMarker, so the parent can tell them from the plugin ending
// the process (describe_in_child). An exception here is the harness's: the SDK catches the
// plugin's at the C boundary.
int run_describe(const fs::path& plugin, const fs::path& out) {
    if (!tie_to_parent()) return kChildSetupFailure;
    auto fail = [](const std::string& message) {
        std::fprintf(stderr, "%s%s\n", kDescribeErrorMarker, message.c_str());
        std::fflush(stderr);
        return kDescribeFailure;
    };
    try {
        auto info = describe_plugin(plugin);
        if (!info) return fail(info.error().message);
        auto written = write_file_atomically(out, to_json(info.value()).dump(2));
        if (!written) return fail(written.error().message);
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    return 0;
}

// Child: one case.
int run_case_command(const fs::path& plugin_info, const fs::path& case_file, const fs::path& out,
                     const fs::path& report) {
    if (!tie_to_parent()) return kChildSetupFailure;
    auto fail = [](const std::string& message) {
        std::fprintf(stderr, "acetate-harness: %s\n", message.c_str());
        return kChildSetupFailure;
    };
    auto read = [](const fs::path& file) -> Result<nlohmann::json> {
        return read_json_file(file, kMaxHarnessFileBytes, "a harness file");
    };
    auto info_json = read(plugin_info);
    if (!info_json) return fail(info_json.error().message);
    auto info = plugin_info_from_json(*info_json, plugin_info.string());
    if (!info) return fail(info.error().message);
    auto spec_json = read(case_file);
    if (!spec_json) return fail(spec_json.error().message);
    auto spec = case_spec_from_json(*spec_json, case_file.string());
    if (!spec) return fail(spec.error().message);
    auto result = run_case({info.value(), spec.value(), out, report});
    if (!result) return fail(result.error().message);
    auto written = write_file_atomically(case_result_file(out), to_json(result.value()).dump(2));
    if (!written) return fail(written.error().message);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    // Children are reaped with waitpid: a SIGCHLD ignored by whoever started us must not be
    // inherited (the kernel would then reap them itself and every case would look hung).
    signal(SIGCHLD, SIG_DFL);
    CLI::App app{
        "acetate-harness: validates Acetate effect plugins and keeps the registry of "
        "their validation stages (docs/harness.md)"};
    app.require_subcommand(1);
    std::optional<fs::path> registry_flag;
    app.add_option("--registry", registry_flag,
                   "Registry file (default: $ACETATE_REGISTRY, else the build tree's "
                   "validation/registry.json, or $XDG_DATA_HOME/acetate/registry.json when "
                   "installed)");

    ValidateOptions validate;
    std::string stage_name = "integrated";
    std::optional<fs::path> report_flag, signoffs_flag;
    bool no_signoffs = false;
    validate.jobs = std::max(1u, std::thread::hardware_concurrency());
    CLI::App* v = app.add_subcommand("validate", "Run the automated checks and record evidence");
    v->add_option("plugin", validate.plugin, "The plugin's shared library")->required();
    v->add_option("--stage", stage_name, "Highest stage to run: alpha-tested | integrated")
        ->check(CLI::IsMember({"alpha-tested", "integrated"}))
        ->default_val("integrated");
    v->add_option("--strictness", validate.strictness, "1-10: how many cases and seeds")
        ->check(CLI::Range(1, 10))
        ->default_val(5);
    v->add_option("--seed", validate.seed, "Seed of every case's inputs and parameters")
        ->default_val(1);
    v->add_option("--report", report_flag, "Report folder (default ./harness-report/<plugin>)");
    v->add_option("--json", validate.json_file, "Also write the JSON report here");
    v->add_option("--junit", validate.junit_file,
                  "Also write JUnit XML here (one suite per stage, one test per case)");
    v->add_option("--jobs", validate.jobs, "Cases run at once")->check(CLI::Range(1, 256));
    v->add_option("--timeout", validate.timeout_seconds, "Seconds a case may take")
        ->check(CLI::Range(1.0, 3600.0))
        ->default_val(120);
    v->add_option("--case", validate.only_cases,
                  "Run only this case (repeatable), e.g. to reproduce a failure; records nothing");
    v->add_option("--plugin-path", validate.plugin_paths,
                  "Where to find the other integrated plugins (then the default search path)");
    v->add_option("--signoffs", signoffs_flag,
                  "Committed sign-offs to import (default: the source tree's, or the "
                  "installation's share/acetate/validation/signoffs.json)");
    v->add_flag("--no-signoffs", no_signoffs, "Import no committed sign-offs");
    bool shuffle = false;
    v->add_option("--repeat", validate.repeat,
                  "Run every case N times, each in a fresh process; a case whose verdict "
                  "changes is FLAKY")
        ->check(CLI::Range(1, 1000))
        ->default_val(1);
    CLI::Option* shuffle_flag =
        v->add_flag("--shuffle", shuffle, "Run the cases (and their repeats) in random order");
    v->add_option("--shuffle-seed", validate.shuffle_seed,
                  "The random order's seed (implies --shuffle; printed by every shuffled run)")
        ->excludes(shuffle_flag);

    FuzzOptions fuzz;
    std::string fuzz_duration = "10m";
    std::optional<fs::path> fuzz_report;
    fuzz.jobs = validate.jobs;
    CLI::App* f = app.add_subcommand(
        "fuzz", "Draw cases from the whole input model until the time is up; shrink a failure");
    f->add_option("plugin", fuzz.plugin, "The plugin's shared library")->required();
    f->add_option("--duration", fuzz_duration, "How long to draw cases: 90s, 10m, 1h")
        ->default_val("10m");
    f->add_option("--jobs", fuzz.jobs, "Cases run at once")->check(CLI::Range(1, 256));
    f->add_option("--seed", fuzz.seed, "Seed of the drawn cases")->default_val(1);
    f->add_option("--timeout", fuzz.timeout_seconds, "Seconds a case may take")
        ->check(CLI::Range(1.0, 3600.0))
        ->default_val(120);
    f->add_option("--report", fuzz_report, "Report folder (default ./harness-fuzz/<plugin>)");
    f->add_option("--reproduce", fuzz.reproduce, "Run only this case file (a shrunk case)");

    fs::path review_plugin, promote_plugin;
    std::string reviewer, review_notes, promoter, promote_notes;
    CLI::App* r = app.add_subcommand("review", "Record a review sign-off (REVIEWED)");
    r->add_option("plugin", review_plugin)->required();
    r->add_option("--reviewer", reviewer, "Who reviewed the source")->required();
    r->add_option("--notes", review_notes, "What was reviewed")->required();
    CLI::App* p = app.add_subcommand("promote", "INTEGRATED -> VALIDATED");
    p->add_option("plugin", promote_plugin)->required();
    p->add_option("--by", promoter, "Who promotes it")->required();
    p->add_option("--notes", promote_notes, "Why");
    bool status_json = false;
    CLI::App* s = app.add_subcommand("status", "Show the registry");
    s->add_flag("--json", status_json, "As JSON");

    fs::path describe_plugin_file, describe_out;
    CLI::App* d = app.add_subcommand("describe", "(child) Write what a plugin declares as JSON");
    d->add_option("plugin", describe_plugin_file)->required();
    d->add_option("--out", describe_out)->required();
    fs::path case_info, case_file, case_out, case_report;
    CLI::App* c = app.add_subcommand("run-case", "(child) Run one case of a validation");
    c->add_option("--plugin-info", case_info)->required();
    c->add_option("--case", case_file)->required();
    c->add_option("--out", case_out)->required();
    c->add_option("--report", case_report)->required();

    // Options of the whole command (--registry) may also follow the subcommand.
    for (CLI::App* sub : {v, r, p, s}) sub->fallthrough();
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    const fs::path registry = registry_path(registry_flag);
    try {
        if (f->parsed()) {
            auto seconds = parse_duration(fuzz_duration);
            if (!seconds) return fail(seconds.error().message);
            fuzz.duration_seconds = *seconds;
            std::error_code ec;
            if (!fs::is_regular_file(fuzz.plugin, ec))
                return fail(fmt::format("{}: no such plugin file", fuzz.plugin.string()));
            fuzz.plugin = fs::absolute(fuzz.plugin);
            fuzz.report_directory = fs::absolute(
                fuzz_report ? *fuzz_report : fs::path("harness-fuzz") / fuzz.plugin.stem());
            if (fuzz.reproduce) fuzz.reproduce = fs::absolute(*fuzz.reproduce);
            fuzz.self = self_path();
            return run_fuzz(fuzz);
        }
        if (v->parsed()) {
            validate.up_to = stage_name == "alpha-tested" ? ValidationStage::AlphaTested
                                                          : ValidationStage::Integrated;
            validate.registry = registry;
            validate.self = self_path();
            validate.signoffs = no_signoffs     ? std::nullopt
                                : signoffs_flag ? signoffs_flag
                                                : default_signoffs_path();
            // Absolute: children run with their own folders, and the scenes they write name
            // their images by path.
            validate.report_directory = fs::absolute(
                report_flag ? *report_flag : fs::path("harness-report") / validate.plugin.stem());
            std::error_code ec;
            if (!fs::is_regular_file(validate.plugin, ec))
                return fail(fmt::format("{}: no such plugin file", validate.plugin.string()));
            validate.plugin = fs::absolute(validate.plugin);
            if (shuffle) validate.shuffle_seed = std::random_device{}();
            return run_validate(validate);
        }
        if (r->parsed()) return run_review(review_plugin, registry, reviewer, review_notes);
        if (p->parsed()) return run_promote(promote_plugin, registry, promoter, promote_notes);
        if (s->parsed()) return run_status(registry, status_json);
        if (d->parsed()) return run_describe(describe_plugin_file, describe_out);
        if (c->parsed()) return run_case_command(case_info, case_file, case_out, case_report);
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    return 2;
}
