#include "validate.hpp"

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
#include "waivers.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

// ---- running the cases --------------------------------------------------------------------

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

// This machine's name as a folder name: a --case shard's own folder is named by it and its
// process id, as two machines' process ids may coincide.
std::string host_name() {
    char name[256] = {};
    if (gethostname(name, sizeof name - 1) != 0) return "host";
    return case_folder(name);
}

CheckResult* find_check(CaseResult& c, const std::string& name) {
    for (CheckResult& check : c.checks)
        if (check.check == name) return &check;
    return nullptr;
}

// The determinism runs compare across processes: every run's digest must match the first's
// (two fresh processes, with different poisons; and one that rendered other scenes and frames
// first). A plugin that is not deterministic cannot be judged for state isolation (its images
// differ anyway), so that check is skipped rather than failed twice for one fault.
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
        check->verdict = Verdict::Fail;
        check->message = fmt::format(
            "{} rendered the same case differently from a fresh process (digests {} and {}){}",
            history ? "a process that had rendered other scenes and frames first"
                    : "a second process",
            first->output_digest.substr(0, 12), r.output_digest.substr(0, 12),
            history ? "" : "; their poisons differed, so reading unwritten memory shows here");
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
    // shows after other loads and frames only is history, which state-isolation judges too.
    bool deterministic = true;
    for (const CaseResult& r : results)
        for (const CheckResult& c : r.checks)
            if (c.check == "determinism" && c.verdict == Verdict::Fail &&
                r.id != "determinism/after-history")
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

// Integrated or validated plugins other than this one, found on the plugin search path with
// the binary the registry recorded for them.
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

}  // namespace

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

