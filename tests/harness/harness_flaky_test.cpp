// `acetate-harness validate --repeat N --shuffle` (docs/harness.md, "Flaky plugins"): every case
// runs N times, each run in a fresh process, all runs in one random order, and a case whose
// verdict changes is FLAKY, which fails the run. The planted fault is the battery's `flaky`: the
// first build() of a whole run (a ticket in the test's own folder) adds light where alpha is 0,
// every later one is correct. A correct plugin repeated and shuffled must never read FLAKY.
// A case killed at the time limit runs again before its TIMEOUT counts, alone or in a shared
// process, whose other unfinished cases run again alone (`slow_first_build`).

#include <gtest/gtest.h>

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

// `acetate-harness validate PLUGIN --stage alpha-tested --strictness 1 EXTRA` in `dir`, with its
// own registry and report, and the flaky plugin's ticket folder.
test::CommandResult validate(const fs::path& dir, const std::string& stem, const std::string& extra,
                             int timeout = 60) {
    fs::create_directories(dir / "tickets");
    const fs::path plugin = fs::path(ACETATE_HARNESS_PLUGIN_DIR) / (stem + ".so");
    const std::string command =
        "cd " + shell_quote(dir.string()) + " && " + test::harness_environment() +
        " ACETATE_TEST_FLAKY_DIR=" + shell_quote((dir / "tickets").string()) + " " +
        shell_quote(ACETATE_HARNESS_PATH) + " --registry " +
        shell_quote((dir / "registry.json").string()) + " validate " +
        shell_quote(plugin.string()) + " --stage alpha-tested --strictness 1 --jobs 2 " +
        "--timeout " + std::to_string(timeout) + " --no-signoffs --report " +
        shell_quote((dir / "report").string()) + " " + extra;
    return test::run_command(command, dir);
}

json report_of(const fs::path& dir) {
    return json::parse(test::read_file(dir / "report" / "report.json"));
}

// One case, three runs: the run that takes ticket 1 fails, the other two pass, whatever order
// the shuffle draws. The same case run once (a fresh ticket folder) is an ordinary FAIL: only
// repeating it shows that its verdict is not a property of the plugin and the input alone.
TEST(HarnessFlaky, AVerdictThatChangesBetweenRunsIsFlakyAndFailsTheRun) {
    const fs::path dir = test::scratch_dir();
    const test::CommandResult run =
        validate(dir, "flaky",
                 "--case contract/standard --repeat 3 --shuffle --junit " +
                     shell_quote((dir / "junit.xml").string()));
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, 1);
    EXPECT_TRUE(contains(run.out,
                         "every case 3 times, each in a fresh process, in random order "
                         "(--shuffle-seed "))
        << run.out;
    const json report = report_of(dir);
    ASSERT_EQ(report["cases"].size(), 1u) << report.dump();
    const json& c = report["cases"][0];
    EXPECT_EQ(c["verdict"], "FLAKY");
    // The repeat check names every run's verdict: one FAIL (the ticket-1 build), two PASS.
    bool named = false;
    for (const json& check : c["checks"]) {
        if (check["check"] == "repeat") {
            named = true;
            const std::string message = check["message"];
            EXPECT_TRUE(contains(message, "across 3 runs")) << message;
            EXPECT_TRUE(contains(message, "FAIL")) << message;
            EXPECT_TRUE(contains(message, "PASS")) << message;
        }
        // The failing run is the one shown: its coverage check failed.
        if (check["check"] == "coverage") {
            EXPECT_EQ(check["verdict"], "FAIL") << check.dump();
        }
    }
    EXPECT_TRUE(named) << c.dump();
    // Reproducing it repeats it too, in the same order.
    EXPECT_TRUE(contains(c["reproduce"].get<std::string>(), "--repeat 3 --shuffle-seed "))
        << c["reproduce"];
    EXPECT_TRUE(fs::exists(dir / "tickets" / "ticket-3"));  // the other runs really ran
    EXPECT_TRUE(contains(run.out, "FLAKY")) << run.out;
    // CI sees it too: the JUnit file marks the case failed, of type FLAKY, and is valid.
    const std::string junit = test::read_file(dir / "junit.xml");
    EXPECT_TRUE(contains(junit, "<failure ")) << junit;
    EXPECT_TRUE(contains(junit, "type=\"FLAKY\"")) << junit;
    const test::CommandResult schema =
        test::run_command("xmllint --noout --schema " + shell_quote(ACETATE_JUNIT_XSD) + " " +
                              shell_quote((dir / "junit.xml").string()),
                          dir);
    EXPECT_EQ(schema.code, 0) << schema.describe();

    const fs::path once = test::scratch_dir();
    const test::CommandResult single = validate(once, "flaky", "--case contract/standard");
    EXPECT_EQ(single.code, 1) << single.describe();
    EXPECT_EQ(report_of(once)["cases"][0]["verdict"], "FAIL");
}

