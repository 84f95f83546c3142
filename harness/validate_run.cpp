// `acetate-harness validate` as its steps, in the order ValidationRun::run() takes them: the
// report folder, the shards' results (a merge), the plugin described in a child, the plan, the
// registry and references, the alpha stage, the integration stage, the merge's leftovers, the
// registry written in one update, the reports. A step that cannot go on returns the one-line
// error the run ends with; the reports are written either way.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <set>

#include "case_batch.hpp"
#include "case_repeat.hpp"
#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "neighbours.hpp"
#include "references.hpp"
#include "report_junit.hpp"
#include "shard.hpp"
#include "ssh_signature.hpp"
#include "validate_registry.hpp"
#include "validate_support.hpp"
#include "waivers.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

class ValidationRun {
  public:
    explicit ValidationRun(const ValidateOptions& o) : o_(o) {}

    int run() {
        // 1. The report folder, and this process's own files in it.
        if (auto opened = open_report_folder(); !opened) {
            std::fprintf(stderr, "acetate-harness: %s\n", opened.error().message.c_str());
            return 1;
        }
        // 2. Every child runs with the Khronos validation layer (but determinism/without-layer):
        //    a validation message while the plugin runs fails the vulkan-validation check, and
        //    evidence is never recorded without.
        setenv("ACETATE_VALIDATION", "1", 1);
        // 3. A merge reads the shards' results and verifies their signatures.
        if (auto read = read_shards(); !read) return fail_run(read.error().message);
        // 4. The plugin, described in a child (its code runs there), as it is now.
        if (auto described = describe(); !described) return fail_run(described.error().message);
        // 5. The plan: every case of the run; a shard's cut of it; for a merge, none missing.
        if (auto planned = plan(); !planned) return fail_run(planned.error().message);
        // 6. The registry (one transaction, written at the end), the references, the
        //    committed sign-offs.
        if (auto opened = open_registry(); !opened) return fail_run(opened.error().message);
        // 7. The alpha stage's cases.
        auto alpha = alpha_stage();
        if (!alpha) return fail_run(alpha.error().message);
        // 8. The integration stage's, beside the other integrated plugins, when alpha passed
        //    (or only some cases run: their verdict is the merge's).
        bool passed = *alpha;
        if ((passed || partial_) && o_.up_to >= ValidationStage::Integrated) {
            auto integrated = integration_stage();
            if (!integrated) return fail_run(integrated.error().message);
            passed = *integrated && passed;
        }
        // 9. A merge was given no result outside the plan.
        if (auto leftover = refuse_unplanned_results(passed); !leftover)
            return fail_run(leftover.error().message);
        // 10. What the run recorded, written in one update; the reports.
        commit_registry();
        return print_outcome();
    }

  private:
    Result<void> open_report_folder() {
        std::error_code ec;
        fs::create_directories(o_.report_directory, ec);
        if (ec)
            return make_error(ErrorCode::Io,
                              fmt::format("{}: cannot create the report folder: {}",
                                          o_.report_directory.string(), ec.message()));
        report_.harness_version = kHarnessVersion;
        report_.plugin_file = o_.plugin.string();
        report_.strictness = o_.strictness;
        report_.seed = o_.seed;
        report_.started_at = utc_now_iso8601();
        // This process's own files (plugin.json, describe.log, its report): a shard's go into
        // a folder of its own under --out, which no other shard writes or reads, so shards may
        // share one --out; the pictures stay under the report folder, one folder per case.
        own_ = !o_.out    ? o_.report_directory
               : o_.shard ? *o_.out / "shards" / o_.shard->folder()
                          : *o_.out / "shards" / fmt::format("cases-{}-{}", host_name(), getpid());
        return {};
    }

    Result<void> read_shards() {
        merging_ = !o_.merge_from.empty();
        if (!merging_) return {};
        auto read = read_shard_results(o_.merge_from,
                                       SignatureVerifier(o_.allowed_signers, kCaseResultNamespace));
        if (!read) return read.error();
        shards_ = std::move(read.value());
        if (shards_.front().strictness != o_.strictness || shards_.front().seed != o_.seed)
            return make_error(ErrorCode::InvalidInput,
                              "merge: the options' strictness and seed must be the shards'");
        return {};
    }

