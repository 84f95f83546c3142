// Waivers (docs/registry.md, "Waivers"): `acetate-harness waive PLUGIN CHECK --reason --until
// --by` accepts one failing check for one plugin source. The planted fault is the battery's
// negative_colour, which fails `non-negative` and nothing else. Waived, the check reads WAIVED
// (never PASS), the run passes and its evidence says so; expired, the run fails with a case that
// names the waiver. Bad waivers are refused in one line.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_files.hpp"
#include "test_signer.hpp"

namespace acetate {
namespace {

using ::acetate::test::contains;

namespace fs = std::filesystem;
using nlohmann::json;
using test::shell_quote;

class HarnessWaivers : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::scratch_dir();
        plugin_ = dir_ / "negative_colour.so";
        fs::copy_file(fs::path(ACETATE_HARNESS_PLUGIN_DIR) / "negative_colour.so", plugin_);
    }

    // `acetate-harness --registry R ARGS`, signing as the test maintainer.
    test::CommandResult harness(const std::string& args) const {
        return test::run_command(
            "cd " + shell_quote(dir_.string()) + " && " + test::harness_environment() + " " +
                test::signer_environment() + " " + shell_quote(ACETATE_HARNESS_PATH) +
                " --registry " + shell_quote(registry().string()) + " " + args,
            dir_);
    }
    test::CommandResult validate() const {
        return harness("validate " + shell_quote(plugin_.string()) +
                       " --stage alpha-tested --strictness 1 --jobs 2 --timeout 60 "
                       "--no-signoffs --report " +
                       shell_quote((dir_ / "report").string()));
    }
    test::CommandResult waive(const std::string& args) const {
        return harness("waive " + shell_quote(plugin_.string()) + " " + args);
    }
    fs::path registry() const { return dir_ / "registry.json"; }
    json report() const { return json::parse(test::read_file(dir_ / "report" / "report.json")); }

    fs::path dir_, plugin_;
};

// One error line, naming the plugin or the argument, and nothing recorded.
void expect_one_line(const test::CommandResult& run, const std::string& part) {
    SCOPED_TRACE(run.describe());
    EXPECT_EQ(run.code, 1);
    const auto lines = test::nonempty_lines(run.err);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_TRUE(contains(lines[0], part)) << lines[0];
}

TEST_F(HarnessWaivers, AWaivedCheckReadsWaivedAndAnExpiredWaiverFails) {
    // Not before a review: a waiver is granted on reviewed code.
    expect_one_line(waive("non-negative --reason 'dark fringe by design' --until 2099-12-31 "
                          "--by pat@example.org"),
                    "waiver refused: it is UNVALIDATED for this source");
    const test::CommandResult reviewed =
        harness("review " + shell_quote(plugin_.string()) +
                " --reviewer rita@example.org --notes 'read the shader'");
    ASSERT_EQ(reviewed.code, 0) << reviewed.describe();

    // Without a waiver the run fails on non-negative alone.
    {
        const test::CommandResult run = validate();
        SCOPED_TRACE(run.describe());
        EXPECT_EQ(run.code, 1);
        EXPECT_TRUE(contains(run.out, "non-negative")) << run.out;
    }

    // Bad waivers: refused in one line, nothing recorded.
    expect_one_line(waive("process --reason r --until 2099-12-31 --by pat@example.org"),
                    "\"process\" is not a check a waiver may name");
    expect_one_line(waive("non-negative --reason r --until 2020-01-01 --by pat@example.org"),
                    "waiver refused: --until 2020-01-01 is already past");
    {  // A flag's value the one reader of numbers and days refuses: a usage error, exit 2.
        const test::CommandResult run =
            waive("non-negative --reason r --until 31/12/2099 --by pat@example.org");
        EXPECT_EQ(run.code, 2) << run.describe();
        EXPECT_EQ(test::nonempty_lines(run.err),
                  std::vector<std::string>{
                      "acetate-harness: --until: must be a day YYYY-MM-DD, got \"31/12/2099\""})
            << run.describe();
    }
    expect_one_line(waive("non-negative --reason ' ' --until 2099-12-31 --by pat@example.org"),
                    "the reason is empty");
    EXPECT_FALSE(contains(test::read_file(registry()), "waivers"));

    const test::CommandResult waived = waive(
        "non-negative --reason 'a dark fringe by design' --until 2099-12-31 --by pat@example.org");
    ASSERT_EQ(waived.code, 0) << waived.describe();
    EXPECT_TRUE(contains(waived.out, "it reads WAIVED, never PASS")) << waived.out;
    {
        const test::CommandResult run = validate();
        SCOPED_TRACE(run.describe());
        EXPECT_EQ(run.code, 0);
        const json r = report();
        size_t waived_checks = 0, passed_non_negative = 0;
        for (const json& c : r["cases"]) {
            EXPECT_NE(c["verdict"], "FAIL") << c.dump(2);
            for (const json& check : c["checks"]) {
                if (check["check"] != "non-negative") {
                    EXPECT_NE(check["verdict"], "WAIVED") << check.dump(2);
                    continue;
                }
                if (check["verdict"] == "WAIVED") {
                    ++waived_checks;
                    EXPECT_TRUE(contains(check["message"].get<std::string>(),
                                         "waived until 2099-12-31 by pat@example.org (a dark "
                                         "fringe by design)"))
                        << check.dump(2);
                }
                if (check["verdict"] == "PASS") ++passed_non_negative;
            }
        }
        EXPECT_GT(waived_checks, 0u);
        const json status = json::parse(harness("status --json").out);
        ASSERT_EQ(status["plugins"].size(), 1u);
        const json& e = status["plugins"][0];
        EXPECT_EQ(e["stage"], "ALPHA_TESTED");
        EXPECT_TRUE(contains(e["alpha_tested"]["summary"].get<std::string>(), "under a waiver"))
            << e.dump(2);
        EXPECT_GT(e["alpha_tested"]["counts"]["WAIVED"].get<int>(), 0) << e.dump(2);
        EXPECT_EQ(e["waivers"][0]["by"], "pat@example.org");
        EXPECT_TRUE(contains(harness("status").out,
                             "waiver: non-negative until 2099-12-31 by pat@example.org"));
    }

    // The waiver's last day passes (the registry written as it would read then): the run fails,
    // naming the expired waiver.
    {
        std::string text = test::read_file(registry());
        text.replace(text.find("2099-12-31"), 10, "2021-06-30");
        test::write_text(registry(), text);
        const test::CommandResult run = validate();
        SCOPED_TRACE(run.describe());
        EXPECT_EQ(run.code, 1);
        bool named = false;
        const json r = report();
        for (const json& c : r["cases"])
            if (c["id"] == "waivers/expired") {
                EXPECT_EQ(c["verdict"], "FAIL");
                named = contains(c["message"].get<std::string>(),
                                 "expired: non-negative (until 2021-06-30)");
            }
        EXPECT_TRUE(named) << r["cases"].dump(2);
    }
}

}  // namespace
}  // namespace acetate
