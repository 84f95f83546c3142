// The installed programs' flags and outputs, end to end, as outside testers found them
// (the trust path: docs/conventions.md): every number, day and name a flag takes goes through the
// one reader (host/core/number_text.hpp), and no output replaces an input
// (host/core/output_paths.hpp). Each refusal is exactly one line on stderr, a non-zero exit, and
// the input's bytes unchanged. Every refusal here comes before any device is opened: no GPU is used
// (a regression that let one through would reach lavapipe, with the test environment's caches).

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "shard.hpp"
#include "test_files.hpp"
#include "test_signer.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using test::shell_quote;

// Runs `program args` in `dir` with the harness's test environment.
test::CommandResult run(const fs::path& dir, const char* program, const std::string& args) {
    return test::run_command("cd " + shell_quote(dir.string()) + " && " +
                                 test::harness_environment() + " " + shell_quote(program) + " " +
                                 args,
                             dir);
}

// Exactly one line on stderr, this one, and this exit status.
void expect_refusal(const test::CommandResult& r, int code, const std::string& line) {
    EXPECT_EQ(r.code, code) << r.describe();
    EXPECT_EQ(r.err, line + "\n") << r.describe();
}

// A scene of one tile, no effects: what the bench and the renderer read.
fs::path scene_dir() {
    const fs::path dir = test::scratch_dir();
    ImageRGBA tile(4, 4);
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x) tile.at(x, y)[3] = 1.0f;
    test::write_exr(dir / "tile.exr", tile);
    test::write_text(dir / "scene.json", R"({
  "format": "acetate-scene/1",
  "canvas": {"width": 4, "height": 4, "background": [0, 0, 0, 1]},
  "floors": [{"name": "ground", "tiles": [{"image": "tile.exr", "rect": [0, 0, 4, 4]}]}]
})");
    return dir;
}

// ---- acetate-bench ------------------------------------------------------------------------

TEST(BenchFlags, NumbersThatAreNotFiniteOrInRangeAreRefused) {
    const fs::path dir = scene_dir();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--time nan", "--time: must be a finite number, got \"nan\""},
        {"--time inf", "--time: must be a finite number, got \"inf\""},
        {"--time 1e39", "--time: must be at most 3.4028234663852886e+38, got 1e39"},
        {"--warn nan", "--warn: must be a finite number, got \"nan\""},
        {"--fail nan", "--fail: must be a finite number, got \"nan\""},
        {"--fail -1", "--fail: must be at least 0, got -1"},
        {"--frames -1", "--frames: must be at least 1, got -1"},
        {"--frames 3x", "--frames: must be an integer, got \"3x\""},
        {"--frames 10001", "--frames: must be at most 10000, got 10001"},
        {"--floor -1", "--floor: must be at least 0, got -1"},
        {"--floor 4294967296", "--floor: must be at most 4294967295, got 4294967296"},
    };
    for (const auto& [flags, message] : cases) {
        const auto r = run(dir, ACETATE_BENCH_PATH, "scene.json --json out.json " + flags);
        expect_refusal(r, 2, "acetate-bench: " + message);
        EXPECT_FALSE(fs::exists(dir / "out.json")) << flags;
    }
}