    // A merge plans from the plugin itself, as a single run does, never from what the result
    // files say it was: they are only the shards' word.
    Result<void> describe() {
        auto described = describe_in_child(o_.self, o_.plugin, own_, o_.timeout_seconds);
        if (!described) return described.error();
        if (merging_ && described->binary_sha256 != shards_.front().plugin.binary_sha256)
            return make_error(
                ErrorCode::InvalidInput,
                fmt::format(
                    "merge: {} is not the binary the shards ran (SHA-256 {} here, {} in {})",
                    o_.plugin.string(), described->binary_sha256.substr(0, 12),
                    shards_.front().plugin.binary_sha256.substr(0, 12),
                    shards_.front().file.string()));
        auto scenes = find_reference_scenes(o_.references, described->id);
        if (!scenes) return scenes.error();
        described->reference_scenes = std::move(scenes.value());
        plugin_ = std::move(described.value());
        if (merging_) report_.plugin_file = plugin_.file;
        report_.id = plugin_.id;
        report_.version = plugin_.version;
        report_.display_name = plugin_.display_name;
        report_.scope = plugin_.scope;
        report_.coverage = plugin_.coverage;
        report_.binary_sha256 = plugin_.binary_sha256;
        report_.source_digest = plugin_.source_digest;
        plugin_info_file_ = own_ / "plugin.json";
        return write_file_atomically(plugin_info_file_, to_json(plugin_).dump(2));
    }

    Result<void> plan() {
        const std::vector<PlannedCase> planned =
            plan_of_run(plugin_, o_.strictness, o_.seed, o_.up_to >= ValidationStage::Integrated);
        // A shard cuts its cases from the plan and leaves the plan beside the results (status).
        only_cases_ = o_.only_cases;
        if (o_.shard) {
            ShardPlan cut{plugin_.id,    plugin_.version, plugin_.binary_sha256,
                          o_.strictness, o_.seed,         o_.shard->count,
                          planned};
            ACETATE_TRY(write_shard_plan(*o_.out, cut));
            for (size_t i = 0; i < planned.size(); ++i)
                if (o_.shard->owns(i)) only_cases_.push_back(planned[i].id);
            std::printf("shard %s: %zu of the plan's %zu cases\n", o_.shard->label().c_str(),
                        only_cases_.size(), planned.size());
        }
        partial_ = o_.shard || !only_cases_.empty();
        // A merge needs a result for every case of the plan: every missing one is named at once.
        if (merging_)
            if (auto missing = missing_results(planned, shards_, o_.merge_from.front()))
                return make_error(ErrorCode::InvalidInput, *missing);
        if (partial_ && !o_.shard) {
            // Every case a full run at this strictness has (integration ones with no
            // companions: their ids do not depend on them).
            std::vector<std::string> known;
            for (const CaseSpec& c : plan_cases(plugin_, o_.strictness, o_.seed, true, true, {}))
                known.push_back(c.id);
            for (const std::string& id : only_cases_)
                if (std::find(known.begin(), known.end(), id) == known.end())
                    return make_error(ErrorCode::InvalidInput,
                                      fmt::format("--case {}: no such case at strictness {} "
                                                  "(cases: {})",
                                                  id, o_.strictness, fmt::join(known, ", ")));
        }
        return {};
    }

