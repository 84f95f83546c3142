// The process-hygiene check (docs/harness.md, `process-hygiene`): every plugin call in a case
// (load, build, unload) must leave the process as it found it. The planted fault is the
// battery's `unhygienic`, which breaks the rule named by $ACETATE_TEST_HYGIENE_RULE: one run of
// one case per rule, each failing process-hygiene alone with the change, the call and the
// plugin named. The control is the same plugin with no rule, which passes every check (and
// every battery plugin's run passes process-hygiene, harness_battery_test.cpp).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "test_files.hpp"

namespace acetate {
namespace {

using ::acetate::test::contains;

namespace fs = std::filesystem;
using nlohmann::json;
using test::shell_quote;

struct Rule {
    std::string name;     // $ACETATE_TEST_HYGIENE_RULE
    std::string message;  // what the check must say changed
};

void PrintTo(const Rule& r, std::ostream* os) {
    *os << (r.name.empty() ? "none" : r.name);
}

const Rule kRules[] = {
    {"", ""},  // the control
    {"rounding",
     "build of floor0.test.harness.unhygienic: rounding mode: to nearest -> toward "
     "zero"},
#if defined(__x86_64__)
    {"flush-to-zero", "flush-to-zero (MXCSR FTZ): off -> on"},
#endif
    {"signal", "signal disposition: SIGUSR1 added"},
    {"block-signal", "blocked signals: ["},
    {"environment", "environment: ACETATE_TEST_LEFT_BEHIND set"},
    {"descriptor", "added (/dev/null)"},
    {"thread", "threads: "},
    {"folder", "working folder: "},
    {"umask", "umask: "},
    {"locale", "locale: "},
};

class ProcessHygiene : public ::testing::TestWithParam<Rule> {};

TEST_P(ProcessHygiene, APluginCallThatChangesTheProcessFailsAndIsNamed) {
    const Rule& rule = GetParam();
    const fs::path dir = test::scratch_dir();
    const fs::path plugin = fs::path(ACETATE_HARNESS_PLUGIN_DIR) / "unhygienic.so";
    const std::string command =
        "cd " + shell_quote(dir.string()) + " && " + test::harness_environment() +
        " ACETATE_TEST_HYGIENE_RULE=" + shell_quote(rule.name) + " " +
        shell_quote(ACETATE_HARNESS_PATH) + " --registry " +
        shell_quote((dir / "registry.json").string()) + " validate " +
        shell_quote(plugin.string()) +
        " --case contract/standard --stage alpha-tested --strictness 1 --timeout 60 "
        "--no-signoffs --report " +
        shell_quote((dir / "report").string());
    const test::CommandResult run = test::run_command(command, dir);
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, rule.name.empty() ? 0 : 1);
    const json report = json::parse(test::read_file(dir / "report" / "report.json"));
    ASSERT_EQ(report["cases"].size(), 1u);
    const json& c = report["cases"][0];
    bool seen = false;
    for (const json& check : c["checks"]) {
        const std::string message = check["message"];
        if (check["check"] != "process-hygiene") {
            EXPECT_EQ(check["verdict"], "PASS") << check.dump(2);
            continue;
        }
        seen = true;
        if (rule.name.empty()) {
            EXPECT_EQ(check["verdict"], "PASS") << message;
            // At least a load, a build and an unload were watched (a host may build more).
            EXPECT_GE(std::atoi(message.c_str()), 3) << message;
            EXPECT_TRUE(contains(message, " plugin calls (loads, builds, unloads) each left"))
                << message;
        } else {
            EXPECT_EQ(check["verdict"], "FAIL") << message;
            EXPECT_TRUE(contains(message, rule.message)) << message;
            EXPECT_TRUE(contains(message, "test.harness.unhygienic") ||
                        contains(message, "unhygienic.so"))
                << message;
        }
    }
    EXPECT_TRUE(seen) << c.dump(2);
}

INSTANTIATE_TEST_SUITE_P(Rules, ProcessHygiene, ::testing::ValuesIn(kRules), [](const auto& info) {
    std::string name = info.param.name.empty() ? "none" : info.param.name;
    for (char& ch : name)
        if (ch == '-') ch = '_';
    return name;
});

}  // namespace
}  // namespace acetate
