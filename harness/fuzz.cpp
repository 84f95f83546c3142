#include "fuzz.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "case_batch.hpp"
#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "core/strict_json.hpp"
#include "input_model.hpp"
#include "registry.hpp"
#include "report.hpp"
#include "validate.hpp"

namespace acetate::harness {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

// Shrinking stops after this many accepted steps: each step makes the case strictly simpler,
// so a case needs far fewer (a 300x200 canvas halves to 1x1 in 18).
constexpr int kMaxShrinkSteps = 200;

std::string reproduce_line(const FuzzOptions& o, const fs::path& case_file) {
    return fmt::format("acetate-harness fuzz {} --reproduce {} --timeout {}",
                       shell_word(o.plugin.string()), shell_word(case_file.string()),
                       o.timeout_seconds);
}

// The checks that failed in a case (or its process verdict: CRASH, TIMEOUT).
std::vector<std::string> failing_checks(const CaseResult& r) {
    std::vector<std::string> out;
    if (r.verdict == Verdict::Crash || r.verdict == Verdict::Timeout)
        out.push_back(to_string(r.verdict));
    for (const CheckResult& c : r.checks)
        if (is_failing(c.verdict)) out.push_back(c.check);
    return out;
}

bool shares_a_failure(const CaseResult& r, const std::vector<std::string>& wanted) {
    for (const std::string& check : failing_checks(r))
        if (std::find(wanted.begin(), wanted.end(), check) != wanted.end()) return true;
    return false;
}

std::string one_line(const CaseSpec& s) {
    std::string text;
    for (const auto& [dimension, value] : s.inputs)
        text += fmt::format("{}{}: {}", text.empty() ? "" : "; ", dimension, value);
    return text + "; params " + s.params.dump();
}

// A drawn case: the whole model at uniform random coordinates.
CaseSpec draw(const PluginInfo& plugin, uint64_t seed, uint64_t index) {
    CaseSpec s;
    s.id = fmt::format("fuzz/{}", index);
    s.description = "a case drawn from the whole input model";
    s.seed = case_seed(seed, s.id);
    std::mt19937_64 rng(s.seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<double> u(scenario_dimensions(plugin));
    for (double& v : u) v = unit(rng);
    scenario_at(plugin, u, s);
    s.poison = index % 3 == 2 ? Poison::Large : Poison::NaN;
    s.inputs = describe_inputs(s, plugin);
    return s;
}

struct Shrunk {
    CaseResult result;
    CaseSpec spec;
    int steps = 0;
    uint64_t tried = 0;
};

// Greedy: of the candidates, in order, the first that still fails one of the same checks
// becomes the case; again until no candidate fails. Candidates run `jobs` at a time.
Shrunk shrink(const FuzzOptions& o, CaseBatch& batch, const PluginInfo& plugin, CaseSpec spec,
              CaseResult result) {
    const std::vector<std::string> wanted = failing_checks(result);
    Shrunk out{result, spec};
    while (out.steps < kMaxShrinkSteps) {
        std::vector<CaseSpec> candidates = shrink_candidates(out.spec, plugin);
        bool accepted = false;
        for (size_t first = 0; first < candidates.size() && !accepted; first += o.jobs) {
            std::vector<CaseSpec> group(
                candidates.begin() + first,
                candidates.begin() + std::min(candidates.size(), first + o.jobs));
            for (size_t i = 0; i < group.size(); ++i) {
                group[i].id = fmt::format("shrink/{}-{}", out.steps + 1, first + i + 1);
                group[i].inputs = describe_inputs(group[i], plugin);
            }
            const std::vector<CaseResult> results = run_case_batch(batch, group);
            out.tried += group.size();
            for (size_t i = 0; i < group.size() && !accepted; ++i)
                if (shares_a_failure(results[i], wanted)) {
                    out.spec = group[i];
                    out.result = results[i];
                    accepted = true;
                }
        }
        if (!accepted) break;
        ++out.steps;
        std::printf("shrink step %d: %s\n", out.steps, one_line(out.spec).c_str());
        std::fflush(stdout);
    }
    return out;
}

Result<PluginInfo> describe(const FuzzOptions& o) {
    setenv("ACETATE_VALIDATION", "1", 1);  // as validate: evidence of the same kind
    auto info = describe_in_child(o.self, o.plugin, o.report_directory, o.timeout_seconds);
    if (!info) return info.error();
    ACETATE_TRY(write_file_atomically(o.report_directory / "plugin.json", to_json(*info).dump(2)));
    return info;
}

int reproduce(const FuzzOptions& o, CaseBatch& batch) {
    auto text = read_json_file(*o.reproduce, kMaxHarnessFileBytes, "a fuzz case");
    auto spec =
        text ? case_spec_from_json(*text, o.reproduce->string()) : Result<CaseSpec>(text.error());
    if (!spec) {
        std::fprintf(stderr, "acetate-harness: %s\n", spec.error().message.c_str());
        return 1;
    }
    // Fuzzing draws contract cases, which run the plugin under test alone. A case file that
    // names other libraries would have this command load code no registry vouched for.
    if (!spec->companions.empty()) {
        std::fprintf(stderr,
                     "acetate-harness: %s: companions: a fuzz case runs the plugin alone; this "
                     "case names %zu other librar%s (integration cases run through acetate-"
                     "harness validate, which takes companions only from the registry)\n",
                     o.reproduce->string().c_str(), spec->companions.size(),
                     spec->companions.size() == 1 ? "y" : "ies");
        return 1;
    }
    batch.total = 1;
    const CaseResult r = run_case_batch(batch, std::vector<CaseSpec>{spec.value()}).front();
    std::printf("%s: %s%s%s\n", r.id.c_str(), to_string(r.verdict), r.message.empty() ? "" : ": ",
                r.message.c_str());
    for (const CheckResult& c : r.checks)
        std::printf("%-26s %-8s %s\n", c.check.c_str(), to_string(c.verdict), c.message.c_str());
    return is_failing(r.verdict) ? 1 : 0;
}

}  // namespace

Result<double> parse_duration(const std::string& text) {
    size_t used = 0;
    double value = 0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    const std::string unit = text.substr(used);
    const double scale = unit.empty() || unit == "s" ? 1
                         : unit == "m"               ? 60
                         : unit == "h"               ? 3600
                                                     : 0;
    if (used == 0 || scale == 0 || !std::isfinite(value) || value <= 0)
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("--duration: expected seconds or a number with s, m or h "
                                      "(e.g. 90s, 10m), got \"{}\"",
                                      text));
    return value * scale;
}