    Result<void> open_registry() {
        // A malformed registry stops the run here, rather than reading as "nothing recorded".
        // Everything this run records goes through one transaction, written only at its end:
        // a run refused on the way writes nothing.
        auto opened = RegistryTransaction::open(o_.registry);
        if (!opened) return opened.error();
        registry_.emplace(std::move(opened).value());
        // So do malformed references; missing ones mean the reference cases only render.
        auto references = load_references(o_.references, plugin_.id);
        if (!references) return references.error();
        references_ = std::move(references.value());
        if (!partial_) ACETATE_TRY(import_sign_offs());
        const ValidationStage before = current_stage(registry_->view(), o_, plugin_);
        report_.stage_before = to_string(before);
        std::printf(
            "validating %s %s (%s, %s, %s) from %s\nregistry %s: %s; strictness %d, seed "
            "%llu, %u jobs\n",
            plugin_.id.c_str(), plugin_.version.c_str(), plugin_.display_name.c_str(),
            plugin_.scope.c_str(), plugin_.coverage.c_str(), o_.plugin.string().c_str(),
            o_.registry.string().c_str(), to_string(before), o_.strictness,
            (unsigned long long)o_.seed, o_.jobs);
        report_.combinations = combinations_summary(plugin_, o_.strictness, o_.seed);
        std::printf("combinations: %s\n", report_.combinations.c_str());
        if (o_.repeat > 1 || o_.shuffle_seed)
            std::printf(
                "every case %u time%s, each in a fresh process%s\n", o_.repeat,
                o_.repeat == 1 ? "" : "s",
                o_.shuffle_seed
                    ? fmt::format(", in random order (--shuffle-seed {})", *o_.shuffle_seed).c_str()
                    : "");
        batch_.self = o_.self;
        batch_.plugin_info_file = plugin_info_file_;
        batch_.report_directory = o_.report_directory;
        batch_.jobs = o_.jobs;
        batch_.timeout_seconds = o_.timeout_seconds;
        batch_.cases_per_process = o_.cases_per_process;
        batch_.reproduce = [this](const CaseSpec& spec) { return reproduce_command(o_, spec.id); };
        return {};
    }

    Result<void> import_sign_offs() {
        auto imported = import_committed(*registry_, o_, plugin_);
        if (!imported) return imported.error();
        for (const std::string& line : imported.value()) std::printf("%s\n", line.c_str());
        return {};
    }

    Result<bool> alpha_stage() {
        auto cases = select(plan_cases(plugin_, o_.strictness, o_.seed, true, false, {}));
        stale_references_ = attach_references(cases, references_, plugin_);
        ACETATE_TRY(attach_neighbours(cases, neighbour_directory(o_.self)));
        if (!references_)
            std::printf(
                "references: none blessed for %s in %s (the reference cases only "
                "render)\n",
                plugin_.id.c_str(), o_.references.string().c_str());
        else if (stale_references_)
            std::printf("references: %s\n", stale_references_->message.c_str());
        if (partial_ && o_.up_to < ValidationStage::Integrated &&
            cases.size() != only_cases_.size())
            return make_error(ErrorCode::InvalidInput,
                              "--case: integration cases do not run with --stage alpha-tested");
        if (cases.empty()) return true;
        return run_stage(ValidationStage::AlphaTested, cases, {});
    }

    Result<bool> integration_stage() {
        std::vector<std::string> notes;
        Registry verified = registry_->view();
        std::vector<CompanionPlugin> companions;
        // A companion is loaded into this process: only one whose sign-offs hold.
        verified.verify_sign_offs(SignatureVerifier(o_.allowed_signers));
        if (!merging_) companions = find_companions(verified, plugin_, o_.plugin_paths, notes);
        for (const ShardResult& r : shards_)  // merging: the companions the shards ran with
            if (r.stage == ValidationStage::Integrated) companions = r.spec.companions;
        // ... each of which must be what this registry holds as integrated, sign-offs
        // verified: a result file cannot vouch for a library.
        for (const CompanionPlugin& c : companions)
            if (merging_ &&
                verified.binary_stage(c.id, c.binary_sha256) < ValidationStage::Integrated)
                return make_error(
                    ErrorCode::InvalidInput,
                    fmt::format("merge: the shards ran beside {} (SHA-256 {}), "
                                "which {} does not hold as INTEGRATED or VALIDATED",
                                c.id, c.binary_sha256.substr(0, 12), o_.registry.string()));
        for (const std::string& note : notes) std::printf("note: %s\n", note.c_str());
        std::printf("integration: with %zu other integrated plugin%s%s\n", companions.size(),
                    companions.size() == 1 ? "" : "s", companions.empty() ? " (none yet)" : "");
        const auto cases =
            select(plan_cases(plugin_, o_.strictness, o_.seed, false, true, companions));
        bool passed = true;
        if (!cases.empty()) {
            auto ran = run_stage(ValidationStage::Integrated, cases, companions);
            if (!ran) return ran.error();
            passed = *ran;
        }
        // Sign-offs committed for this binary apply once its automated stages are recorded.
        if (passed && !partial_) ACETATE_TRY(import_sign_offs());
        return passed;
    }

