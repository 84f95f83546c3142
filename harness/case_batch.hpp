#pragma once
// Runs cases in child processes, `jobs` at a time, each with its own folder under
// `<report>/cases/` (case.json in, result.json, log.txt and pictures out), and turns each
// child's end into a CaseResult: its own result, or CRASH / TIMEOUT / FAIL with the cause.
// `validate` and `fuzz` both run their cases through it.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "case_spec.hpp"
#include "report.hpp"

namespace acetate::harness {

// The subcommand that makes acetate-harness a fork server (its main() calls serve_forks).
inline constexpr const char* kForkServerCommand = "fork-server";
// Whether children are forked from a server: yes, unless ACETATE_FORK_SERVER is "0".
bool fork_server_wanted();
// The fork server's preparation (serve_forks' `prepare`): what every case's child would do the
// same way at its start, done once in the server: glslang's built-in tables for both stages,
// and the Vulkan loader, driver and (with ACETATE_VALIDATION=1) validation layer loaded and
// relocated. Measured on lighting's validation: half the children's CPU time.
bool prepare_case_children(std::string& error);

inline constexpr unsigned kDefaultCasesPerProcess = 8;

struct CaseBatch {
    std::filesystem::path self;              // acetate-harness, started as `run-case`
    std::filesystem::path plugin_info_file;  // what `describe` wrote
    std::filesystem::path report_directory;  // cases/<folder>/ go under it
    unsigned jobs = 2;
    double timeout_seconds = 120;
    // The command line that re-runs one case (CaseResult::reproduce); none when unset.
    std::function<std::string(const CaseSpec&)> reproduce;
    bool quiet = false;  // no progress line per case
    // Called with the case's position in the batch and its final result (after a retry), as
    // each case finishes: a shard writes it at once (shard.hpp), so a shard killed later has
    // lost only the cases it was running.
    std::function<void(size_t, const CaseResult&)> on_result;
    // Fork each case's child from a server started once (core/fork_server.hpp); false when the
    // environment says ACETATE_FORK_SERVER=0.
    bool fork_server = fork_server_wanted();
    // Cases run one after another in one child process, on one device (case_runner.hpp): the
    // child's start and the device's opening, about half of a short case, are paid once for
    // them. 1 gives every case a process of its own. Cases that need one are alone whatever
    // this says (group_cases).
    unsigned cases_per_process = kDefaultCasesPerProcess;
    size_t done = 0, total = 0;  // progress: "[done/total]"
};

// Runs `cases` and returns their results in the same order; prints a progress line as each
// finishes (unless quiet).
std::vector<CaseResult> run_case_batch(CaseBatch& batch, const std::vector<CaseSpec>& cases);
// The same, case i in the folder cases/<folders[i]> (a repeated case needs one per run).
std::vector<CaseResult> run_case_batch(CaseBatch& batch, const std::vector<CaseSpec>& cases,
                                       const std::vector<std::string>& folders);

// Which cases share a child process, as positions in `cases`, in order: runs of consecutive
// cases, each at most `per_process` long and short enough that every job gets several (a long
// last process would leave the other cores idle). A case that must start a process of its own
// is alone: one run without the validation layer, or one of a kind that judges the process
// itself (CaseKindInfo::own_process).
std::vector<std::vector<size_t>> group_cases(const std::vector<CaseSpec>& cases,
                                             unsigned per_process, unsigned jobs);

// A case's folder name under cases/: its id with every character but letters, digits and '-'
// turned into '_'.
std::string case_folder(const std::string& id);

// A shell word: quoted when it holds anything but plain path characters.
std::string shell_word(const std::string& text);

}  // namespace acetate::harness
