// Fan-out (docs/cluster.md): `validate --list-cases` prints the plan, four shards each run a
// quarter of it with `validate --case ID... --out DIR` (as four cluster tasks would), and
// `merge DIR` judges and records them. The merged run must equal one run of the same plugin,
// strictness and seed: the same verdict for every case and check, the same registry state.
// Shards from another seed, a missing case and a shard of a different binary are one line
// naming the file, and leave the registry as it was.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <array>
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
    // `validate --shard K/N --out DIR` for the plugin at the test's strictness and seed.
    test::CommandResult shard(const fs::path& registry, const std::string& k_of_n,
                              const fs::path& out) const {
        return harness(registry, "validate " + common() + " --shard " + k_of_n + " --out " +
                                     shell_quote(out.string()));
    }
    // Two shards at once, into one folder; the exit status is the first non-zero of the two.
    test::CommandResult harness_pair(const fs::path& registry,
                                     const std::array<std::string, 2>& shards,
                                     const fs::path& out) const {
        // `&` binds looser than `&&`: the folder and environment are set first, on their own.
        std::string command = "cd " + shell_quote(dir_.string()) + " || exit 1; export " +
                              test::harness_environment() + " " + test::signer_environment() + "; ";
        for (size_t i = 0; i < shards.size(); ++i)
            command += "{ " + shell_quote(ACETATE_HARNESS_PATH) + " --registry " +
                       shell_quote(registry.string()) + " validate " + common() + " --shard " +
                       shards[i] + " --out " + shell_quote(out.string()) + " > shard" +
                       std::to_string(i) + ".log 2>&1; echo $? > shard" + std::to_string(i) +
                       ".status; } & ";
        command +=
            "wait; cat shard0.log shard1.log; s0=$(cat shard0.status); s1=$(cat "
            "shard1.status); [ \"$s0\" = 0 ] || exit \"$s0\"; exit \"$s1\"";
        return test::run_command(command, dir_);
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
    // Shards 0, 1 and 3 of 4 share one folder, two at a time, as a job array throttled to 2
    // would run them: each describes the plugin into a folder of its own.
    const fs::path shared = dir_ / "shared";
    const test::CommandResult pair = harness_pair(sharded, {"0/4", "1/4"}, shared);
    ASSERT_EQ(pair.code, 0) << pair.describe();
    const test::CommandResult third = shard(sharded, "3/4", shared);
    ASSERT_EQ(third.code, 0) << third.describe();

    // Shard 2/4 never ran: the merge names every case it owes, on one line, and records nothing.
    const std::string registry_before = test::read_file(sharded);
    const test::CommandResult incomplete =
        harness(sharded, "merge " + shell_quote(shared.string()));
    EXPECT_EQ(incomplete.code, 1) << incomplete.describe();
    std::vector<std::string> owed;
    for (size_t i = 2; i < ids.size(); i += 4) owed.push_back(ids[i]);
    std::string owed_line = "shard 2/4: " + std::to_string(owed.size()) + " cases: ";
    for (size_t i = 0; i < owed.size(); ++i) owed_line += (i ? ", " : "") + owed[i];
    const std::vector<std::string> lines = test::nonempty_lines(incomplete.err);
    ASSERT_EQ(lines.size(), 3u) << incomplete.err;
    EXPECT_TRUE(contains(lines[0], "merge: " + std::to_string(owed.size()) + " of the plan's " +
                                       std::to_string(ids.size()) + " cases have no result"))
        << lines[0];
    EXPECT_EQ(lines[1], "  " + owed_line);
    EXPECT_TRUE(contains(lines[2], "run those shards again")) << lines[2];
    EXPECT_EQ(test::read_file(sharded), registry_before);
    const test::CommandResult progress =
        harness(sharded, "status --plan " + shell_quote(shared.string()));
    ASSERT_EQ(progress.code, 0) << progress.describe();
    EXPECT_TRUE(contains(progress.out, std::to_string(ids.size() - owed.size()) + " of " +
                                           std::to_string(ids.size()) + " results"))
        << progress.out;
    for (const std::string& line : test::nonempty_lines(progress.out))
        if (contains(line, "shard 2/4")) {
            EXPECT_TRUE(contains(line, " 0 of ") && !contains(line, "complete")) << line;
        }

    // The missing shard, re-run on its own, completes the run.
    const test::CommandResult rerun = shard(sharded, "2/4", shared);
    ASSERT_EQ(rerun.code, 0) << rerun.describe();
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
    // Two cases of the plan only: every other one is named as missing (no shard ran them:
    // these are --case results), and nothing is recorded.
    {
        const test::CommandResult merged =
            harness(registry, "merge " + shell_quote(shared.string()));
        EXPECT_EQ(merged.code, 1) << merged.describe();
        const auto lines = test::nonempty_lines(merged.err);
        ASSERT_EQ(lines.size(), 3u) << merged.err;
        EXPECT_TRUE(contains(lines[0], " cases have no result in " + shared.string())) << lines[0];
        std::vector<std::string> planned = test::nonempty_lines(
            harness(registry, "validate " + common() + " --stage alpha-tested --list-cases").out);
        std::erase_if(planned, [](const std::string& id) {
            return id == "contract/standard" || id == "sizes/1x1";
        });
        std::string expected = "  " + std::to_string(planned.size()) + " cases: ";
        for (size_t i = 0; i < planned.size(); ++i) expected += (i ? ", " : "") + planned[i];
        EXPECT_EQ(lines[1], expected);
        EXPECT_TRUE(contains(lines[2], "run those cases again")) << lines[2];
        EXPECT_EQ(test::read_file(registry), registry_before);
    }

    // A plan.json of another run (another seed) beside the results: it could only make the
    // merge ask for more, but it is not this run's, and the merge says so.
    const json results = json::parse(test::read_file(shared / "results" / "sizes_1x1.json"));
    test::write_text(shared / "plan.json",
                     json{{"format", "acetate-shard-plan/1"},
                          {"plugin",
                           {{"id", results["plugin"]["id"]},
                            {"version", results["plugin"]["version"]},
                            {"binary_sha256", results["plugin"]["binary_sha256"]}}},
                          {"strictness", results["strictness"]},
                          {"seed", 8},
                          {"shards", 1},
                          {"cases", json::array()}}
                         .dump());
    expect_refusal((shared / "plan.json").string() + ": the plan of another run");
    fs::remove(shared / "plan.json");

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

// A shard writes each result as its case finishes: killed mid-run (the whole process group,
// as a scheduler's cancel does), it keeps what finished, each file whole and signed; the merge
// names what it lost, and the same shard run again completes the folder.
TEST_F(HarnessShards, AKilledShardKeepsTheCasesThatFinished) {
    const fs::path registry = dir_ / "registry.json";
    review(registry);
    if (HasFatalFailure()) return;
    const std::vector<std::string> ids = test::nonempty_lines(
        harness(registry, "validate " + common() + " --stage alpha-tested --list-cases").out);
    const fs::path shared = dir_ / "shared";
    const test::CommandResult killed = test::run_command(
        "cd " + shell_quote(dir_.string()) + " || exit 1; export " + test::harness_environment() +
            " " + test::signer_environment() + "; setsid " + shell_quote(ACETATE_HARNESS_PATH) +
            " --registry " + shell_quote(registry.string()) + " validate " +
            shell_quote(plugin().string()) +
            " --strictness 1 --seed 7 --timeout 60 --jobs 1 --stage alpha-tested --shard 0/1 "
            "--out shared > killed.log 2>&1 & pid=$!; n=0; for i in $(seq 1200); do "
            "n=$(ls shared/results/ 2>/dev/null | grep -c '\\.json$'); [ \"$n\" -ge 3 ] && "
            "break; sleep 0.05; done; kill -KILL -$pid; wait $pid; echo \"status $?\"",
        dir_);
    EXPECT_TRUE(contains(killed.out, "status 137")) << killed.describe();

    std::vector<fs::path> kept;
    for (const auto& item : fs::directory_iterator(shared / "results"))
        if (item.path().extension() == ".json") kept.push_back(item.path());
    ASSERT_GE(kept.size(), 3u);
    ASSERT_LT(kept.size(), ids.size()) << "killed before the end";
    for (const fs::path& file : kept) {
        EXPECT_NO_THROW(json::parse(test::read_file(file))) << file;
        EXPECT_TRUE(fs::is_regular_file(file.string() + ".sig")) << file;
    }
    const test::CommandResult progress =
        harness(registry, "status --plan " + shell_quote(shared.string()));
    EXPECT_TRUE(contains(progress.out, std::to_string(kept.size()) + " of " +
                                           std::to_string(ids.size()) + " results; not complete"))
        << progress.describe();
    const test::CommandResult lost = harness(registry, "merge " + shell_quote(shared.string()));
    EXPECT_EQ(lost.code, 1) << lost.describe();
    EXPECT_TRUE(
        contains(lost.err, "  shard 0/1: " + std::to_string(ids.size() - kept.size()) + " cases: "))
        << lost.err;

    const test::CommandResult again =
        harness(registry, "validate " + common() + " --stage alpha-tested --shard 0/1 --out " +
                              shell_quote(shared.string()));
    ASSERT_EQ(again.code, 0) << again.describe();
    const test::CommandResult merged = harness(registry, "merge " + shell_quote(shared.string()));
    EXPECT_EQ(merged.code, 0) << merged.describe();
    EXPECT_EQ(json::parse(test::read_file(registry))["plugins"][0]["stage"], "ALPHA_TESTED");
}

// A shard of a plugin that fails a check exits 0 once its results are written: a scheduler
// reads a non-zero status as its own failure (and retries, or holds the merge back). The merge
// judges the results, fails the plugin, and writes its report and JUnit. A shard that cannot
// run (the plugin cannot be described) exits non-zero.
TEST_F(HarnessShards, AFailingPluginsShardsExitZeroAndItsMergeFailsIt) {
    const fs::path registry = dir_ / "registry.json";
    fs::copy_file(fs::path(ACETATE_HARNESS_PLUGIN_DIR) / "colour_at_zero.so",
                  dir_ / "plugins" / "colour_at_zero.so");
    const std::string failing = shell_quote((dir_ / "plugins" / "colour_at_zero.so").string()) +
                                " --strictness 1 --seed 7 --jobs 2 --timeout 60 --stage "
                                "alpha-tested";
    const fs::path shared = dir_ / "shared";
    for (const char* k : {"0/2", "1/2"}) {
        const test::CommandResult run =
            harness(registry, "validate " + failing + " --shard " + k + " --out " +
                                  shell_quote(shared.string()));
        EXPECT_EQ(run.code, 0) << run.describe();
    }
    const test::CommandResult progress =
        harness(registry, "status --plan " + shell_quote(shared.string()));
    EXPECT_TRUE(contains(progress.out, "failing; ready to merge")) << progress.describe();
    const fs::path junit = dir_ / "junit.xml";
    const test::CommandResult merged =
        harness(registry, "merge " + shell_quote(shared.string()) + " --junit " +
                              shell_quote(junit.string()));
    EXPECT_EQ(merged.code, 1) << merged.describe();
    EXPECT_TRUE(contains(merged.out, "FAILED")) << merged.out;
    EXPECT_TRUE(contains(test::read_file(junit), "<failure")) << "the merge's JUnit";
    EXPECT_TRUE(fs::is_regular_file(shared / "report.json"));

    test::write_text(dir_ / "plugins" / "not_a_plugin.so", "text, not a library");
    const test::CommandResult broken = harness(
        registry, "validate " + shell_quote((dir_ / "plugins" / "not_a_plugin.so").string()) +
                      " --strictness 1 --shard 0/2 --out " + shell_quote((dir_ / "b").string()));
    EXPECT_EQ(broken.code, 1) << broken.describe();
    EXPECT_TRUE(contains(broken.err, "cannot describe the plugin")) << broken.err;
}

}  // namespace
}  // namespace acetate