TEST(BenchOutputs, AnOutputThatIsAnInputIsRefusedAndTheInputKept) {
    const fs::path dir = scene_dir();
    fs::create_symlink("scene.json", dir / "link.json");
    fs::create_hard_link(dir / "tile.exr", dir / "hard.exr");
    const std::string scene = test::read_file(dir / "scene.json");
    const std::string tile = test::read_file(dir / "tile.exr");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--json scene.json", "--json scene.json: would overwrite an input of this run (scene: "},
        {"--json link.json", "--json link.json: would overwrite an input of this run (scene: "},
        {"--json hard.exr",
         "--json hard.exr: would overwrite an input of this run (scene.json: "
         "floors[0].tiles[0].image: "},
        {"--json tile.exr", "--json tile.exr: would overwrite an input of this run (scene.json: "},
    };
    for (const auto& [flags, start] : cases) {
        const auto r = run(dir, ACETATE_BENCH_PATH, "scene.json " + flags);
        EXPECT_EQ(r.code, 1) << r.describe();
        ASSERT_EQ(test::nonempty_lines(r.err).size(), 1u) << r.describe();
        EXPECT_EQ(r.err.rfind("acetate-bench: " + start, 0), 0u) << r.describe();
        EXPECT_EQ(test::read_file(dir / "scene.json"), scene) << flags;
        EXPECT_EQ(test::read_file(dir / "tile.exr"), tile) << flags;
    }
    // --html DIR writes DIR/index.html: a scene of that name is refused, and no folder made.
    fs::create_directories(dir / "report");
    fs::copy_file(dir / "scene.json", dir / "report" / "index.html");
    fs::copy_file(dir / "tile.exr", dir / "report" / "tile.exr");
    const auto r = run(dir, ACETATE_BENCH_PATH, "report/index.html --html report");
    expect_refusal(r, 1,
                   "acetate-bench: --html report/index.html: would overwrite an input of this "
                   "run (scene: report/index.html)");
    EXPECT_EQ(test::read_file(dir / "report" / "index.html"), scene);
}

// ---- acetate ------------------------------------------------------------------------------

TEST(AcetateFlags, NumbersThatAreNotFiniteOrDoNotFitAreRefused) {
    const fs::path dir = scene_dir();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--time nan", "--time: must be a finite number, got \"nan\""},
        {"--time 1e39", "--time: must be at most 3.4028234663852886e+38, got 1e39"},
        {"--floor -1", "--floor: must be at least 0, got -1"},
        {"--floor 0x", "--floor: must be an integer, got \"0x\""},
    };
    for (const auto& [flags, message] : cases) {
        const auto r = run(dir, ACETATE_CLI_PATH, "render scene.json -o out.png " + flags);
        expect_refusal(r, 2, "acetate: " + message);
        EXPECT_FALSE(fs::exists(dir / "out.png")) << flags;
    }
}

// ---- acetate-harness ----------------------------------------------------------------------

class HarnessInputs : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::scratch_dir();
        // Not a shared library: a run that got past the checks would fail at describe, after
        // writing its reports; the checks must come first.
        test::write_text(dir_ / "plugin.so", "not a plugin\n");
        test::write_text(dir_ / "registry.json", "{}\n");
    }
    test::CommandResult harness(const std::string& args) const {
        return run(dir_, ACETATE_HARNESS_PATH, "--registry registry.json " + args);
    }
    fs::path dir_;
};

TEST_F(HarnessInputs, NumbersThatWrapOrAreNotFiniteAreRefused) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"validate plugin.so --seed -1", "--seed: must be at least 0, got -1"},
        {"validate plugin.so --shuffle-seed 18446744073709551616",
         "--shuffle-seed: must be at most 18446744073709551615, got 18446744073709551616"},
        {"validate plugin.so --timeout nan", "--timeout: must be a finite number, got \"nan\""},
        {"validate plugin.so --jobs 0", "--jobs: must be at least 1, got 0"},
        {"validate plugin.so --strictness 3x", "--strictness: must be an integer, got \"3x\""},
        {"validate plugin.so --repeat -1", "--repeat: must be at least 1, got -1"},
        {"fuzz plugin.so --seed 18446744073709551616",
         "--seed: must be at most 18446744073709551615, got 18446744073709551616"},
        {"bless plugin.so --by me --timeout inf",
         "--timeout: must be a finite number, got \"inf\""},
    };
    for (const auto& [args, message] : cases) {
        const auto r = harness(args + " --report report");
        expect_refusal(r, 2, "acetate-harness: " + message);
        EXPECT_FALSE(fs::exists(dir_ / "report")) << args;
    }
    const auto r = harness("fuzz plugin.so --duration 1e308h");
    expect_refusal(r, 1,
                   "acetate-harness: --duration: must be at most 31536000 seconds (a year), got "
                   "1e308h");
}

