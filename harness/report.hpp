#pragma once
// What one `acetate-harness validate` run found, and how it is written out: report.json for
// machines, index.html for people (docs/harness.md describes both).
//
// A run is a list of cases (an input scenario: sizes/1x1, params/max, ...), each run in its own
// child process. A case evaluates several checks (premultiplied, coverage, ...); a check's
// verdict over the run is the worst of its verdicts over the cases.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace acetate::harness {

// Ordered by severity: a check's overall verdict is the maximum over its cases. WAIVED is a
// FAIL a maintainer's waiver accepts (never read as PASS); FLAKY is a case run several times
// (--repeat) whose verdict changed from one run to another.
enum class Verdict {
    Pass = 0,
    Skip = 1,
    Warn = 2,
    Waived = 3,
    Fail = 4,
    Flaky = 5,
    Timeout = 6,
    Crash = 7
};
// "PASS", "SKIP", "WARN", "WAIVED", "FAIL", "FLAKY", "TIMEOUT", "CRASH"
const char* to_string(Verdict verdict);
std::optional<Verdict> parse_verdict(std::string_view name);
// FAIL, FLAKY, TIMEOUT and CRASH fail a run (non-zero exit, no evidence recorded).
bool is_failing(Verdict verdict);
// CRASH and TIMEOUT: the child process, not a check, failed.
bool is_process_failure(Verdict verdict);
// Every verdict, by severity.
inline constexpr std::array<Verdict, 8> kVerdicts = {
    Verdict::Pass, Verdict::Skip,  Verdict::Warn,    Verdict::Waived,
    Verdict::Fail, Verdict::Flaky, Verdict::Timeout, Verdict::Crash};
// The pseudo-check that collects cases whose child process crashed or ran out of time.
inline constexpr const char* kProcessCheck = "process";
// How report.json writes the values JSON has no number for.
inline constexpr std::string_view kNaN = "NaN", kInfinity = "Infinity",
                                  kMinusInfinity = "-Infinity";

// One offending pixel: where, on which floor (-1: the composite / a global effect's output),
// the values before and after the effect, and what is wrong with them.
struct Violation {
    int64_t x = 0, y = 0;
    int64_t floor = -1;
    std::array<float, 4> input{0, 0, 0, 0};   // premultiplied rgba going in
    std::array<float, 4> output{0, 0, 0, 0};  // premultiplied rgba coming out
    std::string what;                         // e.g. "a = 0 but rgb = (0.25, 0, 0)"
};

// One check's verdict in one case.
struct CheckResult {
    std::string check;  // "premultiplied", "coverage", ...
    Verdict verdict = Verdict::Pass;
    std::string message;      // one line: what was checked and the threshold, or what failed
    uint64_t violations = 0;  // offending pixels (all of them, not only the examples)
    std::vector<Violation> examples;  // the first few, for the report
    // Images for the report, relative to the report directory, by role: "heatmap.floor0", ...
    std::map<std::string, std::string> images;
};

// One case: a child process that rendered one scenario and evaluated its checks.
struct CaseResult {
    std::string id;                   // "sizes/1x1", "params/random-3", ...; unique in a run
    std::string description;          // one line for people
    uint64_t seed = 0;                // reproduces the case's inputs and parameters
    Verdict verdict = Verdict::Pass;  // the worst of its checks, or CRASH / TIMEOUT
    std::string message;              // for CRASH / TIMEOUT: the signal or the time limit
    std::vector<CheckResult> checks;
    // Input and output pictures, relative to the report directory, by role: "input.floor0",
    // "output.floor0", "composite", ...
    std::map<std::string, std::string> images;
    double seconds = 0;         // wall time of the child
    std::string reproduce;      // the command line that re-runs exactly this case
    std::string log;            // the child's stderr, last lines
    std::string output_digest;  // SHA-256 of the outputs it read back (determinism)
    // The input model's dimensions and this case's value of each ("lights": "none", ...).
    std::map<std::string, std::string> inputs;
};

// An automated stage the run tried, and what came of it.
struct StageRun {
    std::string stage;      // "ALPHA_TESTED" / "INTEGRATED"
    bool passed = false;    // no failing verdict
    bool recorded = false;  // evidence went into the registry
    std::string note;       // why it was not recorded, or where
};

// One sign-off or evidence line of the plugin's history in the registry.
struct HistoryLine {
    std::string at, what, by;  // when, "review" / "ALPHA_TESTED evidence" / ..., who or harness
    std::string notes;
};

struct ValidationReport {
    std::string harness_version;
    std::string plugin_file;  // as given
    std::string id, version, display_name;
    std::string scope;     // "floor" / "global"
    std::string coverage;  // "preserving" / "expanding"
    std::string binary_sha256, source_digest;
    std::string stage_before, stage_after;  // registry stages, e.g. "REVIEWED"
    int strictness = 5;
    uint64_t seed = 0;
    std::string combinations;  // how the dimensions were combined (combinations_summary)
    std::string started_at;    // ISO-8601 UTC
    double seconds = 0;
    std::vector<StageRun> stages;
    std::vector<CaseResult> cases;
    std::vector<HistoryLine> history;
    std::string error;  // set when the run could not start (the plugin did not load, ...)
};

// A check's overall verdict and how many cases gave each verdict.
struct CheckSummary {
    std::string check;
    Verdict verdict = Verdict::Skip;
    std::map<Verdict, uint64_t> cases;
    std::string first_failure;  // "params/max: ..." for the first failing case, if any
};
std::vector<CheckSummary> summarize_checks(const ValidationReport& report);
// Per dimension of the input model, per value tried: the cases and their worst verdict.
struct InputValueSummary {
    uint64_t cases = 0;
    Verdict worst = Verdict::Pass;
};
std::map<std::string, std::map<std::string, InputValueSummary>> summarize_inputs(
    const ValidationReport& report);
// Case verdict -> number of cases, with the names of registry evidence ("PASS", "FAIL", ...).
std::map<std::string, uint64_t> count_verdicts(const ValidationReport& report);
bool run_failed(const ValidationReport& report);

nlohmann::json to_json(const Violation& violation);
nlohmann::json to_json(const CheckResult& check);
nlohmann::json to_json(const CaseResult& result);
nlohmann::json to_json(const ValidationReport& report);
// The inverse of to_json(CaseResult): how the parent reads a child's result file.
Result<CaseResult> case_result_from_json(const nlohmann::json& json, std::string_view name);
// The same inside another reader of the one field reader (core/json_fields.hpp): a bad field
// throws json_fields::JsonFieldError, for that reader's read_json to catch.
CaseResult read_case_result(const nlohmann::json& json, const std::string& path);

// report.json, written atomically.
Result<void> write_json_report(const ValidationReport& report, const std::filesystem::path& file);
// index.html in `directory`: a summary table per check, then per case its checks, violation
// examples and images (paths as in the report, relative to `directory`), the stage history
// and how to reproduce each failure. Self-contained apart from the images; written atomically.
Result<void> write_html_report(const ValidationReport& report,
                               const std::filesystem::path& directory);

}  // namespace acetate::harness
