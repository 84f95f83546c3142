// Fan-out (docs/cluster.md): `validate --list-cases` prints the plan, four shards each run a
// quarter of it with `validate --case ID... --out DIR` (as four cluster tasks would), and
// `merge DIR` judges and records them. The merged run must equal one run of the same plugin,
// strictness and seed: the same verdict for every case and check, the same registry state.
// Shards from another seed, a missing case and a shard of a different binary are one line
// naming the file, and leave the registry as it was.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ssh_signature.hpp"
#include "test_files.hpp"
#include "test_signer.hpp"

namespace acetate {
namespace {

using ::acetate::test::contains;

namespace fs = std::filesystem;
using nlohmann::json;
using test::shell_quote;

// Writes `j` to a result file and signs it again as the test's runner: what the merge checks
// past the signature is judged on files a trusted runner wrote.
void write_signed(const fs::path& file, const json& j) {
    test::write_text(file, j.dump(2));
    auto signature =
        ssh_sign(test::test_signer().runner_key, test::read_file(file), kCaseResultNamespace);
    ASSERT_TRUE(signature) << signature.error().message;
    test::write_text(fs::path(file.string() + ".sig"), signature.value());
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

    // A verdict edited in the shared folder: the runner's signature no longer holds.
    const fs::path file = shared / "results" / "sizes_1x1.json";
    const std::string signed_bytes = test::read_file(file);
    json j = json::parse(signed_bytes);
    j["result"]["verdict"] = "PASS";
    j["result"]["message"] = "edited";
    test::write_text(file, j.dump(2));
    expect_refusal(file.string() +
                   ": the runner's signature (sizes_1x1.json.sig) does not match what it claims "
                   "to sign (runner@example.org's key, other content)");
    // Signed by a key the allowed signers do not list.
    test::write_text(file, signed_bytes);
    auto stranger = ssh_sign(test::test_signer().unlisted_key, signed_bytes, kCaseResultNamespace);
    ASSERT_TRUE(stranger) << stranger.error().message;
    test::write_text(fs::path(file.string() + ".sig"), stranger.value());
    expect_refusal(file.string() +
                   ": the runner's signature (sizes_1x1.json.sig) was made by a key "
                   "that allowed_signers does not list");
    // A maintainer's key, allowed sign-offs only, cannot sign a result.
    auto maintainer = ssh_sign(test::test_signer().key, signed_bytes, kCaseResultNamespace);
    ASSERT_TRUE(maintainer) << maintainer.error().message;
    test::write_text(fs::path(file.string() + ".sig"), maintainer.value());
    expect_refusal(file.string() + ": the runner's signature (sizes_1x1.json.sig) ");
    // No signature at all.
    fs::remove(fs::path(file.string() + ".sig"));
    expect_refusal(file.string() + ": not signed: no sizes_1x1.json.sig");

    // One result from another seed (from here on, each file is signed by the runner).
    j = json::parse(signed_bytes);
    j["seed"] = 8;
    write_signed(file, j);
    expect_refusal(file.string() + ": from another seed (8 here, 7 in ");

    // A strictness no run takes (0 would read as "not recorded", which needs no waiver).
    j["seed"] = 7;
    j["strictness"] = 0;
    write_signed(file, j);
    expect_refusal(file.string() + ": strictness: 0 is not a strictness a run takes (1 to 10)");

    // Another harness.
    j["strictness"] = 1;
    j["harness_version"] = "acetate-harness 9.9.9";
    write_signed(file, j);
    expect_refusal(file.string() +
                   ": harness_version: \"acetate-harness 9.9.9\" is not this "
                   "harness");

    // One from another binary.
    j["harness_version"] = json::parse(
        test::read_file(shared / "results" / "contract_standard.json"))["harness_version"];
    j["plugin"]["binary_sha256"] = std::string(64, 'e');
    write_signed(file, j);
    expect_refusal(file.string() + ": from another binary (SHA-256 eeeeeeeeeeee here");

    // Every result claiming another binary: the merge describes the plugin file itself.
    for (const char* name : {"sizes_1x1.json", "contract_standard.json"}) {
        json k = json::parse(test::read_file(shared / "results" / name));
        k["plugin"]["binary_sha256"] = std::string(64, 'e');
        write_signed(shared / "results" / name, k);
    }
    expect_refusal("merge: " + plugin().string() + " is not the binary the shards ran (SHA-256 ");

    // A folder with no results.
    fs::create_directories(dir_ / "empty");
    const test::CommandResult empty =
        harness(registry, "merge " + shell_quote((dir_ / "empty").string()));
    EXPECT_EQ(empty.code, 1) << empty.describe();
    EXPECT_TRUE(contains(empty.err, "no results/ folder")) << empty.err;
}

// A refused merge writes nothing: here every planned case has a result, plus one for a case the
// plan does not have. Before the refusal, the stages had been judged; none may be recorded.
// Without the stray result the same folder merges (the control).
TEST_F(HarnessShards, ARefusedMergeLeavesTheRegistryAsItWas) {
    const fs::path registry = dir_ / "registry.json";
    review(registry);
    if (HasFatalFailure()) return;
    const test::CommandResult listed =
        harness(registry, "validate " + common() + " --stage alpha-tested --list-cases");
    ASSERT_EQ(listed.code, 0) << listed.describe();
    std::string cases;
    for (const std::string& id : test::nonempty_lines(listed.out))
        cases += " --case " + shell_quote(id);
    const fs::path shared = dir_ / "shared";
    const test::CommandResult run =
        harness(registry, "validate " + common() + " --stage alpha-tested" + cases + " --out " +
                              shell_quote(shared.string()));
    ASSERT_EQ(run.code, 0) << run.describe();
    const std::string registry_before = test::read_file(registry);

    json stray = json::parse(test::read_file(shared / "results" / "sizes_1x1.json"));
    stray["spec"]["id"] = "sizes/2x3x4";
    stray["result"]["id"] = "sizes/2x3x4";
    const fs::path stray_file = shared / "results" / "stray.json";
    write_signed(stray_file, stray);
    const test::CommandResult refused = harness(registry, "merge " + shell_quote(shared.string()));
    EXPECT_EQ(refused.code, 1) << refused.describe();
    const auto lines = test::nonempty_lines(refused.err);
    ASSERT_EQ(lines.size(), 1u) << refused.describe();
    EXPECT_TRUE(contains(lines[0], stray_file.string() + ": case sizes/2x3x4 is not in the plan"))
        << lines[0];
    EXPECT_EQ(test::read_file(registry), registry_before);

    fs::remove(stray_file);
    fs::remove(fs::path(stray_file.string() + ".sig"));
    const test::CommandResult merged = harness(registry, "merge " + shell_quote(shared.string()));
    EXPECT_EQ(merged.code, 0) << merged.describe();
    const json entry = json::parse(test::read_file(registry))["plugins"][0];
    EXPECT_EQ(entry["stage"], "ALPHA_TESTED");
    EXPECT_EQ(entry["alpha_tested"]["strictness"], 1);
    EXPECT_EQ(entry["alpha_tested"]["seed"], 7);
}

// A shard signs what it writes: without a runner's name and key it refuses before any case
// runs, in one line; a key that is a FIFO is refused the same way, not waited on.
TEST_F(HarnessShards, AShardWithoutARunnerKeyRunsNothing) {
    const fs::path registry = dir_ / "registry.json";
    const fs::path shared = dir_ / "shared";
    const std::string base =
        "validate " + common() + " --case sizes/1x1 --out " + shell_quote(shared.string());
    const test::CommandResult unsigned_run = test::run_command(
        "cd " + shell_quote(dir_.string()) + " && env -u ACETATE_RUNNER -u ACETATE_RUNNER_KEY " +
            test::harness_environment() + " " + shell_quote(ACETATE_HARNESS_PATH) + " --registry " +
            shell_quote(registry.string()) + " " + base,
        dir_);
    EXPECT_EQ(unsigned_run.code, 1) << unsigned_run.describe();
    auto lines = test::nonempty_lines(unsigned_run.err);
    ASSERT_EQ(lines.size(), 1u) << unsigned_run.describe();
    EXPECT_TRUE(contains(lines[0], "--out: each result is signed by the runner that produced it"))
        << lines[0];
    EXPECT_FALSE(fs::exists(shared / "results"));

    const fs::path fifo = dir_ / "runner-fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const test::CommandResult fifo_run =
        harness(registry, base + " --runner-key " + shell_quote(fifo.string()));
    EXPECT_EQ(fifo_run.code, 1) << fifo_run.describe();
    lines = test::nonempty_lines(fifo_run.err);
    ASSERT_EQ(lines.size(), 1u) << fifo_run.describe();
    EXPECT_TRUE(
        contains(lines[0], "--runner-key: " + fifo.string() + ": not a regular file (a FIFO)"))
        << lines[0];
    EXPECT_FALSE(fs::exists(shared / "results"));
}

}  // namespace
}  // namespace acetate
