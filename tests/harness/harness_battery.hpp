#pragma once
// What the broken-plugin battery's files share (harness_battery_test.cpp runs the battery,
// harness_battery_dimensions.cpp holds the evidence of the plugins that each break one dimension
// of the input model): one `validate` run of a plugin and what it left, read back.

#include <Imath/half.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "checks.hpp"
#include "registry.hpp"
#include "report.hpp"
#include "test_files.hpp"

namespace acetate::battery {

using ::acetate::test::contains;

namespace fs = std::filesystem;
using harness::Verdict;
using nlohmann::json;
using test::shell_quote;

// Seconds of CPU time a case may take: a case needs 0.3 to 2 s here (the limit counts the
// child's CPU time, so a busy machine does not use it up), and the limit leaves room.
// hangs_at_max's cases at iterations = 8 are killed at the shorter limit (twice each: it is what
// those cases cost), which still leaves its other cases twice what the slowest needs.
inline constexpr int kTimeoutSeconds = 30;
inline constexpr int kHangTimeoutSeconds = 4;

// A verdict from the report; a test failure (and FAIL) for an unknown name.
inline Verdict verdict_of(const json& j) {
    const auto v = harness::parse_verdict(j.get<std::string>());
    EXPECT_TRUE(v.has_value()) << "not a verdict: " << j.dump();
    return v.value_or(Verdict::Fail);
}

// A number of a violation's rgba: the report writes NaN and the infinities as strings.
inline float number(const json& j) {
    if (j.is_number()) return j.get<float>();
    const std::string s = j.get<std::string>();
    if (s == "NaN") return std::numeric_limits<float>::quiet_NaN();
    return s == "-Infinity" ? -std::numeric_limits<float>::infinity()
                            : std::numeric_limits<float>::infinity();
}

// The folder a case's files are in (validate.cpp's slug of the id).
inline std::string slug(const std::string& id) {
    std::string out = id;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
    return out;
}

// One `validate` run and what it left.
struct HarnessRun {
    test::CommandResult process;
    fs::path dir, report_dir, registry, plugin;
    json report;
    // Each check's worst verdict over the cases, and the cases that reported it.
    std::map<std::string, Verdict> worst;
    std::map<std::string, std::vector<const json*>> check_cases;  // check -> cases having it

    const json* find_case(const std::string& id) const {
        for (const json& c : report["cases"])
            if (c["id"] == id) return &c;
        return nullptr;
    }
    static const json* find_check(const json& c, const std::string& check) {
        for (const json& k : c["checks"])
            if (k["check"] == check) return &k;
        return nullptr;
    }
    // The case's spec as the harness wrote it for the child (width, height, floors, params).
    json case_spec(const std::string& id) const {
        const fs::path file = report_dir / "cases" / slug(id) / "case.json";
        try {
            return json::parse(test::read_file(file));
        } catch (const json::exception& e) {
            ADD_FAILURE() << file << ": " << e.what();
            return json::object();
        }
    }
    std::string describe() const { return process.describe(); }
};

// `acetate-harness --registry R validate PLUGIN --no-signoffs --report D --strictness 1
// --jobs 2 --timeout T --stage alpha-tested EXTRA`, in `dir`.
inline test::CommandResult validate(const fs::path& dir, const fs::path& plugin,
                                    const fs::path& report, const std::string& extra = "",
                                    int timeout = kTimeoutSeconds) {
    const std::string command =
        "cd " + shell_quote(dir.string()) + " && " + test::harness_environment() + " " +
        shell_quote(ACETATE_HARNESS_PATH) + " --registry " +
        shell_quote((dir / "registry.json").string()) + " validate " +
        shell_quote(plugin.string()) + " --no-signoffs --report " + shell_quote(report.string()) +
        " --strictness 1 --jobs 2 --timeout " + std::to_string(timeout) + " --stage alpha-tested " +
        extra;
    return test::run_command(command, dir);
}

inline json read_report(const fs::path& report_dir) {
    const fs::path file = report_dir / "report.json";
    try {
        return json::parse(test::read_file(file));
    } catch (const json::exception& e) {
        ADD_FAILURE() << file << ": " << e.what();
        return json::object();
    }
}

// The evidence of the input-model plugins (harness_battery_dimensions.cpp): each fails only in
// the cases of its own dimension, or a combined/* point that drew the same value.
void odd_width_even_height(const HarnessRun& run);
void high_floor_index(const HarnessRun& run);
void no_lights(const HarnessRun& run);
void many_lights(const HarnessRun& run);
void off_canvas_light(const HarnessRun& run);
void tiny_radius(const HarnessRun& run);
void huge_radius(const HarnessRun& run);
void full_mask(const HarnessRun& run);
void absent_mask(const HarnessRun& run);
void param_interior(const HarnessRun& run);
void negative_time(const HarnessRun& run);
void large_time(const HarnessRun& run);
void frame_count(const HarnessRun& run);
void other_canvas_load(const HarnessRun& run);
void subnormal_alpha(const HarnessRun& run);
void negative_colour(const HarnessRun& run);
void build_leak(const HarnessRun& run);
void result_partly_unwritten(const HarnessRun& run);
void undefined_everywhere(const HarnessRun& run);
void light_on_floor(const HarnessRun& run);
void sun_overhead(const HarnessRun& run);
void dark_light(const HarnessRun& run);
void mask_over_one(const HarnessRun& run);
void ascii_floor_names(const HarnessRun& run);
void empty_floor_bounds(const HarnessRun& run);
void fraction_below_one(const HarnessRun& run);
void clears_outside_coverage(const HarnessRun& run);
void canvas_fraction_falloff(const HarnessRun& run);
void half_float_positions(const HarnessRun& run);
void camera_blind(const HarnessRun& run);
void scale_blind(const HarnessRun& run);
void undefined_away_from_defaults(const HarnessRun& run);
void reach_checked(const HarnessRun& run);
void reach_cut_off(const HarnessRun& run);

}  // namespace acetate::battery
