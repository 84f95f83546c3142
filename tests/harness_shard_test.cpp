// Fan-out (docs/cluster.md): `validate --list-cases` prints the plan, four shards each run a
// quarter of it with `validate --case ID... --out DIR` (as four cluster tasks would), and
// `merge DIR` judges and records them. The merged run must equal one run of the same plugin,
// strictness and seed: the same verdict for every case and check, the same registry state.
// Shards from another seed, a missing case and a shard of a different binary are one line
// naming the file, and leave the registry as it was.

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_files.hpp"
#include "test_signer.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::shell_quote;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

class HarnessShards : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::scratch_dir();
        fs::create_directories(dir_ / "plugins");
        fs::copy_file(fs::path(ACETATE_HARNESS_PLUGIN_DIR) / "well_behaved.so", plugin());
    }
    fs::path plugin() const { return dir_ / "plugins" / "well_behaved.so"; }

    test::CommandResult harness(const fs::path& registry, const std::string& args) const {
        return test::run_command(
            "cd " + shell_quote(dir_.string()) + " && " + test::harness_environment() + " " +
                test::signer_environment() + " " + shell_quote(ACETATE_HARNESS_PATH) +
                " --registry " + shell_quote(registry.string()) + " " + args,
            dir_);
    }
    void review(const fs::path& registry) const {
        const test::CommandResult run =
            harness(registry, "review " + shell_quote(plugin().string()) +
                                  " --reviewer rita@example.org --notes 'read it'");
        ASSERT_EQ(run.code, 0) << run.describe();
    }
    std::string common() const {
        return shell_quote(plugin().string()) + " --strictness 1 --seed 7 --jobs 2 --timeout 60";
    }

    // Each case's verdict and each of its checks' verdicts, by case id.
    static std::map<std::string, std::string> verdicts(const fs::path& report) {
        std::map<std::string, std::string> out;
        const json r = json::parse(test::read_file(report));
        for (const json& c : r["cases"]) {
            std::string v = c["verdict"].get<std::string>();
            for (const json& check : c["checks"])
                v += " " + check["check"].get<std::string>() + "=" +
                     check["verdict"].get<std::string>();
            out[c["id"].get<std::string>()] = v;
        }
        return out;
    }
    // The registry entry with what differs between two honest runs taken out: the review (each
    // registry had its own, signed a moment apart), the evidence's times and report paths.
    static json entry(const fs::path& registry) {
        json e = json::parse(test::read_file(registry))["plugins"][0];
        e.erase("review");
        for (const char* stage : {"alpha_tested", "integrated"}) {
            e[stage].erase("at");
            e[stage].erase("report");
        }
        return e;
    }

    fs::path dir_;
};

TEST_F(HarnessShards, FourShardsMergedEqualOneRun) {
    const fs::path single = dir_ / "single.json", sharded = dir_ / "sharded.json";
    review(single);
    review(sharded);
    if (HasFatalFailure()) return;

    const test::CommandResult one = harness(
        single, "validate " + common() + " --report " + shell_quote((dir_ / "one").string()));
    ASSERT_EQ(one.code, 0) << one.describe();

    const test::CommandResult listed = harness(sharded, "validate " + common() + " --list-cases");
    ASSERT_EQ(listed.code, 0) << listed.describe();
    const std::vector<std::string> ids = test::nonempty_lines(listed.out);
    ASSERT_GT(ids.size(), 8u);
    EXPECT_EQ(ids,
              test::nonempty_lines(harness(sharded, "validate " + common() + " --list-cases").out))
        << "the plan is stable";
    const fs::path shared = dir_ / "shared";
    for (size_t shard = 0; shard < 4; ++shard) {
        std::string cases;
        for (size_t i = shard; i < ids.size(); i += 4) cases += " --case " + shell_quote(ids[i]);
        const test::CommandResult run = harness(
            sharded, "validate " + common() + cases + " --out " + shell_quote(shared.string()));
        ASSERT_EQ(run.code, 0) << run.describe();
    }
    const std::string before_merge = test::read_file(sharded);
    EXPECT_EQ(json::parse(before_merge)["plugins"][0]["stage"], "REVIEWED")
        << "a shard records nothing";

    const test::CommandResult merged = harness(sharded, "merge " + shell_quote(shared.string()));
    ASSERT_EQ(merged.code, 0) << merged.describe();
    EXPECT_TRUE(contains(merged.out, "REVIEWED -> INTEGRATED")) << merged.out;

    EXPECT_EQ(verdicts(shared / "report.json"), verdicts(dir_ / "one" / "report.json"));
    EXPECT_EQ(verdicts(shared / "report.json").size(), ids.size());
    EXPECT_EQ(entry(sharded), entry(single));
    EXPECT_EQ(entry(sharded)["stage"], "INTEGRATED");
}

TEST_F(HarnessShards, ResultsThatDoNotBelongToOneRunAreOneLineNamingTheFile) {
    const fs::path registry = dir_ / "registry.json";
    review(registry);
    if (HasFatalFailure()) return;
    const fs::path shared = dir_ / "shared";
    const test::CommandResult run =
        harness(registry, "validate " + common() +
                              " --stage alpha-tested --case contract/standard"
                              " --case sizes/1x1 --out " +
                              shell_quote(shared.string()));
    ASSERT_EQ(run.code, 0) << run.describe();
    const std::string registry_before = test::read_file(registry);

    auto expect_refusal = [&](const std::string& part) {
        const test::CommandResult merged =
            harness(registry, "merge " + shell_quote(shared.string()));
        SCOPED_TRACE(merged.describe());
        EXPECT_EQ(merged.code, 1);
        const auto lines = test::nonempty_lines(merged.err);
        ASSERT_EQ(lines.size(), 1u);
        EXPECT_TRUE(contains(lines[0], part)) << lines[0];
        EXPECT_EQ(test::read_file(registry), registry_before);
    };
    // Two cases of the plan only: the rest are missing.
    expect_refusal("merge: no result for case ");

    // One result from another seed.
    const fs::path file = shared / "results" / "sizes_1x1.json";
    json j = json::parse(test::read_file(file));
    j["seed"] = 8;
    test::write_text(file, j.dump(2));
    expect_refusal(file.string() + ": from another seed (8 here, 7 in ");

    // One from another binary.
    j["seed"] = 7;
    j["plugin"]["binary_sha256"] = std::string(64, 'e');
    test::write_text(file, j.dump(2));
    expect_refusal(file.string() + ": from another binary (SHA-256 eeeeeeeeeeee here");

    // A folder with no results.
    fs::create_directories(dir_ / "empty");
    const test::CommandResult empty =
        harness(registry, "merge " + shell_quote((dir_ / "empty").string()));
    EXPECT_EQ(empty.code, 1) << empty.describe();
    EXPECT_TRUE(contains(empty.err, "no results/ folder")) << empty.err;
}

}  // namespace
}  // namespace acetate
