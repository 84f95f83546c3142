#pragma once
// `acetate-harness fuzz`: draws contract cases from the whole input model (input_model.hpp)
// until its time is up, each in a child process as `validate` runs them; on the first failure
// it shrinks the case (fewer floors, a smaller canvas, no history, parameters toward their
// defaults, time toward 0, the simplest inputs) to the smallest one that still fails the same
// check, and prints a `--reproduce` line for it. docs/harness.md, "Fuzzing".

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "case_spec.hpp"
#include "core/result.hpp"

namespace acetate::harness {

struct FuzzOptions {
    std::filesystem::path plugin;
    double duration_seconds = 600;  // --duration: drawing stops then (shrinking may go on)
    unsigned jobs = 2;
    uint64_t seed = 1;
    double timeout_seconds = 120;                    // one case
    std::filesystem::path report_directory;          // cases, report.json, index.html, shrunk.json
    std::optional<std::filesystem::path> reproduce;  // --reproduce CASE.json: run just that
    std::filesystem::path self;                      // this executable, for the children
};

// Returns the exit status: 0 when no drawn case failed, 1 when one did (or the case given to
// --reproduce failed) or the run could not start.
int run_fuzz(const FuzzOptions& options);

// "90", "90s", "10m", "1h": seconds; an error names the text.
Result<double> parse_duration(const std::string& text);

// The next smaller cases to try when `failing` fails: each changes one thing toward the
// simplest case (in this order: floors, history, canvas, parameters, time, inputs). Empty
// when it is as small as it gets.
std::vector<CaseSpec> shrink_candidates(const CaseSpec& failing, const PluginInfo& plugin);

}  // namespace acetate::harness