    // Every result a merge was given belongs to the plan; those of a stage a single run would
    // not have reached (its alpha stage failed) are left out, as that run would not have them.
    Result<void> refuse_unplanned_results(bool passed) const {
        for (const ShardResult& r : shards_)
            if (!merged_.count(r.spec.id) && (passed || r.stage == ValidationStage::AlphaTested))
                return make_error(ErrorCode::InvalidInput,
                                  fmt::format("{}: case {} is not in the plan of this run "
                                              "(strictness {}, seed {})",
                                              r.file.string(), r.spec.id, o_.strictness, o_.seed));
        return {};
    }

    // Not refused: what the run recorded is written now, in one update.
    void commit_registry() {
        after_ = registry_->view();
        if (auto committed = registry_->commit(); !committed) {
            for (StageRun& s : report_.stages)
                if (s.recorded) {
                    s.recorded = false;
                    s.passed = false;
                    s.note = "passed, but recording failed: " + committed.error().message;
                }
            recording_failed_ = true;
            std::fprintf(stderr, "acetate-harness: %s\n", committed.error().message.c_str());
            auto on_disk = Registry::load(o_.registry);
            after_ = on_disk ? std::move(on_disk).value() : Registry();
        }
    }

    int print_outcome() {
        report_.stage_after = to_string(current_stage(after_, o_, plugin_));
        report_.history = history_of(after_, plugin_);
        print_summary(report_);
        std::printf("\n%s %s: %s -> %s; %s\n", plugin_.id.c_str(), plugin_.version.c_str(),
                    report_.stage_before.c_str(), report_.stage_after.c_str(),
                    run_failed(report_) ? "FAILED"
                    : recording_failed_ ? "checks passed, but the evidence was not recorded"
                                        : "all checks passed");
        for (const StageRun& s : report_.stages)
            std::printf("  %s: %s\n", s.stage.c_str(), s.note.c_str());
        if (o_.out) {
            std::printf("results: %s (for `acetate-harness merge`, which judges them)\n",
                        (*o_.out / "results").string().c_str());
            return finish(0);
        }
        return finish(run_failed(report_) || recording_failed_ ? 1 : 0);
    }

    // ---- a stage ------------------------------------------------------------------------

    // The cases this process runs: all of them, or those --shard or --case named.
    std::vector<CaseSpec> select(std::vector<CaseSpec> cases) const {
        if (!partial_) return cases;
        std::erase_if(cases, [&](const CaseSpec& c) {
            return std::find(only_cases_.begin(), only_cases_.end(), c.id) == only_cases_.end();
        });
        return cases;
    }

    // A stage's results: run here (and written to --out for a merge elsewhere), or read back
    // from the shards. A merge lacking a case is an error, as is a result for no planned case.
    Result<std::vector<CaseResult>> obtain(ValidationStage stage,
                                           const std::vector<CaseSpec>& cases) {
        if (!merging_) {
            batch_.total += cases.size() * std::max(1u, o_.repeat);
            // A shard writes each result as its case finishes; the first write that fails
            // (a full disk, the key) stops the shard with that error once the batch is done.
            std::optional<Error> unwritten;
            if (o_.out)
                batch_.on_result = [&](size_t i, const CaseResult& result) {
                    if (unwritten) return;
                    const ShardOutput to{*o_.out,
                                         plugin_,
                                         o_.strictness,
                                         o_.seed,
                                         Runner{o_.runner, o_.runner_key.value_or(fs::path())},
                                         o_.shard};
                    if (auto w = write_shard_result(to, stage, cases[i], result); !w)
                        unwritten = w.error();
                };
            std::vector<CaseResult> results =
                run_repeated(batch_, cases, {o_.repeat, o_.shuffle_seed});
            batch_.on_result = {};
            if (unwritten) return *unwritten;
            return results;
        }
        std::vector<CaseResult> results;
        for (const CaseSpec& c : cases) {
            auto found = std::find_if(shards_.begin(), shards_.end(),
                                      [&](const ShardResult& r) { return r.spec.id == c.id; });
            if (found == shards_.end())
                return make_error(ErrorCode::InvalidInput,
                                  fmt::format("merge: no result for case {} in {}", c.id,
                                              o_.merge_from.front().string()));
            results.push_back(found->result);
            merged_.insert(c.id);
        }
        return results;
    }