std::vector<CaseSpec> shrink_candidates(const CaseSpec& f, const PluginInfo& plugin) {
    std::vector<CaseSpec> out;
    auto with = [&](auto change) {
        CaseSpec s = f;
        change(s);
        out.push_back(std::move(s));
    };
    // Floors: one floor; the floors above the plugin's dropped; the top floor dropped.
    if (f.floors > 1) {
        if (f.plugin_floor < 0)
            with([](CaseSpec& s) { s.floors = 1; });
        else if (uint32_t(f.plugin_floor) + 1 < f.floors)
            with([](CaseSpec& s) { s.floors = uint32_t(s.plugin_floor) + 1; });
        if (f.plugin_floor != 0)
            with([](CaseSpec& s) {
                s.floors -= 1;
                if (s.plugin_floor >= int32_t(s.floors)) s.plugin_floor = int32_t(s.floors) - 1;
            });
    }
    if (f.prior_loads > 0) with([](CaseSpec& s) { s.prior_loads = 0; });
    if (f.frames > 1) with([](CaseSpec& s) { s.frames = 1; });
    if (f.frames > 2) with([](CaseSpec& s) { s.frames /= 2; });
    // Canvas: 1, then halves of either parity, then one pixel less.
    auto sizes = [](uint32_t n) {
        std::vector<uint32_t> v;
        for (uint32_t m : {1u, n / 2, n / 2 + 1, n - 1})
            if (m >= 1 && m < n && std::find(v.begin(), v.end(), m) == v.end()) v.push_back(m);
        return v;
    };
    for (uint32_t w : sizes(f.width)) with([w](CaseSpec& s) { s.width = w; });
    for (uint32_t h : sizes(f.height)) with([h](CaseSpec& s) { s.height = h; });
    // Parameters: to the default, else halfway there.
    for (const ParamInfo& p : plugin.params) {
        if (!f.params.contains(p.name)) continue;
        const float v = f.params[p.name].get<float>();
        if (v == p.default_value) continue;
        with([&](CaseSpec& s) { s.params.erase(p.name); });
        float half = v + (p.default_value - v) * 0.5f;
        if (p.type == "int" || p.type == "bool") half = std::round(half);
        if (half != v && half != p.default_value)
            with([&](CaseSpec& s) { s.params[p.name] = half; });
    }
    // Time: 0, half, the whole seconds.
    if (f.time != 0) {
        with([](CaseSpec& s) { s.time = 0; });
        if (std::abs(f.time) > 1e-3) with([](CaseSpec& s) { s.time *= 0.5; });
        if (std::trunc(f.time) != f.time && std::trunc(f.time) != 0)
            with([](CaseSpec& s) { s.time = std::trunc(s.time); });
    }
    // Inputs: the standard pattern, three lights, masks with content.
    if (f.pattern != Pattern::Standard) with([](CaseSpec& s) { s.pattern = Pattern::Standard; });
    if (f.lights != LightSet::Standard) with([](CaseSpec& s) { s.lights = LightSet::Standard; });
    if (f.masks != MaskFill::Content) with([](CaseSpec& s) { s.masks = MaskFill::Content; });
    if (f.floor_variant != FloorVariant::Standard)
        with([](CaseSpec& s) { s.floor_variant = FloorVariant::Standard; });
    for (CaseSpec& s : out) s.inputs.clear();  // re-described by the caller
    return out;
}

