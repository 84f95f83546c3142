#include "report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <set>

#include "core/atomic_file.hpp"
#include "core/json_fields.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;
using nlohmann::json;

// ---- verdicts -------------------------------------------------------------------------------

const char* to_string(Verdict verdict) {
    switch (verdict) {
        case Verdict::Pass:
            return "PASS";
        case Verdict::Skip:
            return "SKIP";
        case Verdict::Warn:
            return "WARN";
        case Verdict::Waived:
            return "WAIVED";
        case Verdict::Fail:
            return "FAIL";
        case Verdict::Flaky:
            return "FLAKY";
        case Verdict::Timeout:
            return "TIMEOUT";
        case Verdict::Crash:
            return "CRASH";
    }
    return "UNKNOWN";
}

std::optional<Verdict> parse_verdict(std::string_view name) {
    for (Verdict verdict : kVerdicts) {
        const std::string upper = to_string(verdict);
        std::string lower = upper;
        std::transform(lower.begin(), lower.end(), lower.begin(),
                       [](unsigned char c) { return char(std::tolower(c)); });
        if (name == upper || name == lower) return verdict;
    }
    return std::nullopt;
}

bool is_process_failure(Verdict verdict) {
    return verdict == Verdict::Crash || verdict == Verdict::Timeout;
}

bool is_failing(Verdict verdict) {
    return verdict == Verdict::Fail || verdict == Verdict::Flaky || is_process_failure(verdict);
}

// ---- summaries ------------------------------------------------------------------------------

namespace {

// One check's verdicts as the cases come in. The first failure wins over the first warning
// whenever there is one, so both are held until the end.
struct CheckTally {
    explicit CheckTally(std::string check) { summary.check = std::move(check); }

    CheckSummary summary;
    bool seen = false;
    std::string first_failing, first_warning;

    void add(Verdict verdict, const std::string& case_id, const std::string& message) {
        summary.verdict = seen ? std::max(summary.verdict, verdict) : verdict;
        seen = true;
        ++summary.cases[verdict];
        std::string* first = is_failing(verdict)        ? &first_failing
                             : verdict == Verdict::Warn ? &first_warning
                                                        : nullptr;
        if (first && first->empty()) *first = fmt::format("{}: {}", case_id, message);
    }

    CheckSummary finish() && {
        summary.first_failure = !first_failing.empty() ? first_failing : first_warning;
        return std::move(summary);
    }
};

}  // namespace

std::vector<CheckSummary> summarize_checks(const ValidationReport& report) {
    std::vector<CheckTally> tallies;
    std::map<std::string, size_t> index;  // check name -> position in `tallies`
    for (const CaseResult& result : report.cases) {
        for (const CheckResult& check : result.checks) {
            auto [at, added] = index.try_emplace(check.check, tallies.size());
            if (added) tallies.emplace_back(check.check);
            tallies[at->second].add(check.verdict, result.id, check.message);
        }
    }

    // Every case that ran is one verdict of the process: a crash or a timeout, or it completed
    // (PASS). A crashed child usually wrote no check results, so without this row the summary
    // would not show the crash at all. A run with no cases has nothing to say about processes.
    if (!report.cases.empty()) {
        CheckTally process(kProcessCheck);
        for (const CaseResult& result : report.cases)
            process.add(is_process_failure(result.verdict) ? result.verdict : Verdict::Pass,
                        result.id, result.message);
        tallies.push_back(std::move(process));
    }

    std::vector<CheckSummary> out;
    out.reserve(tallies.size());
    for (CheckTally& tally : tallies) out.push_back(std::move(tally).finish());
    return out;
}

std::map<std::string, std::map<std::string, InputValueSummary>> summarize_inputs(
    const ValidationReport& report) {
    std::map<std::string, std::map<std::string, InputValueSummary>> out;
    for (const CaseResult& c : report.cases)
        for (const auto& [dimension, value] : c.inputs) {
            InputValueSummary& s = out[dimension][value];
            ++s.cases;
            s.worst = std::max(s.worst, c.verdict);
        }
    return out;
}

std::map<std::string, uint64_t> count_verdicts(const ValidationReport& report) {
    std::map<std::string, uint64_t> counts;
    for (const CaseResult& result : report.cases) ++counts[to_string(result.verdict)];
    return counts;
}

bool run_failed(const ValidationReport& report) {
    if (!report.error.empty()) return true;
    return std::any_of(report.cases.begin(), report.cases.end(), [](const CaseResult& result) {
        return is_failing(result.verdict) ||
               std::any_of(result.checks.begin(), result.checks.end(),
                           [](const CheckResult& check) { return is_failing(check.verdict); });
    });
}

// ---- JSON writing ---------------------------------------------------------------------------

