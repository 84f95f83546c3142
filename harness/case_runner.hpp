#pragma once
// The child side of the harness: runs cases in this process (which the parent started for
// them, with validation layers on) and writes each case's `result.json` plus its pictures into
// the case's directory. A crash or hang here takes only this process down; the parent reports
// it, and runs again alone each case the process did not finish (case_batch.hpp).

#include <filesystem>
#include <vector>

#include "case_spec.hpp"
#include "report.hpp"

namespace acetate::harness {

struct CaseContext {
    PluginInfo plugin;
    CaseSpec spec;
    std::filesystem::path case_directory;    // result.json, log.txt, pictures, the scenes' inputs
    std::filesystem::path report_directory;  // pictures are named relative to it
};

// Runs the cases one after another. They share one Vulkan device, opened for the first and
// closed after the last (messages at its teardown count for the last case); each case has its
// own renderer (so its own load of the plugin), its own watch of the process's state, its own
// count of validation messages and its own log.txt (this process's stdout and stderr while it
// runs). Each case's result.json is written before the next case starts, so the parent can
// tell which cases finished. Environment failures (no Vulkan device, an unwritable directory)
// stop the run with an error, which the parent reports as the failure of the case that has no
// result.
Result<void> run_cases(const std::vector<CaseContext>& cases);

// The file the child writes its CaseResult to (atomically), and the parent reads.
std::filesystem::path case_result_file(const std::filesystem::path& case_directory);
// The case's log: the child's output while it ran the case.
std::filesystem::path case_log_file(const std::filesystem::path& case_directory);

}  // namespace acetate::harness
