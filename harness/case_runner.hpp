#pragma once
// The child side of the harness: runs one case in this process (which the parent started just
// for it, with validation layers on) and writes `result.json` plus the case's pictures into
// its directory. A crash or hang here takes only this process down; the parent reports it.

#include <filesystem>

#include "case_spec.hpp"
#include "report.hpp"

namespace acetate::harness {

struct CaseContext {
    PluginInfo plugin;
    CaseSpec spec;
    std::filesystem::path case_directory;    // result.json, pictures, the scenes' inputs
    std::filesystem::path report_directory;  // pictures are named relative to it
};

// Runs the case; never throws. Environment failures (no Vulkan device, an unwritable
// directory) come back as an error, which the parent reports as the case's failure.
Result<CaseResult> run_case(const CaseContext& context);

// The file the child writes its CaseResult to (atomically), and the parent reads.
std::filesystem::path case_result_file(const std::filesystem::path& case_directory);

}  // namespace acetate::harness
