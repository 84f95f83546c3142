#include "case_batch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "case_kinds.hpp"
#include "case_runner.hpp"
#include "core/atomic_file.hpp"
#include "core/child_process.hpp"
#include "core/fork_server.hpp"
#include "core/input_file.hpp"
#include "core/strict_json.hpp"
#include "validate.hpp"
#include "vulkan/shader_compiler.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A file a child wrote: a child runs plugin code, so it is read like any untrusted input.
Result<json> read_json(const fs::path& file) {
    return read_json_file(file, kMaxHarnessFileBytes, "a harness file");
}

// What a case's child left, as a result: its own result.json, or CRASH / TIMEOUT / FAIL with
// the cause. Id, seed and the other fields of the case are the caller's.
CaseResult case_result(const fs::path& directory, const ChildOutcome& outcome) {
    CaseResult result;
    const std::string log = tail_of_file(case_log_file(directory), 4000);
    result.log = log;
    // The child writes result.json last, just before it returns 0: a status 0 without it is
    // the plugin's exit(0), handled with the other exits below.
    std::error_code ec;
    const bool wrote_result = fs::exists(case_result_file(directory), ec);
    if (outcome.started && !outcome.timed_out && outcome.exit_code == 0 && wrote_result) {
        auto parsed = read_json(case_result_file(directory));
        auto read = parsed ? case_result_from_json(*parsed, "result.json")
                           : Result<CaseResult>(parsed.error());
        if (read) {
            result = std::move(read.value());
            result.log = log;
        } else {
            result.verdict = Verdict::Crash;
            result.message = "the child wrote no readable result: " + read.error().message;
        }
    } else if (outcome.timed_out) {
        result.verdict = Verdict::Timeout;
        result.message = outcome.message;
    } else if (outcome.signal || (outcome.started && outcome.exit_code != kChildSetupFailure)) {
        // Killed by a signal, or exited on its own with a status the harness never uses (the
        // plugin called exit()): either way the plugin took the process down. The log's last
        // lines usually say why (an assertion, the plugin's own error message).
        result.verdict = Verdict::Crash;
        result.message = with_log(plugin_ended(outcome, "during the case"), log);
    } else {
        // The child ran but could not run the case (no device, an unwritable folder): the case
        // failed, and its last log line says why.
        result.verdict = Verdict::Fail;
        result.message = fmt::format("{}: {}", outcome.message, last_line(log));
        CheckResult run_check;
        run_check.check = "run";
        run_check.verdict = Verdict::Fail;
        run_check.message = "the case could not run: " + result.message;
        result.checks.push_back(run_check);
    }
    return result;
}

}  // namespace

std::string case_folder(const std::string& id) {
    std::string out = id;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
    return out;
}

std::string shell_word(const std::string& text) {
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("/._-+:=,", c);
    });
    if (plain) return text;
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

bool fork_server_wanted() {
    const char* value = std::getenv("ACETATE_FORK_SERVER");
    return !(value && std::strcmp(value, "0") == 0);
}

bool prepare_case_children(std::string& error) {
    warm_shader_compiler();
    auto preloaded = VulkanContext::preload_libraries(ContextOptions::from_environment());
    if (!preloaded) error = preloaded.error().message;
    return bool(preloaded);
}

std::vector<CaseResult> run_case_batch(CaseBatch& run, const std::vector<CaseSpec>& cases) {
    std::vector<std::string> folders;
    for (const CaseSpec& spec : cases) folders.push_back(case_folder(spec.id));
    return run_case_batch(run, cases, folders);
}

std::vector<std::vector<size_t>> group_cases(const std::vector<CaseSpec>& cases,
                                             unsigned per_process, unsigned jobs) {
    // At least four processes a job where there are cases enough.
    const size_t slots = size_t(std::max(jobs, 1u)) * 4;
    const size_t per_job = (cases.size() + slots - 1) / slots;
    const size_t size = std::clamp<size_t>(per_job, 1, std::max(per_process, 1u));
    std::vector<std::vector<size_t>> groups;
    bool open = false;  // the last group takes more cases
    for (size_t i = 0; i < cases.size(); ++i) {
        const bool alone = !cases[i].validation_layer || case_kind_info(cases[i].kind).own_process;
        if (alone || !open || groups.back().size() >= size) groups.emplace_back();
        groups.back().push_back(i);
        open = !alone;
    }
    return groups;
}