// A case killed at the time limit runs once more in a fresh process before its TIMEOUT counts
// (the limit counts CPU time, and a loaded machine can still starve a case): slow_first_build
// computes for 30 s in its first build only, past the 5 s limit, and finishes when run again.
TEST(HarnessTimeouts, ACaseThatTimesOutOnceRunsAgainAndPasses) {
    const fs::path dir = test::scratch_dir();
    const test::CommandResult run =
        validate(dir, "slow_first_build", "--case contract/standard", 5);
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, 0);
    EXPECT_TRUE(contains(run.out, "running it once more")) << run.out;
    const json report = report_of(dir);
    ASSERT_EQ(report["cases"].size(), 1u) << report.dump();
    const json& c = report["cases"][0];
    EXPECT_EQ(c["verdict"], "PASS") << c.dump(2);
    const std::string message = c["message"];
    EXPECT_TRUE(contains(message, "timed out once (no result after 5 s of CPU time")) << message;
    EXPECT_TRUE(contains(message, "then finished when run once more")) << message;
    EXPECT_TRUE(fs::exists(dir / "tickets" / "ticket-2"));  // the second run built again
}

// Sixteen cases on two jobs share processes two by two. The process whose build takes ticket 1
// runs out of time on its first case: that case has timed out once, as a case alone would
// have, and runs once more alone, and passes; the case after it in that process runs alone and
// passes without a word; no case is TIMEOUT.
TEST(HarnessTimeouts, ASharedProcessThatRunsOutOfTimeLeavesItsCasesToRunAlone) {
    const fs::path dir = test::scratch_dir();
    std::string cases;
    for (const char* id : {"contract/standard", "contract/three-floors", "sizes/1x1", "sizes/odd",
                           "sizes/odd-even", "sizes/even-odd", "sizes/thin", "inputs/hdr",
                           "inputs/alpha-ramp", "inputs/subnormal", "inputs/empty", "inputs/opaque",
                           "floors/one-of-two", "lights/none", "lights/one", "lights/sun"})
        cases += std::string(" --case ") + id;
    const test::CommandResult run = validate(dir, "slow_first_build", cases, 5);
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, 0);
    const json report = report_of(dir);
    ASSERT_EQ(report["cases"].size(), 16u) << report.dump();
    size_t noted = 0;
    for (const json& c : report["cases"]) {
        EXPECT_EQ(c["verdict"], "PASS") << c.dump(2);
        const std::string message = c["message"];
        if (message.empty()) continue;
        ++noted;
        EXPECT_TRUE(contains(message,
                             "timed out once (its process, shared with 1 other case, "
                             "ran out of time while running it: no result after 5 s "
                             "of CPU time"))
            << message;
        EXPECT_TRUE(contains(message, "then finished when run once more in a fresh process"))
            << message;
        EXPECT_TRUE(contains(run.out, c["id"].get<std::string>() + ": its process, shared with"))
            << run.out;
    }
    EXPECT_EQ(noted, 1u) << "the case the process was running, and only it, says so";
    // Ticket 1 went to the shared process; every build after it was another's.
    EXPECT_TRUE(fs::exists(dir / "tickets" / "ticket-2"));
}

TEST(HarnessFlaky, ACorrectPluginRepeatedInRandomOrderIsNeverFlaky) {
    const fs::path dir = test::scratch_dir();
    const test::CommandResult run =
        validate(dir, "well_behaved", "--repeat 2 --shuffle-seed 12345");
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, 0);
    EXPECT_TRUE(contains(run.out, "(--shuffle-seed 12345)")) << run.out;
    const json report = report_of(dir);
    ASSERT_FALSE(report["cases"].empty());
    // The reference cases only render (no references are blessed for the battery): SKIP.
    for (const json& c : report["cases"])
        EXPECT_EQ(c["verdict"],
                  c["id"].get<std::string>().rfind("reference/", 0) == 0 ? "SKIP" : "PASS")
            << c["id"];
    // Both runs of every case ran, each in its own folder.
    const std::string first = report["cases"][0]["id"];
    std::string folder = first;
    for (char& ch : folder)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-') ch = '_';
    EXPECT_TRUE(fs::exists(dir / "report" / "cases" / folder / "result.json"));
    EXPECT_TRUE(fs::exists(dir / "report" / "cases" / (folder + "-run2") / "result.json"));
}

}  // namespace
}  // namespace acetate