    // Runs (or reads) a stage's cases, judges them and records the stage when they pass and
    // the stage before it is held, for this binary and source.
    Result<bool> run_stage(ValidationStage stage, const std::vector<CaseSpec>& cases,
                           const std::vector<CompanionPlugin>& companions) {
        StageRun stage_run;
        stage_run.stage = to_string(stage);
        auto obtained = obtain(stage, cases);
        if (!obtained) return obtained.error();
        std::vector<CaseResult> results = std::move(obtained.value());
        compare_across_processes(results, o_.report_directory);
        // The failing case that stands for references blessed for another source.
        if (stage == ValidationStage::AlphaTested && stale_references_ && !partial_)
            results.push_back(*stale_references_);
        apply_waivers(results,
                      waivers_of(o_.registry, plugin_.id, plugin_.version, plugin_.source_digest),
                      utc_today());
        stage_run.passed = all_pass(results);
        const ValidationStage now = current_stage(registry_->view(), o_, plugin_);
        if (!stage_run.passed) {
            stage_run.note = "a check failed: nothing recorded";
        } else if (partial_) {
            stage_run.note = "only some cases ran (--shard or --case): nothing recorded";
        } else if (int(now) < int(stage) - 1) {
            stage_run.note = fmt::format(
                "passed, but not recorded: the plugin is {} and {} needs {} first{}",
                to_string(now), to_string(stage), to_string(ValidationStage(int(stage) - 1)),
                now == ValidationStage::Unvalidated
                    ? fmt::format(" (acetate-harness review {} --reviewer NAME --notes TEXT)",
                                  o_.plugin.string())
                    : "");
        } else if (auto same = file_sha256(o_.plugin);
                   !same || same.value() != plugin_.binary_sha256) {
            // The file changed during the run: the cases may have run another binary.
            stage_run.note = "passed, but not recorded: the plugin file changed during the run";
            stage_run.passed = false;
            recording_failed_ = true;
        } else if (auto r = record(*registry_, o_, plugin_, stage, results,
                                   fs::absolute(o_.report_directory / "report.json").string(),
                                   companions);
                   !r) {
            stage_run.note = "passed, but recording failed: " + r.error().message;
            stage_run.passed = false;
            recording_failed_ = true;
        } else {
            stage_run.recorded = true;
            stage_run.note = fmt::format("recorded in {}", o_.registry.string());
        }
        report_.cases.insert(report_.cases.end(), results.begin(), results.end());
        report_.stages.push_back(stage_run);
        return stage_run.passed;
    }

    // ---- the end ------------------------------------------------------------------------

    // Writes the reports; a run that already failed says so in one line, with the reports'
    // own failure (a full disk, say) appended rather than printed as a second error.
    int finish(int status) {
        const fs::path shown =
            fs::absolute(o_.out ? own_ / "report.json" : o_.report_directory / "index.html");
        report_.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
        auto written = write_json_report(report_, own_ / "report.json");
        if (written && o_.json_file) written = write_json_report(report_, *o_.json_file);
        if (written && o_.junit_file) written = write_junit_report(report_, *o_.junit_file);
        // A shard's page would be one of many over one folder: the merge writes the page.
        if (written && !o_.out) written = write_html_report(report_, o_.report_directory);
        if (!report_.error.empty()) {
            std::fprintf(stderr, "acetate-harness: %s%s\n", report_.error.c_str(),
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
    }
    int fail_run(const std::string& message) {
        report_.error = message;
        return finish(1);
    }

    const ValidateOptions& o_;
    const Clock::time_point start_ = Clock::now();
    ValidationReport report_;
    fs::path own_;  // this process's own files
    bool merging_ = false;
    std::vector<ShardResult> shards_;  // a merge's input
    std::set<std::string> merged_;     // the cases a merge took a result for
    PluginInfo plugin_;
    fs::path plugin_info_file_;
    std::vector<std::string> only_cases_;  // --case, or a shard's cut
    bool partial_ = false;                 // only some cases run: nothing is recorded
    std::optional<RegistryTransaction> registry_;
    Registry after_;  // the registry once the run's records are written
    std::optional<ReferenceSet> references_;
    std::optional<CaseResult> stale_references_;  // references blessed for another source
    CaseBatch batch_;
    bool recording_failed_ = false;
};

}  // namespace

int run_validate(const ValidateOptions& o) {
    return ValidationRun(o).run();
}

}  // namespace acetate::harness
