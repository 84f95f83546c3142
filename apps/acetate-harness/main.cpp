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
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <thread>

#include "../flag_values.hpp"
#include "bless_command.hpp"
#include "case_batch.hpp"
#include "case_runner.hpp"
#include "core/atomic_file.hpp"
#include "core/fork_server.hpp"
#include "core/input_file.hpp"
#include "core/json_fields.hpp"
#include "core/number_text.hpp"
#include "core/output_paths.hpp"
#include "core/strict_json.hpp"
#include "fuzz.hpp"
#include "registry.hpp"
#include "registry_commands.hpp"
#include "registry_location.hpp"
#include "shard.hpp"
#include "ssh_signature.hpp"
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

// Child: cases, one after another (harness/case_runner.hpp): the i-th --case file's result in
// the i-th --out folder.
int run_cases_command(const fs::path& plugin_info, const std::vector<fs::path>& case_files,
                      const std::vector<fs::path>& outs, const fs::path& report) {
    if (!tie_to_parent()) return kChildSetupFailure;
    auto fail = [](const std::string& message) {
        std::fprintf(stderr, "acetate-harness: %s\n", message.c_str());
        return kChildSetupFailure;
    };
    if (case_files.size() != outs.size())
        return fail(fmt::format("run-case: {} --case files but {} --out folders", case_files.size(),
                                outs.size()));
    auto read = [](const fs::path& file) -> Result<nlohmann::json> {
        return read_json_file(file, kMaxHarnessFileBytes, "a harness file");
    };
    auto info_json = read(plugin_info);
    if (!info_json) return fail(info_json.error().message);
    auto info = plugin_info_from_json(*info_json, plugin_info.string());
    if (!info) return fail(info.error().message);
    std::vector<CaseContext> cases;
    for (size_t i = 0; i < case_files.size(); ++i) {
        auto spec_json = read(case_files[i]);
        if (!spec_json) return fail(spec_json.error().message);
        auto spec = case_spec_from_json(*spec_json, case_files[i].string());
        if (!spec) return fail(spec.error().message);
        cases.push_back({info.value(), spec.value(), outs[i], report});
    }
    auto ran = run_cases(cases);
    if (!ran) return fail(ran.error().message);
    return 0;
}

// --duration: seconds, or a number with s, m or h. The number goes through the one reader
// (finite, no sign '+', nothing after the unit); the wording of a refusal is the flag's own.
constexpr double kMaxFuzzSeconds = 365 * 24 * 3600.0;  // a year: longer is a typo, not a plan
Result<double> read_duration(const std::string& text) {
    const char unit = text.empty() ? '\0' : text.back();
    const double scale = unit == 'm' ? 60 : unit == 'h' ? 3600 : 1;
    const bool has_unit = unit == 's' || unit == 'm' || unit == 'h';
    auto number = number_text::finite_number(
        std::string_view(text).substr(0, text.size() - (has_unit ? 1 : 0)), "--duration", 0,
        std::numeric_limits<double>::max());
    if (number && *number > 0 && *number * scale <= kMaxFuzzSeconds) return *number * scale;
    if (number && *number > 0)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("--duration: must be at most {} seconds (a year), got {}",
                                      kMaxFuzzSeconds, text));
    return make_error(ErrorCode::InvalidInput,
                      fmt::format("--duration: expected seconds or a number with s, m or h "
                                  "(e.g. 90s, 10m), got {}",
                                  json_fields::json_quoted(text)));
}

// Every regular file under `folder` (the golden references, a shard's results/), each an
// input of the run. Symbolic links to folders are not followed: a loop cannot hang it.
void add_files_under(std::vector<RunFile>& inputs, const fs::path& folder,
                     const std::string& role) {
    std::error_code ec;
    for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file(ec)) inputs.push_back({it->path(), role});
}

// What validate and merge read besides the plugin: the registry, the keys, the sign-offs and
// the golden references.
std::vector<RunFile> recording_inputs(const ValidateOptions& o) {
    std::vector<RunFile> in{{o.registry, "the registry"},
                            {o.allowed_signers, "the allowed signers"},
                            {o.allowed_signers.parent_path() / "revoked_keys", "the revoked keys"}};
    if (o.signoffs) in.push_back({*o.signoffs, "the sign-offs"});
    add_files_under(in, o.references, "the golden references");
    return in;
}

