#pragma once
// What the steps of `validate` (validate_run.cpp) share with `--list-cases` and with each
// other: the re-run command of a case, the comparisons across processes, the companions, the
// summary printed at the end (validate.cpp).

#include <filesystem>
#include <string>
#include <vector>

#include "case_spec.hpp"
#include "registry.hpp"
#include "report.hpp"
#include "validate.hpp"

namespace acetate::harness {

// The command line that runs one case again, alone, with this run's options.
std::string reproduce_command(const ValidateOptions& o, const std::string& case_id);

// This machine's name as a folder name: a --case shard's own folder is named by it and its
// process id, as two machines' process ids may coincide.
std::string host_name();

// The determinism runs compare across processes: every run's digest must match
// determinism/run-1's; where one differs, its `determinism` check fails and names the first
// floor that differs (from the outputs the cases kept under `report_dir`).
void compare_across_processes(std::vector<CaseResult>& results,
                              const std::filesystem::path& report_dir);

// Whether no case and no check of `results` failed.
bool all_pass(const std::vector<CaseResult>& results);

// Integrated or validated plugins other than this one, found on the plugin search path with
// the binary the registry recorded for them; a note for each that was not found.
std::vector<CompanionPlugin> find_companions(const Registry& registry, const PluginInfo& plugin,
                                             const std::vector<std::filesystem::path>& extra_paths,
                                             std::vector<std::string>& notes);

// The table of checks printed at the end of a run: each check's verdict and case counts.
void print_summary(const ValidationReport& report);

}  // namespace acetate::harness