int run_validate(const ValidateOptions& o) {
    const auto start = Clock::now();
    ValidationReport report;
    report.harness_version = kHarnessVersion;
    report.plugin_file = o.plugin.string();
    report.strictness = o.strictness;
    report.seed = o.seed;
    report.started_at = utc_now_iso8601();
    std::error_code ec;
    fs::create_directories(o.report_directory, ec);
    if (ec) {
        std::fprintf(stderr, "acetate-harness: %s: cannot create the report folder: %s\n",
                     o.report_directory.string().c_str(), ec.message().c_str());
        return 1;
    }
    // This process's own files (plugin.json, describe.log, its report): a shard's go into a
    // folder of its own under --out, which no other shard writes or reads, so shards may share
    // one --out; the pictures stay under the report folder, one folder per case.
    const fs::path own =
        !o.out    ? o.report_directory
        : o.shard ? *o.out / "shards" / o.shard->folder()
                  : *o.out / "shards" / fmt::format("cases-{}-{}", host_name(), getpid());
    const fs::path html = o.report_directory / "index.html";
    // Writes the reports; a run that already failed says so in one line, with the reports'
    // own failure (a full disk, say) appended rather than printed as a second error.
    const fs::path shown = fs::absolute(o.out ? own / "report.json" : html);
    auto finish = [&](int status) {
        report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        auto written = write_json_report(report, own / "report.json");
        if (written && o.json_file) written = write_json_report(report, *o.json_file);
        if (written && o.junit_file) written = write_junit_report(report, *o.junit_file);
        // A shard's page would be one of many over one folder: the merge writes the page.
        if (written && !o.out) written = write_html_report(report, o.report_directory);
        if (!report.error.empty()) {
            std::fprintf(stderr, "acetate-harness: %s%s\n", report.error.c_str(),
                         written ? ""
                                 : fmt::format(" (and the report could not be written: {})",
                                               written.error().message)
                                       .c_str());
            if (written) std::printf("report: %s\n", shown.string().c_str());
            return 1;
        }
        if (!written) {
            std::fprintf(stderr, "acetate-harness: %s\n", written.error().message.c_str());
            return 1;
        }
        std::printf("report: %s\n", shown.string().c_str());
        return status;
    };
    auto fail_run = [&](const std::string& message) {
        report.error = message;
        return finish(1);
    };

    // Every child runs with the Khronos validation layer: a validation message while the
    // plugin runs fails the vulkan-validation check, and evidence is never recorded without.
    setenv("ACETATE_VALIDATION", "1", 1);
    const bool merging = !o.merge_from.empty();
    std::vector<ShardResult> shards;
    if (merging) {
        auto read = read_shard_results(o.merge_from,
                                       SignatureVerifier(o.allowed_signers, kCaseResultNamespace));
        if (!read) return fail_run(read.error().message);
        shards = std::move(read.value());
        if (shards.front().strictness != o.strictness || shards.front().seed != o.seed)
            return fail_run("merge: the options' strictness and seed must be the shards'");
    }
    // A merge plans from the plugin itself, as a single run does, never from what the result
    // files say it was: they are only the shards' word.
    auto described = describe_in_child(o.self, o.plugin, own, o.timeout_seconds);
    if (!described) return fail_run(described.error().message);
    if (merging && described->binary_sha256 != shards.front().plugin.binary_sha256)
        return fail_run(fmt::format(
            "merge: {} is not the binary the shards ran (SHA-256 {} here, {} in {})",
            o.plugin.string(), described->binary_sha256.substr(0, 12),
            shards.front().plugin.binary_sha256.substr(0, 12), shards.front().file.string()));
    auto scenes = find_reference_scenes(o.references, described->id);
    if (!scenes) return fail_run(scenes.error().message);
    described->reference_scenes = std::move(scenes.value());
    const PluginInfo plugin = std::move(described.value());
    if (merging) report.plugin_file = plugin.file;
    report.id = plugin.id;
    report.version = plugin.version;
    report.display_name = plugin.display_name;
    report.scope = plugin.scope;
    report.coverage = plugin.coverage;
    report.binary_sha256 = plugin.binary_sha256;
    report.source_digest = plugin.source_digest;
    const fs::path plugin_info_file = own / "plugin.json";
    if (auto w = write_file_atomically(plugin_info_file, to_json(plugin).dump(2)); !w)
        return fail_run(w.error().message);
    const std::vector<PlannedCase> plan =
        plan_of_run(plugin, o.strictness, o.seed, o.up_to >= ValidationStage::Integrated);
    // A shard cuts its cases from the plan and leaves the plan beside the results (status).
    std::vector<std::string> only_cases = o.only_cases;
    if (o.shard) {
        ShardPlan cut{plugin.id,    plugin.version, plugin.binary_sha256,
                      o.strictness, o.seed,         o.shard->count,
                      plan};
        if (auto w = write_shard_plan(*o.out, cut); !w) return fail_run(w.error().message);
        for (size_t i = 0; i < plan.size(); ++i)
            if (o.shard->owns(i)) only_cases.push_back(plan[i].id);
        std::printf("shard %s: %zu of the plan's %zu cases\n", o.shard->label().c_str(),
                    only_cases.size(), plan.size());
    }
    // A merge needs a result for every case of the plan: every missing one is named at once.
    if (merging)
        if (auto missing = missing_results(plan, shards, o.merge_from.front()))
            return fail_run(*missing);

    // A malformed registry stops the run here, rather than reading as "nothing recorded".
    // Everything this run records goes through one transaction, written only at its end: a
    // run refused on the way writes nothing.
    auto opened = RegistryTransaction::open(o.registry);
    if (!opened) return fail_run(opened.error().message);
    RegistryTransaction registry = std::move(opened).value();
    // So do malformed references; missing ones mean the reference cases only render.
    auto references = load_references(o.references, plugin.id);
    if (!references) return fail_run(references.error().message);
    const bool partial = o.shard || !only_cases.empty();
    if (!partial) {
        auto imported = import_committed(registry, o, plugin);
        if (!imported) return fail_run(imported.error().message);
        for (const std::string& line : imported.value()) std::printf("%s\n", line.c_str());
    }
    const ValidationStage before = current_stage(registry.view(), o, plugin);
    report.stage_before = to_string(before);
    std::printf(
        "validating %s %s (%s, %s, %s) from %s\nregistry %s: %s; strictness %d, seed "
        "%llu, %u jobs\n",
        plugin.id.c_str(), plugin.version.c_str(), plugin.display_name.c_str(),
        plugin.scope.c_str(), plugin.coverage.c_str(), o.plugin.string().c_str(),
        o.registry.string().c_str(), to_string(before), o.strictness, (unsigned long long)o.seed,
        o.jobs);
    report.combinations = combinations_summary(plugin, o.strictness, o.seed);
    std::printf("combinations: %s\n", report.combinations.c_str());
    if (o.repeat > 1 || o.shuffle_seed)
        std::printf(
            "every case %u time%s, each in a fresh process%s\n", o.repeat, o.repeat == 1 ? "" : "s",
            o.shuffle_seed
                ? fmt::format(", in random order (--shuffle-seed {})", *o.shuffle_seed).c_str()
                : "");

    auto select = [&](std::vector<CaseSpec> cases) {
        if (!partial) return cases;
        std::erase_if(cases, [&](const CaseSpec& c) {
            return std::find(only_cases.begin(), only_cases.end(), c.id) == only_cases.end();
        });
        return cases;
    };
    CaseBatch run;
    run.self = o.self;
    run.plugin_info_file = plugin_info_file;
    run.report_directory = o.report_directory;
    run.jobs = o.jobs;
    run.timeout_seconds = o.timeout_seconds;
    run.reproduce = [&o](const CaseSpec& spec) { return reproduce_command(o, spec.id); };
    bool recording_failed = false;
    // A stage's results: run here (and written to --out for a merge elsewhere), or read back
    // from the shards. A merge lacking a case is an error, as is a result for no planned case.
    std::string obtain_error;
    std::set<std::string> merged;
    auto obtain = [&](ValidationStage stage,
                      const std::vector<CaseSpec>& cases) -> Result<std::vector<CaseResult>> {
        if (!merging) {
            run.total += cases.size() * std::max(1u, o.repeat);
            // A shard writes each result as its case finishes; the first write that fails
            // (a full disk, the key) stops the shard with that error once the batch is done.
            std::optional<Error> unwritten;
            if (o.out)
                run.on_result = [&](size_t i, const CaseResult& result) {
                    if (unwritten) return;
                    const ShardOutput to{*o.out,
                                         plugin,
                                         o.strictness,
                                         o.seed,
                                         Runner{o.runner, o.runner_key.value_or(fs::path())},
                                         o.shard};
                    if (auto w = write_shard_result(to, stage, cases[i], result); !w)
                        unwritten = w.error();
                };
            std::vector<CaseResult> results = run_repeated(run, cases, {o.repeat, o.shuffle_seed});
            run.on_result = {};
            if (unwritten) return *unwritten;
            return results;
        }
        std::vector<CaseResult> results;
        for (const CaseSpec& c : cases) {
            auto found = std::find_if(shards.begin(), shards.end(),
                                      [&](const ShardResult& r) { return r.spec.id == c.id; });
            if (found == shards.end())
                return make_error(ErrorCode::InvalidInput,
                                  fmt::format("merge: no result for case {} in {}", c.id,
                                              o.merge_from.front().string()));
            results.push_back(found->result);
            merged.insert(c.id);
        }
        return results;
    };
    // The failing case that stands for references blessed for another source (set below).
    std::optional<CaseResult> stale_references;
    // Which stages may be recorded: each needs the one before it, for this binary and source.
    auto try_stage = [&](ValidationStage stage, const std::vector<CaseSpec>& cases,
                         const std::vector<CompanionPlugin>& companions) {
        StageRun stage_run;
        stage_run.stage = to_string(stage);
        auto obtained = obtain(stage, cases);
        if (!obtained) {
            obtain_error = obtained.error().message;
            return false;
        }
        std::vector<CaseResult> results = std::move(obtained.value());
        compare_across_processes(results, o.report_directory);
        if (stage == ValidationStage::AlphaTested && stale_references && !partial)
            results.push_back(*stale_references);
        apply_waivers(results,
                      waivers_of(o.registry, plugin.id, plugin.version, plugin.source_digest),
                      utc_today());
        stage_run.passed = all_pass(results);
        const ValidationStage now = current_stage(registry.view(), o, plugin);
        if (!stage_run.passed) {
            stage_run.note = "a check failed: nothing recorded";
        } else if (partial) {
            stage_run.note = "only some cases ran (--shard or --case): nothing recorded";
        } else if (int(now) < int(stage) - 1) {
            stage_run.note = fmt::format(
                "passed, but not recorded: the plugin is {} and {} needs {} first{}",
                to_string(now), to_string(stage), to_string(ValidationStage(int(stage) - 1)),
                now == ValidationStage::Unvalidated
                    ? fmt::format(" (acetate-harness review {} --reviewer NAME --notes TEXT)",
                                  o.plugin.string())
                    : "");
        } else if (auto same = file_sha256(o.plugin);
                   !same || same.value() != plugin.binary_sha256) {
            // The file changed during the run: the cases may have run another binary.
            stage_run.note = "passed, but not recorded: the plugin file changed during the run";
            stage_run.passed = false;
            recording_failed = true;
        } else if (auto r = record(registry, o, plugin, stage, results,
                                   fs::absolute(o.report_directory / "report.json").string(),
                                   companions);
                   !r) {
            stage_run.note = "passed, but recording failed: " + r.error().message;
            stage_run.passed = false;
            recording_failed = true;
        } else {
            stage_run.recorded = true;
            stage_run.note = fmt::format("recorded in {}", o.registry.string());
        }
        report.cases.insert(report.cases.end(), results.begin(), results.end());
        report.stages.push_back(stage_run);
        return stage_run.passed;
    };

    if (partial && !o.shard) {
        // Every case a full run at this strictness has (integration ones with no companions:
        // their ids do not depend on them).
        std::vector<std::string> known;
        for (const CaseSpec& c : plan_cases(plugin, o.strictness, o.seed, true, true, {}))
            known.push_back(c.id);
        for (const std::string& id : only_cases)
            if (std::find(known.begin(), known.end(), id) == known.end())
                return fail_run(fmt::format("--case {}: no such case at strictness {} (cases: {})",
                                            id, o.strictness, fmt::join(known, ", ")));
    }
    auto alpha_cases = select(plan_cases(plugin, o.strictness, o.seed, true, false, {}));
    stale_references = attach_references(alpha_cases, references.value(), plugin);
    if (auto attached = attach_neighbours(alpha_cases, neighbour_directory(o.self)); !attached)
        return fail_run(attached.error().message);
    if (!references.value())
        std::printf("references: none blessed for %s in %s (the reference cases only render)\n",
                    plugin.id.c_str(), o.references.string().c_str());
    else if (stale_references)
        std::printf("references: %s\n", stale_references->message.c_str());
    if (partial && o.up_to < ValidationStage::Integrated && alpha_cases.size() != only_cases.size())
        return fail_run("--case: integration cases do not run with --stage alpha-tested");
    bool passed = alpha_cases.empty() || try_stage(ValidationStage::AlphaTested, alpha_cases, {});
    // Some cases (a shard, --case) run whatever was asked, as the whole run's alpha verdict
    // is only known where every case is (the merge).
    if ((passed || partial) && o.up_to >= ValidationStage::Integrated) {
        std::vector<std::string> notes;
        Registry verified = registry.view();
        std::vector<CompanionPlugin> companions;
        // A companion is loaded into this process: only one whose sign-offs hold.
        verified.verify_sign_offs(SignatureVerifier(o.allowed_signers));
        if (!merging) companions = find_companions(verified, plugin, o.plugin_paths, notes);
        for (const ShardResult& r : shards)  // merging: the companions the shards ran with
            if (r.stage == ValidationStage::Integrated) companions = r.spec.companions;
        // ... each of which must be what this registry holds as integrated, sign-offs verified:
        // a result file cannot vouch for a library.
        for (const CompanionPlugin& c : companions)
            if (merging &&
                verified.binary_stage(c.id, c.binary_sha256) < ValidationStage::Integrated)
                return fail_run(fmt::format(
                    "merge: the shards ran beside {} (SHA-256 {}), which {} does not hold as "
                    "INTEGRATED or VALIDATED",
                    c.id, c.binary_sha256.substr(0, 12), o.registry.string()));
        for (const std::string& note : notes) std::printf("note: %s\n", note.c_str());
        std::printf("integration: with %zu other integrated plugin%s%s\n", companions.size(),
                    companions.size() == 1 ? "" : "s", companions.empty() ? " (none yet)" : "");
        const auto cases =
            select(plan_cases(plugin, o.strictness, o.seed, false, true, companions));
        if (!cases.empty())
            passed = try_stage(ValidationStage::Integrated, cases, companions) && passed;
        if (passed && !partial) {
            auto imported = import_committed(registry, o, plugin);
            if (!imported) return fail_run(imported.error().message);
            for (const std::string& line : imported.value()) std::printf("%s\n", line.c_str());
        }
    }
    if (!obtain_error.empty()) return fail_run(obtain_error);
    // Every result a merge was given belongs to the plan; those of a stage a single run would
    // not have reached (its alpha stage failed) are left out, as that run would not have them.
    for (const ShardResult& r : shards)
        if (!merged.count(r.spec.id) && (passed || r.stage == ValidationStage::AlphaTested))
            return fail_run(
                fmt::format("{}: case {} is not in the plan of this run (strictness "
                            "{}, seed {})",
                            r.file.string(), r.spec.id, o.strictness, o.seed));
    // Not refused: what the run recorded is written now, in one update.
    Registry after = registry.view();
    if (auto committed = registry.commit(); !committed) {
        for (StageRun& s : report.stages)
            if (s.recorded) {
                s.recorded = false;
                s.passed = false;
                s.note = "passed, but recording failed: " + committed.error().message;
            }
        recording_failed = true;
        std::fprintf(stderr, "acetate-harness: %s\n", committed.error().message.c_str());
        auto on_disk = Registry::load(o.registry);
        after = on_disk ? std::move(on_disk).value() : Registry();
    }
    report.stage_after = to_string(current_stage(after, o, plugin));
    report.history = history_of(after, plugin);
    print_summary(report);
    std::printf("\n%s %s: %s -> %s; %s\n", plugin.id.c_str(), plugin.version.c_str(),
                report.stage_before.c_str(), report.stage_after.c_str(),
                run_failed(report) ? "FAILED"
                : recording_failed ? "checks passed, but the evidence was not recorded"
                                   : "all checks passed");
    for (const StageRun& s : report.stages)
        std::printf("  %s: %s\n", s.stage.c_str(), s.note.c_str());
    if (o.out) {
        std::printf("results: %s (for `acetate-harness merge`, which judges them)\n",
                    (*o.out / "results").string().c_str());
        return finish(0);
    }
    return finish(run_failed(report) || recording_failed ? 1 : 0);
}

}  // namespace acetate::harness
