#pragma once
// `acetate-harness bless PLUGIN --by NAME`: renders the plugin's reference cases
// (references.hpp) in child processes, as validate does, and stores their outputs as the
// plugin's golden references for its source digest. Look at the images before committing
// them: every later build is judged against them.

#include <filesystem>
#include <string>

namespace acetate::harness {

struct BlessOptions {
    std::filesystem::path plugin;
    std::filesystem::path references;        // the root: <root>/<plugin id>/
    std::filesystem::path report_directory;  // where the cases run (--report)
    std::filesystem::path self;              // this executable, for the children
    std::string by;
    unsigned jobs = 2;
    double timeout_seconds = 120;
};

// Returns the exit status: 0 when the references were written, 1 otherwise (one line why).
int run_bless(const BlessOptions& options);

}  // namespace acetate::harness