namespace {

// nlohmann writes NaN and the infinities as null, which would lose exactly the values that
// violations are about, so they travel as the strings JavaScript's Number() understands.
json non_finite_to_json(double value) {
    if (std::isnan(value)) return kNaN;
    return value > 0 ? kInfinity : kMinusInfinity;
}

json number_to_json(double value) {
    return std::isfinite(value) ? json(value) : non_finite_to_json(value);
}

// A float as the shortest decimal that reads back as the same float ("0.1", not
// "0.10000000149011612"), falling back to the exact double when going through double would
// round it elsewhere, so reading it back always gives the same bits.
json float_to_json(float value) {
    if (!std::isfinite(value)) return non_finite_to_json(value);
    const double shortest = std::strtod(fmt::format("{}", value).c_str(), nullptr);
    return static_cast<float>(shortest) == value ? shortest : static_cast<double>(value);
}

json rgba_to_json(const std::array<float, 4>& rgba) {
    json out = json::array();
    for (float channel : rgba) out.push_back(float_to_json(channel));
    return out;
}

json images_to_json(const std::map<std::string, std::string>& images) {
    json out = json::object();
    for (const auto& [role, path] : images) out[role] = path;
    return out;
}

// The two records without a public to_json: only the report holds them.
json to_json(const StageRun& run) {
    return json{{"stage", run.stage},
                {"passed", run.passed},
                {"recorded", run.recorded},
                {"note", run.note}};
}

json to_json(const HistoryLine& line) {
    return json{{"at", line.at}, {"what", line.what}, {"by", line.by}, {"notes", line.notes}};
}

template <class T>
json list_to_json(const std::vector<T>& items) {
    json out = json::array();
    for (const T& item : items) out.push_back(to_json(item));
    return out;
}

}  // namespace

json to_json(const Violation& violation) {
    return json{{"x", violation.x},
                {"y", violation.y},
                {"floor", violation.floor},
                {"input", rgba_to_json(violation.input)},
                {"output", rgba_to_json(violation.output)},
                {"what", violation.what}};
}

json to_json(const CheckResult& check) {
    return json{{"check", check.check},
                {"verdict", to_string(check.verdict)},
                {"message", check.message},
                {"violations", check.violations},
                {"examples", list_to_json(check.examples)},
                {"images", images_to_json(check.images)}};
}

json to_json(const CaseResult& result) {
    return json{{"id", result.id},
                {"description", result.description},
                {"seed", result.seed},
                {"verdict", to_string(result.verdict)},
                {"message", result.message},
                {"checks", list_to_json(result.checks)},
                {"images", images_to_json(result.images)},
                {"seconds", number_to_json(result.seconds)},
                {"reproduce", result.reproduce},
                {"log", result.log},
                {"output_digest", result.output_digest},
                {"inputs", result.inputs}};
}

// Per dimension of the input model, each value tried: how many cases, and their worst verdict.
json inputs_to_json(const ValidationReport& report) {
    json out = json::object();
    for (const auto& [dimension, values] : summarize_inputs(report))
        for (const auto& [value, summary] : values)
            out[dimension][value] = {{"cases", summary.cases}, {"worst", to_string(summary.worst)}};
    return out;
}

json to_json(const ValidationReport& report) {
    return json{{"harness_version", report.harness_version},
                {"plugin_file", report.plugin_file},
                {"id", report.id},
                {"version", report.version},
                {"display_name", report.display_name},
                {"scope", report.scope},
                {"coverage", report.coverage},
                {"binary_sha256", report.binary_sha256},
                {"source_digest", report.source_digest},
                {"stage_before", report.stage_before},
                {"stage_after", report.stage_after},
                {"strictness", report.strictness},
                {"combinations", report.combinations},
                {"seed", report.seed},
                {"started_at", report.started_at},
                {"seconds", number_to_json(report.seconds)},
                {"stages", list_to_json(report.stages)},
                {"cases", list_to_json(report.cases)},
                {"history", list_to_json(report.history)},
                {"input_model", inputs_to_json(report)},
                {"error", report.error}};
}

// ---- JSON reading ---------------------------------------------------------------------------
// The one field reader (core/json_fields.hpp); case_result_from_json turns its errors into a
// Result, so the readers below stay straight-line.

