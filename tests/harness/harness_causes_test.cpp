// What `acetate-harness validate` says when the plugin ends its child process (docs/harness.md,
// "How it runs" and "Verdicts"): the cause, never its symptom. A plugin that calls exit(0)
// while it is described stops the run with one line naming that exit, not a missing
// plugin.json; a plugin that exits during a case makes that case CRASH with its exit status and
// the last lines it printed; and the harness's own describe errors (the host refusing a
// descriptor) still come through as the host's message, not as the plugin exiting.
//
// Each plugin is validated once, at strictness 1 and only up to ALPHA_TESTED, in a private
// folder with a private registry.

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_files.hpp"

namespace acetate {
namespace {

using ::acetate::test::contains;

namespace fs = std::filesystem;
using nlohmann::json;
using test::shell_quote;

// Seconds a case may take: a case needs 1 to 5 s here, more when the machine is busy.
constexpr int kTimeoutSeconds = 30;

// The lines of everything a run printed (stdout, then stderr) that contain `part`.
std::vector<std::string> lines_with(const test::CommandResult& run, const std::string& part) {
    std::vector<std::string> found;
    for (const std::string& line : test::nonempty_lines(run.out + "\n" + run.err))
        if (contains(line, part)) found.push_back(line);
    return found;
}

json read_report(const fs::path& report_dir) {
    const fs::path file = report_dir / "report.json";
    try {
        return json::parse(test::read_file(file));
    } catch (const json::exception& e) {
        ADD_FAILURE() << file << ": " << e.what();
        return json::object();
    }
}

// The case's spec as the harness wrote it for the child (validate.cpp's slug of the id).
json case_spec(const fs::path& report_dir, const std::string& id) {
    std::string slug = id;
    for (char& c : slug)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
    const fs::path file = report_dir / "cases" / slug / "case.json";
    try {
        return json::parse(test::read_file(file));
    } catch (const json::exception& e) {
        ADD_FAILURE() << file << ": " << e.what();
        return json::object();
    }
}

class HarnessCauses : public ::testing::Test {
  protected:
    void SetUp() override { dir_ = test::scratch_dir(); }

    // `acetate-harness --registry R validate PLUGIN --no-signoffs --report D --strictness 1
    // --stage alpha-tested --jobs 2`, in the test's folder.
    test::CommandResult validate(const fs::path& plugin) {
        EXPECT_TRUE(fs::is_regular_file(plugin)) << plugin;
        const std::string command =
            "cd " + shell_quote(dir_.string()) + " && " + test::harness_environment() + " " +
            shell_quote(ACETATE_HARNESS_PATH) + " --registry " +
            shell_quote((dir_ / "registry.json").string()) + " validate " +
            shell_quote(plugin.string()) + " --no-signoffs --report " +
            shell_quote(report_dir().string()) + " --strictness 1 --stage alpha-tested --jobs 2" +
            " --timeout " + std::to_string(kTimeoutSeconds);
        return test::run_command(command, dir_);
    }
    fs::path report_dir() const { return dir_ / "report"; }