// Outputs never replace inputs (core/output_paths.hpp), checked before any work: the files a
// flag names (--json, --junit, which must differ from each other too), then the files the run
// writes in its report folder and beside the registry.
Result<void> check_validate_outputs(const ValidateOptions& o, std::vector<RunFile> inputs) {
    std::vector<RunFile> named,
        written{{o.report_directory / "report.json", "--report"},
                {o.report_directory / "index.html", "--report"},
                {o.report_directory / "plugin.json", "--report"},
                {registry_markdown_path(o.registry), "the registry's readable copy"}};
    if (o.json_file) named.push_back({*o.json_file, "--json"});
    if (o.junit_file) named.push_back({*o.junit_file, "--junit"});
    ACETATE_TRY(check_outputs_spare_inputs(named, inputs));
    return check_outputs_spare_inputs(written, inputs);
}

// A shard signs every result it writes (shard.hpp): its runner's name and key, from the flags
// or the environment, and a trial signature before any case runs, so a missing, unreadable or
// passphrase-locked key stops the shard at once rather than after its cases.
Result<void> runner_identity(ValidateOptions& o) {
    if (o.runner.empty())
        if (const char* env = std::getenv("ACETATE_RUNNER"); env) o.runner = env;
    if (!o.runner_key)
        if (const char* env = std::getenv("ACETATE_RUNNER_KEY"); env && *env) o.runner_key = env;
    if (o.runner.empty() || !o.runner_key)
        return make_error(ErrorCode::InvalidInput,
                          "--out: each result is signed by the runner that produced it: give "
                          "--runner NAME and --runner-key FILE (or ACETATE_RUNNER and "
                          "ACETATE_RUNNER_KEY); docs/cluster.md, \"Runner keys\"");
    auto trial =
        ssh_sign(*o.runner_key, "acetate-harness: trial signature\n", kCaseResultNamespace);
    if (!trial)
        return make_error(ErrorCode::InvalidInput, "--runner-key: " + trial.error().message);
    return {};
}