namespace {

using namespace json_fields;

// Each reader leaves `out` at its default when the key is absent.
void read_text(const json& j, const std::string& path, std::string_view key, std::string& out) {
    if (const json* v = optional(j, key)) out = text(*v, field(path, key));
}

void read_unsigned(const json& j, const std::string& path, std::string_view key, uint64_t& out) {
    if (const json* v = optional(j, key)) out = unsigned_integer(*v, field(path, key));
}

void read_signed(const json& j, const std::string& path, std::string_view key, int64_t& out) {
    if (const json* v = optional(j, key)) out = integer(*v, field(path, key));
}

// A number, or one of the strings float_to_json / number_to_json write for non-finite values.
double read_number_value(const json& v, const std::string& path) {
    if (v.is_number()) return v.get<double>();
    if (v.is_string()) {
        const std::string& s = v.get_ref<const std::string&>();
        if (s == kNaN) return std::numeric_limits<double>::quiet_NaN();
        if (s == kInfinity) return std::numeric_limits<double>::infinity();
        if (s == kMinusInfinity) return -std::numeric_limits<double>::infinity();
    }
    fail(path, "must be a number, \"NaN\", \"Infinity\" or \"-Infinity\", got " + describe(v));
}

void read_number(const json& j, const std::string& path, std::string_view key, double& out) {
    if (j.contains(key)) out = read_number_value(j.at(key), field(path, key));
}

void read_rgba(const json& j, const std::string& path, std::string_view key,
               std::array<float, 4>& out) {
    if (!j.contains(key)) return;
    const json& v = j.at(key);
    const std::string here = field(path, key);
    if (!v.is_array() || v.size() != 4)
        fail(here, "must be an array of 4 numbers (r, g, b, a), got " + describe(v));
    for (size_t i = 0; i < 4; ++i) {
        const double channel = read_number_value(v[i], element(here, i));
        // Narrowing a double that rounds past float's largest value is undefined. The bound is
        // half an ulp above FLT_MAX: the shortest decimal of FLT_MAX lies above it, but below this.
        constexpr double kRoundsToInfinity = 0x1.ffffffp+127;
        if (std::isfinite(channel) && std::abs(channel) >= kRoundsToInfinity)
            fail(element(here, i), fmt::format("{} is beyond the range of a float", channel));
        out[i] = static_cast<float>(channel);
    }
}

void read_verdict(const json& j, const std::string& path, std::string_view key, Verdict& out) {
    if (!j.contains(key)) return;
    std::string name;
    read_text(j, path, key, name);
    const std::optional<Verdict> verdict = parse_verdict(name);
    if (!verdict)
        fail(field(path, key),
             fmt::format("\"{}\" is not a verdict (PASS, SKIP, WARN, FAIL, TIMEOUT, CRASH)", name));
    out = *verdict;
}

void read_images(const json& j, const std::string& path, std::string_view key,
                 std::map<std::string, std::string>& out) {
    if (!j.contains(key)) return;
    const json& v = j.at(key);
    const std::string here = field(path, key);
    if (!v.is_object()) fail(here, "must be an object of role: path, got " + describe(v));
    for (const auto& item : v.items()) read_text(v, here, item.key(), out[item.key()]);
}

template <class T, class ReadOne>
void read_list(const json& j, const std::string& path, std::string_view key, std::vector<T>& out,
               ReadOne read_one) {
    if (!j.contains(key)) return;
    const std::string here = field(path, key);
    const json& v = array(j.at(key), here);
    for (size_t i = 0; i < v.size(); ++i) out.push_back(read_one(v[i], element(here, i)));
}

Violation read_violation(const json& j, const std::string& path) {
    expect_object(j, path, {"x", "y"}, {"floor", "input", "output", "what"});
    Violation v;
    read_signed(j, path, "x", v.x);
    read_signed(j, path, "y", v.y);
    read_signed(j, path, "floor", v.floor);
    read_rgba(j, path, "input", v.input);
    read_rgba(j, path, "output", v.output);
    read_text(j, path, "what", v.what);
    return v;
}

CheckResult read_check(const json& j, const std::string& path) {
    expect_object(j, path, {"check"}, {"verdict", "message", "violations", "examples", "images"});
    CheckResult check;
    read_text(j, path, "check", check.check);
    read_verdict(j, path, "verdict", check.verdict);
    read_text(j, path, "message", check.message);
    read_unsigned(j, path, "violations", check.violations);
    read_list(j, path, "examples", check.examples, read_violation);
    read_images(j, path, "images", check.images);
    return check;
}

}  // namespace

CaseResult read_case_result(const json& j, const std::string& path) {
    using namespace json_fields;
    expect_object(j, path, {"id"},
                  {"description", "seed", "verdict", "message", "checks", "images", "seconds",
                   "reproduce", "log", "output_digest", "inputs"});
    CaseResult result;
    read_text(j, path, "id", result.id);
    read_text(j, path, "description", result.description);
    read_unsigned(j, path, "seed", result.seed);
    read_verdict(j, path, "verdict", result.verdict);
    read_text(j, path, "message", result.message);
    read_list(j, path, "checks", result.checks, read_check);
    read_images(j, path, "images", result.images);
    read_number(j, path, "seconds", result.seconds);
    read_text(j, path, "reproduce", result.reproduce);
    read_text(j, path, "log", result.log);
    read_text(j, path, "output_digest", result.output_digest);
    read_images(j, path, "inputs", result.inputs);  // the same shape: an object of strings
    return result;
}

Result<CaseResult> case_result_from_json(const json& document, std::string_view name) {
    try {
        return json_fields::read_json(name, [&] { return read_case_result(document, ""); });
    } catch (const nlohmann::json::exception& e) {
        // The readers check every type first; this is a safety net, not an expected path.
        return make_error(ErrorCode::InvalidInput, fmt::format("{}: {}", name, e.what()));
    }
}

Result<void> write_json_report(const ValidationReport& report, const fs::path& file) {
    // Logs are a child's raw stderr and may hold invalid UTF-8, on which a strict dump throws;
    // replacing such bytes keeps the report writable and valid JSON.
    const std::string text =
        to_json(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    return write_file_atomically(file, text);
}

}  // namespace acetate::harness
