// `acetate-harness fuzz` (docs/harness.md, "Fuzzing"): it draws cases from the whole input
// model until its time is up, and on a failure shrinks the case to the smallest one that still
// fails the same way and prints a `--reproduce` line that fails again.
//
// The planted failure is exits_in_case from the project's battery: it exits with status 7 when
// build() runs for floor 1, which a drawn case reaches through two or more floors, or through
// an earlier load of another scene with more floors. The smallest failing case therefore has a
// 1x1 canvas, default parameters, time 0 and one frame, and reaches floor 1 in one of those two
// ways. A correct plugin (well_behaved) must run the whole time without a failure.

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

fs::path harness_plugin(const std::string& stem) {
    return fs::path(ACETATE_HARNESS_PLUGIN_DIR) / (stem + ".so");
}

// `acetate-harness fuzz PLUGIN EXTRA --report DIR/report --jobs 2 --timeout 30`, in `dir`.
test::CommandResult fuzz(const fs::path& dir, const fs::path& plugin, const std::string& extra) {
    const std::string command =
        "cd " + shell_quote(dir.string()) + " && " + test::harness_environment() + " " +
        shell_quote(ACETATE_HARNESS_PATH) + " fuzz " + shell_quote(plugin.string()) + " " + extra +
        " --report " + shell_quote((dir / "report").string()) + " --jobs 2 --timeout 30";
    return test::run_command(command, dir);
}

// The value after "reproduce: " in the output, as a command line for the shell.
std::string reproduce_line(const std::string& out) {
    for (const std::string& line : test::nonempty_lines(out))
        if (line.rfind("reproduce: ", 0) == 0) return line.substr(11);
    return {};
}

TEST(HarnessFuzz, FindsAndShrinksAPlantedFailureWithinItsTime) {
    const fs::path dir = test::scratch_dir();
    const test::CommandResult run = fuzz(dir, harness_plugin("exits_in_case"), "--duration 2m");
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, 1);
    EXPECT_TRUE(contains(run.out, "failed (CRASH) after")) << run.out;
    const fs::path shrunk_file = dir / "report" / "shrunk-case.json";
    ASSERT_TRUE(fs::is_regular_file(shrunk_file));
    const json shrunk = json::parse(test::read_file(shrunk_file));
    EXPECT_EQ(shrunk["width"], 1);
    EXPECT_EQ(shrunk["height"], 1);
    EXPECT_EQ(shrunk["frames"], 1);
    EXPECT_EQ(shrunk["time"], 0.0);
    EXPECT_TRUE(shrunk["params"].empty()) << shrunk["params"];
    // Still reaching floor 1 by exactly one of its two ways, and no further than it needs.
    const bool two_floors = shrunk["floors"] == 2 && shrunk["prior_loads"] == 0;
    const bool one_earlier_load = shrunk["floors"] == 1 && shrunk["prior_loads"] == 1;
    EXPECT_TRUE(two_floors || one_earlier_load) << shrunk.dump();

    // The reproduce line names the shrunk case and fails again, with the same cause.
    const std::string reproduce = reproduce_line(run.out);
    ASSERT_TRUE(contains(reproduce, "acetate-harness fuzz ")) << run.out;
    ASSERT_TRUE(contains(reproduce, "--reproduce " + shrunk_file.string())) << reproduce;
    const std::string again_command = "cd " + shell_quote(dir.string()) + " && " +
                                      test::harness_environment() + " " +
                                      shell_quote(ACETATE_HARNESS_PATH) +
                                      reproduce.substr(std::string("acetate-harness").size()) +
                                      " --report " + shell_quote((dir / "again").string());
    const test::CommandResult again = test::run_command(again_command, dir);
    EXPECT_EQ(again.code, 1) << again.describe();
    EXPECT_TRUE(contains(again.out, "CRASH: the plugin exited with status 7 during the case"))
        << again.describe();

    // A case file cannot make the command load a library of its choosing: one naming a
    // companion is refused in one line, before any case runs.
    json named = shrunk;
    named["companions"] = json::array({{{"id", "org.example.other"},
                                        {"file", harness_plugin("well_behaved").string()},
                                        {"scope", "floor"},
                                        {"binary_sha256", std::string(64, 'a')}}});
    const fs::path named_file = test::write_text(dir / "named.json", named.dump(2));
    const test::CommandResult refused = fuzz(dir, harness_plugin("exits_in_case"),
                                             "--reproduce " + shell_quote(named_file.string()));
    EXPECT_EQ(refused.code, 1) << refused.describe();
    const auto lines = test::nonempty_lines(refused.err);
    ASSERT_EQ(lines.size(), 1u) << refused.describe();
    EXPECT_TRUE(
        contains(lines[0], named_file.string() + ": companions: a fuzz case runs the plugin alone"))
        << lines[0];
    EXPECT_FALSE(contains(refused.out, "CRASH")) << "no case ran";
}

TEST(HarnessFuzz, ACorrectPluginRunsItsTimeWithoutAFailure) {
    const fs::path dir = test::scratch_dir();
    const test::CommandResult run = fuzz(dir, harness_plugin("well_behaved"), "--duration 20s");
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, 0);
    EXPECT_TRUE(contains(run.out, "no failure in ")) << run.out;
    EXPECT_FALSE(fs::exists(dir / "report" / "shrunk-case.json"));
}

TEST(HarnessFuzz, ABadDurationIsRefusedWithOneLine) {
    const fs::path dir = test::scratch_dir();
    const test::CommandResult run = fuzz(dir, harness_plugin("well_behaved"), "--duration 10x");
    EXPECT_EQ(run.code, 1) << run.describe();
    EXPECT_TRUE(contains(run.err, "--duration: expected seconds or a number with s, m or h"))
        << run.describe();
}

}  // namespace
}  // namespace acetate