int run_fuzz(const FuzzOptions& o) {
    const auto start = Clock::now();
    std::error_code ec;
    fs::create_directories(o.report_directory, ec);
    auto plugin = describe(o);
    if (!plugin) {
        std::fprintf(stderr, "acetate-harness: %s\n", plugin.error().message.c_str());
        return 1;
    }
    CaseBatch batch;
    batch.self = o.self;
    batch.plugin_info_file = o.report_directory / "plugin.json";
    batch.report_directory = o.report_directory;
    batch.jobs = o.jobs;
    batch.timeout_seconds = o.timeout_seconds;
    batch.quiet = true;
    batch.reproduce = [&](const CaseSpec& spec) {
        return reproduce_line(o, o.report_directory / "cases" / case_folder(spec.id) / "case.json");
    };
    if (o.reproduce) return reproduce(o, batch);

    std::printf("fuzzing %s %s for %s with %u jobs, seed %llu\n", plugin->id.c_str(),
                plugin->version.c_str(), fmt::format("{:g} s", o.duration_seconds).c_str(), o.jobs,
                (unsigned long long)o.seed);
    const auto deadline = start + std::chrono::duration<double>(o.duration_seconds);
    uint64_t drawn = 0;
    std::optional<std::pair<CaseSpec, CaseResult>> failure;
    auto last_progress = Clock::now();
    while (!failure && Clock::now() < deadline) {
        std::vector<CaseSpec> group;
        for (unsigned i = 0; i < o.jobs; ++i) group.push_back(draw(*plugin, o.seed, ++drawn));
        const std::vector<CaseResult> results = run_case_batch(batch, group);
        for (size_t i = 0; i < results.size() && !failure; ++i)
            if (is_failing(results[i].verdict)) failure.emplace(group[i], results[i]);
        // Passing cases' folders go: a long campaign draws thousands.
        for (size_t i = 0; i < results.size(); ++i)
            if (!is_failing(results[i].verdict))
                fs::remove_all(o.report_directory / "cases" / case_folder(group[i].id), ec);
        if (Clock::now() - last_progress > std::chrono::seconds(10)) {
            last_progress = Clock::now();
            std::printf("%llu cases, %.0f s, no failure yet\n", (unsigned long long)drawn,
                        std::chrono::duration<double>(Clock::now() - start).count());
            std::fflush(stdout);
        }
    }
    const double drawing = std::chrono::duration<double>(Clock::now() - start).count();
    if (!failure) {
        std::printf("no failure in %llu cases drawn in %.0f s\n", (unsigned long long)drawn,
                    drawing);
        return 0;
    }
    const auto& [spec, result] = *failure;
    std::printf("%s failed (%s) after %llu cases in %.0f s: %s\n", spec.id.c_str(),
                fmt::format("{}", fmt::join(failing_checks(result), ", ")).c_str(),
                (unsigned long long)drawn, drawing, one_line(spec).c_str());
    std::fflush(stdout);
    const Shrunk shrunk = shrink(o, batch, *plugin, spec, result);
    const fs::path shrunk_file = o.report_directory / "shrunk-case.json";
    CaseSpec final_spec = shrunk.spec;
    final_spec.id = "fuzz/shrunk";
    (void)write_file_atomically(shrunk_file, to_json(final_spec).dump(2));

    ValidationReport report;
    report.harness_version = kHarnessVersion;
    report.plugin_file = o.plugin.string();
    report.id = plugin->id;
    report.version = plugin->version;
    report.display_name = plugin->display_name;
    report.scope = plugin->scope;
    report.coverage = plugin->coverage;
    report.binary_sha256 = plugin->binary_sha256;
    report.source_digest = plugin->source_digest;
    report.seed = o.seed;
    report.started_at = utc_now_iso8601();
    report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    report.cases = {result, shrunk.result};
    report.cases.back().reproduce = reproduce_line(o, shrunk_file);
    (void)write_json_report(report, o.report_directory / "report.json");
    (void)write_html_report(report, o.report_directory);

    std::printf("shrunk in %d steps (%llu cases tried) to: %s\n", shrunk.steps,
                (unsigned long long)shrunk.tried, one_line(shrunk.spec).c_str());
    for (const CheckResult& c : shrunk.result.checks)
        if (is_failing(c.verdict)) std::printf("  %s: %s\n", c.check.c_str(), c.message.c_str());
    std::printf("reproduce: %s\nreport: %s\n", reproduce_line(o, shrunk_file).c_str(),
                (o.report_directory / "index.html").string().c_str());
    return 1;
}

}  // namespace acetate::harness