// The program as its command line says; main() also makes it a fork server.
int run_harness(int argc, char** argv) {
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
    std::optional<fs::path> allowed_signers_flag, references_flag;
    app.add_option("--references", references_flag,
                   "The golden references' root, <DIR>/<plugin id>/manifest.json (default: "
                   "$ACETATE_REFERENCES, else validation/references)");
    app.add_option("--allowed-signers", allowed_signers_flag,
                   "The maintainers' keys that verify every sign-off (default: "
                   "$ACETATE_ALLOWED_SIGNERS, else validation/allowed_signers)");

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
    // Numbers, days and names go through the one reader (apps/flag_values.hpp): each
    // refusal is one line, and nothing wraps ("--seed -1") or passes as NaN ("--timeout nan").
    flags::add_number(v, "--strictness", validate.strictness, kMinStrictness, kMaxStrictness,
                      "1-10: how many cases and seeds");
    flags::add_number(v, "--seed", validate.seed, 0, UINT64_MAX,
                      "Seed of every case's inputs and parameters");
    v->add_option("--report", report_flag, "Report folder (default ./harness-report/<plugin>)");
    v->add_option("--json", validate.json_file, "Also write the JSON report here");
    v->add_option("--junit", validate.junit_file,
                  "Also write JUnit XML here (one suite per stage, one test per case)");
    flags::add_number(v, "--jobs", validate.jobs, 1, 256, "Cases run at once");
    flags::add_number(v, "--timeout", validate.timeout_seconds, 1.0, 3600.0,
                      "Seconds a case may take");
    v->add_option("--case", validate.only_cases,
                  "Run only this case (repeatable), e.g. to reproduce a failure; records nothing");
    v->add_flag("--list-cases", validate.list_cases,
                "Print the run's case ids, one per line, and run nothing (for a cluster: "
                "docs/cluster.md)");
    v->add_option("--out", validate.out,
                  "With --shard or --case: write each case's result to DIR/results/ for "
                  "`merge` as it finishes; record nothing; exit 0 once written, failing or not");
    v->add_option_function<std::string>(
         "--shard",
         [&validate](const std::string& text) {
             auto selection = parse_shard_selection(text, "--shard");
             if (!selection) throw CLI::ValidationError(selection.error().message);
             validate.shard = selection.value();
         },
         "With --out: run shard K of N (K from 0): the plan's cases at positions K, K+N, ...")
        ->type_name("K/N")
        ->excludes("--case")
        ->excludes("--list-cases");
    v->add_option("--runner", validate.runner,
                  "With --out: the name the allowed signers list for --runner-key, signed into "
                  "each result (default: $ACETATE_RUNNER)");
    v->add_option("--runner-key", validate.runner_key,
                  "With --out: the key that signs each result, allowed the namespace "
                  "acetate-case-result (default: $ACETATE_RUNNER_KEY)");
    v->add_option("--plugin-path", validate.plugin_paths,
                  "Where to find the other integrated plugins (then the default search path)");
    v->add_option("--signoffs", signoffs_flag,
                  "Committed sign-offs to import (default: the source tree's, or the "
                  "installation's share/acetate/validation/signoffs.json)");
    v->add_flag("--no-signoffs", no_signoffs, "Import no committed sign-offs");
    bool shuffle = false;
    flags::add_number(v, "--repeat", validate.repeat, 1, 1000,
                      "Run every case N times, each in a fresh process; a case whose verdict "
                      "changes is FLAKY");
    flags::add_number(v, "--cases-per-process", validate.cases_per_process, 1, 64,
                      "Cases run one after another in one child process, on one device (1: each "
                      "in its own; --repeat gives each run its own)");
    CLI::Option* shuffle_flag =
        v->add_flag("--shuffle", shuffle, "Run the cases (and their repeats) in random order");
    flags::add_number(v, "--shuffle-seed", validate.shuffle_seed, 0, UINT64_MAX,
                      "The random order's seed (implies --shuffle; printed by every shuffled "
                      "run)")
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
    flags::add_number(f, "--jobs", fuzz.jobs, 1, 256, "Cases run at once");
    flags::add_number(f, "--seed", fuzz.seed, 0, UINT64_MAX, "Seed of the drawn cases");
    flags::add_number(f, "--timeout", fuzz.timeout_seconds, 1.0, 3600.0, "Seconds a case may take");
    f->add_option("--report", fuzz_report, "Report folder (default ./harness-fuzz/<plugin>)");
    f->add_option("--reproduce", fuzz.reproduce, "Run only this case file (a shrunk case)");

    fs::path review_plugin, promote_plugin, waive_plugin;
    SignOffRequest review, promotion;
    std::optional<fs::path> key_flag;
    CLI::App* r = app.add_subcommand("review", "Sign a review of the plugin's source (REVIEWED)");
    r->add_option("plugin", review_plugin)->required();
    flags::add_name(r, "--reviewer", review.by,
                    "Who reviewed the source: the name validation/allowed_signers lists your "
                    "key under")
        ->required();
    r->add_option("--notes", review.notes, "What was reviewed")->required();
    CLI::App* p = app.add_subcommand("promote", "Sign the promotion INTEGRATED -> VALIDATED");
    p->add_option("plugin", promote_plugin)->required();
    flags::add_name(p, "--by", promotion.by, "Who promotes it: the name your key is listed under")
        ->required();
    p->add_option("--notes", promotion.notes, "Why");
    for (CLI::App* signing : {r, p})
        signing->add_option("--key", key_flag,
                            "Your SSH private key (or its .pub with ssh-agent) to sign with "
                            "(default: $ACETATE_SIGNING_KEY)");
    WaiveRequest waive;
    CLI::App* w = app.add_subcommand(
        "waive", "Accept one failing check for this plugin source, with a reason and an expiry");
    w->add_option("plugin", waive_plugin)->required();
    w->add_option("check", waive.check, "The check, or \"strictness\"")->required();
    w->add_option("--reason", waive.reason, "Why the failure is acceptable")->required();
    flags::add_day(w, "--until", waive.until, "The last day it holds, YYYY-MM-DD (UTC)")
        ->required();
    flags::add_name(w, "--by", waive.by, "Who waives it")->required();
    bool status_json = false;
    std::optional<fs::path> status_plan;
    CLI::App* s = app.add_subcommand(
        "status", "Show the registry, or with --plan DIR the progress of a sharded run");
    s->add_flag("--json", status_json, "As JSON");
    s->add_option("--plan", status_plan,
                  "The --out folder of `validate --shard`: results found against its plan, per "
                  "shard")
        ->excludes("--json");

    std::vector<fs::path> merge_folders;
    std::optional<fs::path> merge_report;
    CLI::App* m = app.add_subcommand(
        "merge", "Judge and record the results `validate --shard K/N --out DIR` wrote, as one run");
    m->add_option("folders", merge_folders, "The --out folders of the shards")->required();
    m->add_option("--report", merge_report, "Report folder (default: the first folder)");
    m->add_option("--json", validate.json_file, "Also write the JSON report here");
    m->add_option("--junit", validate.junit_file, "Also write JUnit XML here");

    BlessOptions bless;
    std::optional<fs::path> bless_report;
    bless.jobs = validate.jobs;
    CLI::App* b = app.add_subcommand(
        "bless", "Render the reference cases and store them as the plugin's golden references");
    b->add_option("plugin", bless.plugin, "The plugin's shared library")->required();
    flags::add_name(b, "--by", bless.by, "Who looked at the images and blesses them")->required();
    b->add_option("--report", bless_report,
                  "Where the cases run (default ./harness-bless/<plugin>)");
    flags::add_number(b, "--jobs", bless.jobs, 1, 256, "Cases run at once");
    flags::add_number(b, "--timeout", bless.timeout_seconds, 1.0, 3600.0,
                      "Seconds a case may take");

    fs::path describe_plugin_file, describe_out;
    CLI::App* d = app.add_subcommand("describe", "(child) Write what a plugin declares as JSON");
    d->add_option("plugin", describe_plugin_file)->required();
    d->add_option("--out", describe_out)->required();
    fs::path case_info, case_report;
    std::vector<fs::path> case_files, case_outs;
    CLI::App* c = app.add_subcommand("run-case", "(child) Run cases of a validation in order");
    c->add_option("--plugin-info", case_info)->required();
    c->add_option("--case", case_files, "A case's case.json (repeatable)")->required();
    c->add_option("--out", case_outs, "Its folder, one per --case")->required();
    c->add_option("--report", case_report)->required();

    // Options of the whole command (--registry) may also follow the subcommand.
    for (CLI::App* sub : {v, r, p, s, w, b, m}) sub->fallthrough();
    try {
        app.parse(argc, argv);
    } catch (const CLI::ValidationError& e) {
        // A value a flag refuses: the reader's one line, without CLI11's second; a usage error.
        std::fprintf(stderr, "acetate-harness: %s\n", e.what());
        return 2;
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    const fs::path registry = registry_path(registry_flag);
    try {
        if (f->parsed()) {
            auto seconds = read_duration(fuzz_duration);
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
            {
                std::vector<RunFile> in{{fuzz.plugin, "the plugin"}},
                    out{{fuzz.report_directory / "plugin.json", "--report"}};
                if (fuzz.reproduce) in.push_back({*fuzz.reproduce, "--reproduce"});
                for (const char* name : {"shrunk-case.json", "report.json", "index.html"})
                    if (!fuzz.reproduce) out.push_back({fuzz.report_directory / name, "--report"});
                if (auto spared = check_outputs_spare_inputs(out, in); !spared)
                    return fail(spared.error().message);
            }
            return run_fuzz(fuzz);
        }
        if (v->parsed()) {
            validate.up_to = stage_name == "alpha-tested" ? ValidationStage::AlphaTested
                                                          : ValidationStage::Integrated;
            validate.registry = registry;
            validate.allowed_signers = allowed_signers_path(allowed_signers_flag);
            validate.references = references_path(references_flag);
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
            if (validate.list_cases) return run_list_cases(validate);
            if (validate.shard && !validate.out)
                return fail("--shard: give the shared results folder with --out DIR");
            if (validate.out) {
                if (validate.only_cases.empty() && !validate.shard)
                    return fail(
                        "--out: name the cases to run with --shard K/N or --case ID (validate "
                        "--list-cases prints them)");
                validate.out = fs::absolute(*validate.out);
                if (!report_flag) validate.report_directory = *validate.out;
                if (auto runner = runner_identity(validate); !runner)
                    return fail(runner.error().message);
            }
            std::vector<RunFile> inputs = recording_inputs(validate);
            inputs.push_back({validate.plugin, "the plugin"});
            if (auto spared = check_validate_outputs(validate, inputs); !spared)
                return fail(spared.error().message);
            return run_validate(validate);
        }
        if (m->parsed()) {
            for (const fs::path& folder : merge_folders)
                validate.merge_from.push_back(fs::absolute(folder));
            validate.report_directory =
                fs::absolute(merge_report ? *merge_report : merge_folders.front());
            validate.registry = registry;
            validate.self = self_path();
            validate.allowed_signers = allowed_signers_path(allowed_signers_flag);
            validate.references = references_path(references_flag);
            validate.signoffs = default_signoffs_path();
            // Outputs first, before a result is read: none may be an input of the run.
            std::vector<RunFile> inputs = recording_inputs(validate);
            for (const fs::path& folder : merge_folders)
                add_files_under(inputs, folder / "results", "a shard's result");
            if (auto spared = check_validate_outputs(validate, inputs); !spared)
                return fail(spared.error().message);
            auto shards = read_shard_results(
                merge_folders, SignatureVerifier(validate.allowed_signers, kCaseResultNamespace));
            if (!shards) return fail(shards.error().message);
            const ShardResult& first = shards->front();
            validate.plugin = first.plugin.file;
            validate.strictness = first.strictness;
            validate.seed = first.seed;
            auto goal = merged_run_goal(*shards, merge_folders);
            if (!goal) return fail(goal.error().message);
            validate.up_to = goal.value();
            inputs.push_back({validate.plugin, "the plugin"});
            if (auto spared = check_validate_outputs(validate, inputs); !spared)
                return fail(spared.error().message);
            return run_validate(validate);
        }
        if (b->parsed()) {
            std::error_code ec;
            if (!fs::is_regular_file(bless.plugin, ec))
                return fail(fmt::format("{}: no such plugin file", bless.plugin.string()));
            bless.plugin = fs::absolute(bless.plugin);
            // An installation's references are its shipped plugins', written by no one after
            // `cmake --install`: an author's go beside their plugin, named on purpose.
            const char* references_env = std::getenv("ACETATE_REFERENCES");
            if (!running_from_build_tree() && !(references_flag && !references_flag->empty()) &&
                !(references_env && *references_env))
                return fail(fmt::format(
                    "bless: give --references DIR (or $ACETATE_REFERENCES): bless does not write "
                    "into this installation's {}; keep your plugin's references beside its "
                    "sources and give validate the same DIR",
                    references_path(std::nullopt).string()));
            bless.references = references_path(references_flag);
            bless.report_directory = fs::absolute(
                bless_report ? *bless_report : fs::path("harness-bless") / bless.plugin.stem());
            bless.self = self_path();
            if (auto spared = check_outputs_spare_inputs(
                    {{bless.report_directory / "plugin.json", "--report"},
                     {bless.report_directory / "references.png", "--report"}},
                    {{bless.plugin, "the plugin"}});
                !spared)
                return fail(spared.error().message);
            return run_bless(bless);
        }
        RegistryCommandContext context{
            registry, SignatureVerifier(allowed_signers_path(allowed_signers_flag)), key_flag,
            references_path(references_flag)};
        if (!context.signing_key)
            if (const char* env = std::getenv("ACETATE_SIGNING_KEY"); env && *env)
                context.signing_key = fs::path(env);
        if (s->parsed() && status_plan) return run_shard_status(*status_plan);
        if (s->parsed()) return run_status(context, status_json);
        for (auto [sub, file] : {std::pair{r, &review_plugin}, std::pair{p, &promote_plugin},
                                 std::pair{w, &waive_plugin}}) {
            if (!sub->parsed()) continue;
            auto info = describe(*file);
            if (!info) return fail(info.error().message);
            if (sub == r) return run_review(*info, context, review);
            if (sub == p) return run_promote(*info, context, promotion);
            return run_waive(*info, context, waive);
        }
        if (d->parsed()) return run_describe(describe_plugin_file, describe_out);
        if (c->parsed()) return run_cases_command(case_info, case_files, case_outs, case_report);
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    // Started by a run as its fork server (core/fork_server.hpp): each case's child is forked
    // from this process, prepared once (prepare_case_children) and otherwise untouched, and
    // runs as `acetate-harness run-case ...` would.
    if (argc == 2 && std::strcmp(argv[1], harness::kForkServerCommand) == 0)
        return serve_forks(run_harness, harness::prepare_case_children);
    return run_harness(argc, argv);
}