std::vector<CaseResult> run_case_batch(CaseBatch& run, const std::vector<CaseSpec>& cases,
                                       const std::vector<std::string>& folders) {
    const CaseBatch& o = run;
    std::vector<fs::path> directories, spec_files;
    // A case's folder, empty but for its case.json (again before a case runs alone).
    auto prepare = [&](size_t c) {
        std::error_code ec;
        fs::remove_all(directories[c], ec);
        fs::create_directories(directories[c], ec);
        (void)write_file_atomically(spec_files[c], to_json(cases[c]).dump(2));
    };
    for (size_t c = 0; c < cases.size(); ++c) {
        directories.push_back(o.report_directory / "cases" / folders.at(c));
        spec_files.push_back(directories.back() / "case.json");
        prepare(c);
    }
    // The child that runs `group`, in order, in one process.
    auto job_for = [&](const std::vector<size_t>& group) {
        ChildJob job;
        job.argv = {o.self.string(), "run-case",
                    "--plugin-info", o.plugin_info_file.string(),
                    "--report",      o.report_directory.string()};
        for (size_t c : group)
            for (const std::string& arg : {std::string("--case"), spec_files[c].string(),
                                           std::string("--out"), directories[c].string()})
                job.argv.push_back(arg);
        job.log = case_log_file(directories[group.front()]);
        // A process is given one case's limit: a hang is found as soon as alone, and the
        // cases a process did not finish in it run again alone with the limit each.
        job.timeout = std::chrono::milliseconds(int64_t(o.timeout_seconds * 1000));
        job.fresh_process = !cases[group.front()].validation_layer;  // the server loaded the layer
        return job;
    };
    const std::vector<std::vector<size_t>> groups = group_cases(cases, o.cases_per_process, o.jobs);
    std::vector<ChildJob> group_jobs;
    for (const auto& group : groups) group_jobs.push_back(job_for(group));
    std::vector<CaseResult> results(cases.size());
    // Each case's child forked from one server instead of started anew (core/fork_server.hpp):
    // the same fresh process for a fraction of the start-up. ACETATE_FORK_SERVER=0 spawns each
    // child instead (to compare, or to rule the server out).
    std::unique_ptr<ForkServer> server;
    if (o.fork_server && groups.size() > 1) {
        std::string error;
        server = ForkServer::start({o.self.string(), kForkServerCommand}, error);
    }
    // A case killed at the time limit runs once more, alone in a fresh process, before its
    // TIMEOUT counts: the limit counts CPU time (core/child_process.hpp), and a second run
    // tells a plugin that hangs from a case that was starved by something else.
    std::vector<size_t> timed_out, alone;
    std::vector<std::string> first_timeouts(cases.size()), shared_ends(cases.size());
    auto finish = [&](size_t i, const ChildOutcome& outcome, bool retried, bool grouped) {
        if (outcome.timed_out && !retried) {
            timed_out.push_back(i);
            first_timeouts[i] = outcome.message;
            if (!o.quiet)
                std::printf("  %s: %s; running it once more\n", cases[i].id.c_str(),
                            outcome.message.c_str());
            return;
        }
        CaseResult result = case_result(directories[i], outcome);
        if (retried && outcome.timed_out)
            result.message += "; the same when run once more in a fresh process";
        else if (retried)
            result.message = fmt::format(
                "{}{}timed out once ({}), then finished when run once more in a fresh process",
                result.message, result.message.empty() ? "" : "; ", first_timeouts[i]);
        if (!shared_ends[i].empty() && result.verdict < Verdict::Fail)
            result.message = fmt::format("{}{}{}; run alone, it finished", result.message,
                                         result.message.empty() ? "" : "; ", shared_ends[i]);
        result.id = cases[i].id;
        result.description = cases[i].description;
        result.seed = cases[i].seed;
        result.inputs = cases[i].inputs;
        if (!grouped) result.seconds = outcome.seconds;  // else the child's count for the case
        result.reproduce = o.reproduce ? o.reproduce(cases[i]) : std::string();
        ++run.done;
        if (!o.quiet)
            std::printf("[%zu/%zu] %-28s %-7s %5.1f s%s%s\n", run.done, run.total,
                        result.id.c_str(), to_string(result.verdict), result.seconds,
                        result.message.empty() ? "" : "  ", result.message.c_str());
        std::fflush(stdout);
        results[i] = std::move(result);
        if (o.on_result) o.on_result(i, results[i]);
    };
    // A process of several cases: those it finished are done; the one it was running when it
    // ended otherwise than by exiting cleanly, and every case after it, run again alone (so a
    // crash or hang is the case's own, judged as any single case is). Killed at the limit, the
    // case it was running has timed out once, as a single case killed there has: it runs once
    // more alone before its TIMEOUT counts. After a clean exit with every result written,
    // nothing is left.
    auto finish_group = [&](size_t g, const ChildOutcome& outcome) {
        const std::vector<size_t>& group = groups[g];
        if (group.size() == 1) return finish(group.front(), outcome, false, false);
        const bool clean = outcome.started && !outcome.timed_out && outcome.exit_code == 0;
        size_t k = 0;
        std::error_code ec;
        while (k < group.size() && fs::exists(case_result_file(directories[group[k]]), ec)) ++k;
        // After an unclean end the last result may be the one a dying process wrote.
        if (!clean && k == group.size()) --k;
        for (size_t j = 0; j < k; ++j) {
            ChildOutcome done = outcome;
            done.timed_out = false, done.exit_code = 0, done.signal = 0;
            finish(group[j], done, false, true);
        }
        const std::string shared = fmt::format("its process, shared with {} other case{},",
                                               group.size() - 1, group.size() == 2 ? "" : "s");
        for (size_t j = k; j < group.size(); ++j) {
            if (j == k && outcome.timed_out) {
                // The limit, as a single case's first: one more run alone decides.
                ChildOutcome first = outcome;
                first.message =
                    fmt::format("{} ran out of time while running it: {}", shared, outcome.message);
                finish(group[j], first, false, false);
                continue;
            }
            if (j == k && !clean)
                shared_ends[group[j]] =
                    fmt::format("{} ended while running it ({})", shared, outcome.message);
            alone.push_back(group[j]);
        }
    };
    run_children(group_jobs, o.jobs, finish_group, server.get());
    // Cases run again, each in a process of its own, `parallel` at a time.
    auto run_alone = [&](const std::vector<size_t>& which, unsigned parallel, bool retried) {
        std::vector<ChildJob> again;
        for (size_t i : which) {
            prepare(i);
            again.push_back(job_for({i}));
        }
        run_children(
            again, parallel,
            [&](size_t k, const ChildOutcome& outcome) {
                finish(which[k], outcome, retried, false);
            },
            server.get());
    };
    if (!alone.empty()) run_alone(alone, o.jobs, false);
    // After `alone`: a case it ran may have timed out once.
    if (!timed_out.empty()) run_alone(timed_out, 1, true);
    return results;
}

}  // namespace acetate::harness
