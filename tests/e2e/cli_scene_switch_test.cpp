// `acetate render A.json B.json A.json`: pipelines survive scene changes (the third load
// compiles nothing and creates no pipeline), and the on-disk pipeline cache survives a
// truncated write (a bad file is ignored with a warning, then replaced by a good one).

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "scene/image_io.hpp"
#include "test_files.hpp"
#include "vulkan/pipeline_cache_file.hpp"

namespace acetate::test {
namespace {

struct CliRun {
    int status = -1;
    std::string err;
};

// Runs `acetate render ARGS --allow-unvalidated`: these tests load the built plugins, which
// the registry need not have validated (the host policy is tested in cli_policy_test.cpp).
CliRun run_cli(const std::string& args, const std::filesystem::path& dir,
               const std::filesystem::path& cache_home) {
    const auto err = dir / "stderr.txt";
    const std::string command = "ACETATE_VALIDATION=1 XDG_CACHE_HOME='" + cache_home.string() +
                                "' '" ACETATE_CLI_PATH "' render " + args +
                                " --allow-unvalidated > '" + (dir / "stdout.txt").string() +
                                "' 2> '" + err.string() + "'";
    CliRun run;
    const int raw = std::system(command.c_str());
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    std::ifstream in(err);
    std::stringstream text;
    text << in.rdbuf();
    run.err = text.str();
    return run;
}

std::string scene_json(const std::string& image, bool with_lighting, int width) {
    std::string effects =
        with_lighting ? R"([{"plugin": "acetate.lighting", "params": {"day": 0.5}}])" : "[]";
    return R"({"format": "acetate-scene/1", "canvas": {"width": )" + std::to_string(width) +
           R"(, "height": 24, "background": [0, 0, 0, 1]},
  "floors": [{"name": "ground", "tiles": [{"image": ")" +
           image + R"(", "rect": [0, 0, 24, 24]}],
              "lights": [{"pos": [12, 12], "radius": 10, "color": [1, 1, 1], "intensity": 1}],
              "effects": )" +
           effects + "}]}";
}

class CliSceneSwitch : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = scratch_dir();
        ImageRGBA tile(24, 24);
        for (size_t i = 0; i < tile.pixels.size(); ++i) tile.pixels[i] = (i % 4 == 3) ? 1.0f : 0.4f;
        write_exr(dir_ / "tile.exr", tile);
        write_text(dir_ / "a.json", scene_json("tile.exr", true, 32));
        write_text(dir_ / "b.json", scene_json("tile.exr", false, 40));
    }
    std::filesystem::path dir_;
};

TEST_F(CliSceneSwitch, TheThirdLoadCompilesNothingAndCreatesNoPipeline) {
    const auto out = dir_ / "out.png";
    const auto stats_file = dir_ / "stats.json";
    const CliRun run =
        run_cli("'" + (dir_ / "a.json").string() + "' '" + (dir_ / "b.json").string() + "' '" +
                    (dir_ / "a.json").string() + "' -o '" + out.string() + "' --stats '" +
                    stats_file.string() + "'",
                dir_, dir_ / "cache");
    ASSERT_EQ(run.status, 0) << run.err;
    const auto stats = nlohmann::json::parse(std::ifstream(stats_file));
    const auto& scenes = stats.at("scenes");
    ASSERT_EQ(scenes.size(), 3u);
    EXPECT_GT(scenes[0]["load"]["shaders_compiled"].get<int>(), 0);
    EXPECT_GT(scenes[0]["load"]["pipelines_created"].get<int>(), 0);
    EXPECT_EQ(scenes[2]["load"]["shaders_compiled"].get<int>(), 0);
    EXPECT_EQ(scenes[2]["load"]["pipelines_created"].get<int>(), 0);
    // B uses no plugin: its load created no effect pipeline either (host stages are shared).
    EXPECT_EQ(scenes[1]["load"]["pipelines_created"].get<int>(), 0);
    EXPECT_EQ(stats.at("plugins_loaded").get<int>(), 1);
    // Same scene, same image.
    auto first = load_image(dir_ / "out.scene0.png", ImageRole::Mask);
    auto third = load_image(dir_ / "out.scene2.png", ImageRole::Mask);
    ASSERT_TRUE(first.ok() && third.ok());
    EXPECT_EQ(first->pixels, third->pixels);
    EXPECT_TRUE(std::filesystem::exists(dir_ / "out.scene1.png"));
}

TEST_F(CliSceneSwitch, ATruncatedPipelineCacheIsIgnoredAndReplaced) {
    const auto cache_home = dir_ / "cache";
    const auto cache_file = cache_home / "acetate" / "pipeline-cache.bin";
    const std::string args =
        "'" + (dir_ / "a.json").string() + "' -o '" + (dir_ / "out.png").string() + "'";
    CliRun run = run_cli(args, dir_, cache_home);
    ASSERT_EQ(run.status, 0) << run.err;
    ASSERT_TRUE(std::filesystem::exists(cache_file));
    const auto size = std::filesystem::file_size(cache_file);
    ASSERT_GT(size, 84u) << "our header (84 bytes) plus the driver's data";

    // A write cut short: half the file.
    std::filesystem::resize_file(cache_file, size / 2);
    run = run_cli(args, dir_, cache_home);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.err.find("ignoring the pipeline cache"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("pipeline-cache.bin"), std::string::npos) << run.err;
    // The run wrote a good file again.
    EXPECT_EQ(std::filesystem::file_size(cache_file), size);

    // Garbage of the right size is caught by the checks too, not handed to the driver.
    std::ofstream(cache_file, std::ios::binary | std::ios::trunc) << std::string(size, 'x');
    run = run_cli(args, dir_, cache_home);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.err.find("ignoring the pipeline cache"), std::string::npos) << run.err;
    // No validation message (the policy's warning names the registry file, which may sit in
    // <build>/validation/, so its lines are left out).
    std::istringstream lines(run.err);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("acetate: warning: loading unvalidated plugin ", 0) == 0) continue;
        EXPECT_EQ(line.find("validation"), std::string::npos) << run.err;
    }
}

TEST_F(CliSceneSwitch, ASceneWithABrokenPluginIsReportedAndTheOthersStillRender) {
    write_text(dir_ / "broken.json",
               R"({"format": "acetate-scene/1", "canvas": {"width": 16, "height": 16},
  "floors": [{"name": "ground", "tiles": [{"image": "tile.exr", "rect": [0, 0, 16, 16]}],
              "effects": [{"plugin": "test.bad_shader"}]}]})");
    const CliRun run =
        run_cli("'" + (dir_ / "a.json").string() + "' '" + (dir_ / "broken.json").string() + "' '" +
                    (dir_ / "a.json").string() + "' -o '" + (dir_ / "out.png").string() +
                    "' --plugin-path '" + ACETATE_TEST_PLUGIN_DIR + "'",
                dir_, dir_ / "cache");
    EXPECT_EQ(run.status, 1) << run.err;
    EXPECT_NE(run.err.find("broken.json: floors[0].effects[0]"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("bad_shader.so"), std::string::npos) << run.err;
    EXPECT_TRUE(std::filesystem::exists(dir_ / "out.scene0.png"));
    EXPECT_FALSE(std::filesystem::exists(dir_ / "out.scene1.png"));
    EXPECT_TRUE(std::filesystem::exists(dir_ / "out.scene2.png"));
}

}  // namespace
}  // namespace acetate::test