    fs::path dir_;
};

fs::path harness_plugin(const std::string& stem) {
    return fs::path(ACETATE_HARNESS_PLUGIN_DIR) / (stem + ".so");
}

// The loader's test plugins are built beside the harness's battery folder.
fs::path test_plugin(const std::string& stem) {
    return fs::path(ACETATE_HARNESS_PLUGIN_DIR).parent_path() / (stem + ".so");
}

TEST_F(HarnessCauses, ExitWhileDescribingIsNamedNotAMissingPluginJson) {
    const test::CommandResult run = validate(harness_plugin("exits_while_describing"));
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, 1);
    const std::vector<std::string> said =
        lines_with(run,
                   "cannot describe the plugin: the plugin called exit(0) while describing "
                   "itself");
    ASSERT_EQ(said.size(), 1u);
    EXPECT_TRUE(contains(said[0], "exits_while_describing.so: ")) << said[0];
    // The cause, not its symptom nor the harness's own error path.
    EXPECT_FALSE(contains(run.out + run.err, "plugin.json"));
    EXPECT_FALSE(contains(run.out + run.err, "describe: error"));
    EXPECT_TRUE(read_report(report_dir())["cases"].empty());
}

// Whether a case builds the plugin for floor 1: two or more floors, with the plugin on every
// floor or on floor 1 only (`plugin_floor`, -1 or absent: every floor).
bool builds_floor_one(const json& spec) {
    const int64_t only_on = spec.value("plugin_floor", int64_t(-1));
    return spec.value("floors", 0u) >= 2 && (only_on < 0 || only_on == 1);
}

// A CRASH of exits_in_case: its exit status, then what it printed, on one line; the progress
// line says the same.
void expect_exit_7(const test::CommandResult& run, const std::string& id, const json& c) {
    const std::string message = c["message"].get<std::string>();
    EXPECT_TRUE(contains(message, "the plugin exited with status 7 during the case")) << message;
    EXPECT_TRUE(contains(message, "; last log lines: ")) << message;
    EXPECT_TRUE(contains(message, "exits_in_case: floor 1 is not supported, giving up")) << message;
    EXPECT_FALSE(contains(message, "\n")) << message;
    const std::vector<std::string> progress = lines_with(run, "] " + id + " ");
    ASSERT_EQ(progress.size(), 1u);
    EXPECT_TRUE(contains(progress[0], "CRASH")) << progress[0];
    EXPECT_TRUE(contains(progress[0], message)) << progress[0];
}

TEST_F(HarnessCauses, ExitInCaseIsACrashWithItsStatusAndLastLogLines) {
    const test::CommandResult run = validate(harness_plugin("exits_in_case"));
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, 1);
    const json report = read_report(report_dir());
    size_t crashed = 0, single = 0;
    for (const json& c : report["cases"]) {
        const std::string id = c["id"].get<std::string>();
        SCOPED_TRACE(id + ": " + c.dump(2));
        const json spec = case_spec(report_dir(), id);
        ASSERT_GT(spec.value("floors", 0u), 0u);
        if (c["verdict"] == "CRASH") {
            expect_exit_7(run, id, c);
            ++crashed;
        }
        // A case that loads other scenes first (`prior_loads`) may build floor 1 in those, so
        // only one-floor cases without them must pass.
        if (builds_floor_one(spec)) {
            EXPECT_EQ(c["verdict"], "CRASH");
        } else if (spec.value("floors", 0u) == 1 && spec.value("prior_loads", 0u) == 0) {
            // A reference case only renders: the battery has no blessed references.
            EXPECT_EQ(c["verdict"], spec["kind"] == "golden" ? "SKIP" : "PASS");
            ++single;
        } else {
            EXPECT_TRUE(c["verdict"] == "PASS" || c["verdict"] == "CRASH");
        }
    }
    EXPECT_GT(crashed, 0u);
    EXPECT_GT(single, 0u);
    const json* three = nullptr;
    for (const json& c : report["cases"])
        if (c["id"] == "contract/three-floors") three = &c;
    ASSERT_NE(three, nullptr);
    EXPECT_EQ((*three)["verdict"], "CRASH");
}

TEST_F(HarnessCauses, HostRefusalWhileDescribingKeepsTheHostsMessage) {
    const test::CommandResult run = validate(test_plugin("bad_default"));
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, 1);
    const std::vector<std::string> said = lines_with(run, "cannot describe the plugin: ");
    ASSERT_EQ(said.size(), 1u);
    EXPECT_TRUE(contains(said[0], "params[0] \"strength\": default 1.5 is outside [0, 1]"))
        << said[0];
    // The harness's own error: neither blamed on the plugin nor shown with the child's marker.
    EXPECT_FALSE(contains(said[0], "the plugin called exit")) << said[0];
    EXPECT_FALSE(contains(said[0], "the plugin exited")) << said[0];
    EXPECT_FALSE(contains(said[0], "describe: error")) << said[0];
    EXPECT_TRUE(read_report(report_dir())["cases"].empty());
}

}  // namespace
}  // namespace acetate