TEST_F(HarnessInputs, NamesMustNotBeBlankAndDaysMustExist) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"bless plugin.so --by ''", "--by: must not be empty"},
        {"bless plugin.so --by '  '", "--by: must not be only spaces, got \"  \""},
        {"review plugin.so --reviewer '' --notes read", "--reviewer: must not be empty"},
        {"promote plugin.so --by ''", "--by: must not be empty"},
        {"waive plugin.so coverage --reason why --by '' --until 2099-01-01",
         "--by: must not be empty"},
        {"waive plugin.so coverage --reason why --by me --until 2026-02-30",
         "--until: must be a day that exists, got 2026-02-30 (February 2026 has 28 days)"},
    };
    const std::string registry = test::read_file(dir_ / "registry.json");
    for (const auto& [args, message] : cases) {
        expect_refusal(harness(args), 2, "acetate-harness: " + message);
        EXPECT_EQ(test::read_file(dir_ / "registry.json"), registry) << args;
    }
}

TEST_F(HarnessInputs, ValidateRefusesAReportOverItsInputs) {
    fs::create_symlink("plugin.so", dir_ / "link.so");
    const std::string plugin = test::read_file(dir_ / "plugin.so");
    const std::string registry = test::read_file(dir_ / "registry.json");
    const std::string abs = fs::absolute(dir_).string();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--json plugin.so",
         "--json plugin.so: would overwrite an input of this run (the plugin: " + abs +
             "/plugin.so)"},
        {"--junit link.so", "--junit link.so: would overwrite an input of this run (the plugin: " +
                                abs + "/plugin.so)"},
        {"--junit registry.json",
         "--junit registry.json: would overwrite an input of this run (the registry: "
         "registry.json)"},
        {"--json out.xml --junit out.xml",
         "--junit out.xml: is also the output of --json (out.xml)"},
    };
    for (const auto& [flags, message] : cases) {
        const auto r = harness("validate plugin.so --no-signoffs --report report " + flags);
        expect_refusal(r, 1, "acetate-harness: " + message);
        EXPECT_EQ(test::read_file(dir_ / "plugin.so"), plugin) << flags;
        EXPECT_EQ(test::read_file(dir_ / "registry.json"), registry) << flags;
        EXPECT_FALSE(fs::exists(dir_ / "report")) << flags;
    }
}

// merge reads every shard's results/: its --json and --junit may not be one of them.
TEST_F(HarnessInputs, MergeRefusesAReportOverAShardResult) {
    harness::PluginInfo plugin;
    plugin.file = (dir_ / "plugin.so").string();
    plugin.id = "org.example.test";
    plugin.version = "1.0.0";
    plugin.binary_sha256 = std::string(64, 'a');
    plugin.source_digest = std::string(64, 'b');
    harness::CaseSpec spec;
    spec.id = "contract/standard";
    harness::CaseResult result;
    result.id = spec.id;
    const harness::ShardOutput out{
        dir_ / "shard",
        plugin,
        1,
        7,
        harness::Runner{test::kTestRunnerName, test::test_signer().runner_key},
        std::nullopt};
    ASSERT_TRUE(harness::write_shard_result(out, ValidationStage::AlphaTested, spec, result));
    std::vector<fs::path> files;
    for (const auto& item : fs::directory_iterator(dir_ / "shard" / "results"))
        if (item.path().extension() == ".json") files.push_back(item.path());
    ASSERT_EQ(files.size(), 1u);
    const std::string name = "shard/results/" + files[0].filename().string();
    const std::string bytes = test::read_file(files[0]);
    for (const char* flag : {"--json", "--junit"}) {
        const auto r = harness(std::string("merge shard --report report ") + flag + " " + name);
        const std::vector<std::string> lines = test::nonempty_lines(r.err);
        EXPECT_EQ(r.code, 1) << r.describe();
        ASSERT_EQ(lines.size(), 1u) << r.describe();
        EXPECT_EQ(lines[0],
                  "acetate-harness: " + std::string(flag) + " " + name +
                      ": would overwrite an input of this run (a shard's result: " + name + ")")
            << r.describe();
        EXPECT_EQ(test::read_file(files[0]), bytes);
        EXPECT_FALSE(fs::exists(dir_ / "report"));
    }
}

}  // namespace
}  // namespace acetate
