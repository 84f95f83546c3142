// acetate-bench end to end, on a tiny scene (benchmarks are not timed tests: nothing here
// asserts a time). It runs, shows progress, writes well-formed JSON and an HTML report, and its
// error figures hold on the case with a known answer: the reference configuration compared
// with itself has error 0 and infinite PSNR. Bad input gets one line naming what is wrong.
//
// Runs with Vulkan validation on (ACETATE_VALIDATION=1): the bench fails on any message.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

test::CommandResult run_bench(const fs::path& dir, const std::string& args) {
    return test::run_command(std::string("'") + ACETATE_BENCH_PATH + "' --plugin-path '" +
                                 ACETATE_PLUGIN_DIR + "' " + args,
                             dir);
}

// A 19 x 13 canvas (odd sizes): one tile with an alpha ramp under six lights, lit by
// acetate.lighting (its presets shade at most 4, 8, 16 or 64 lights: low shades fewer than
// ultra here, so their images differ).
fs::path tiny_scene(const fs::path& dir) {
    ImageRGBA tile(19, 13);
    for (uint32_t y = 0; y < 13; ++y)
        for (uint32_t x = 0; x < 19; ++x) {
            const float a = float(x + 1) / 19.0f;
            float* p = tile.at(x, y);
            p[0] = 0.6f * a, p[1] = 0.5f * a, p[2] = 0.3f * a, p[3] = a;
        }
    test::write_exr(dir / "tile.exr", tile);
    return test::write_text(dir / "tiny.json", R"({
  "format": "acetate-scene/1",
  "canvas": {"width": 19, "height": 13, "background": [0, 0, 0, 1]},
  "floors": [{
    "name": "ground",
    "tiles": [{"image": "tile.exr", "rect": [0, 0, 19, 13]}],
    "lights": [
      {"pos": [4, 4], "radius": 9, "color": [1, 0.8, 0.6], "intensity": 2},
      {"pos": [15, 9], "radius": 7, "color": [0.5, 0.7, 1], "intensity": 1.5},
      {"pos": [9, 2], "radius": 6, "color": [1, 1, 1], "intensity": 1},
      {"pos": [2, 11], "radius": 6, "color": [0.2, 1, 0.2], "intensity": 1},
      {"pos": [17, 1], "radius": 8, "color": [1, 0.3, 0.3], "intensity": 1},
      {"pos": [11, 12], "radius": 5, "color": [0.4, 0.4, 1], "intensity": 2}
    ],
    "effects": [{"plugin": "acetate.lighting"}]
  }]
})");
}

TEST(BenchCli, ReportsEveryConfigurationWithTheReferenceAtZeroError) {
    const fs::path dir = test::scratch_dir();
    const fs::path scene = tiny_scene(dir);
    const auto run = run_bench(dir, "'" + scene.string() +
                                        "' --presets low,ultra --formats rgba16f,rgba32f "
                                        "--frames 2 --json '" +
                                        (dir / "bench.json").string() + "' --html '" +
                                        (dir / "report").string() + "'");
    ASSERT_EQ(run.code, 0) << run.describe();
    // Progress: one line per configuration, counted.
    EXPECT_NE(run.err.find("tiny.json: the frame against its limits"), std::string::npos)
        << run.describe();
    EXPECT_NE(run.err.find("[1/5] tiny.json acetate.lighting ultra rgba32f"), std::string::npos)
        << run.describe();
    EXPECT_NE(run.err.find("[5/5]"), std::string::npos) << run.describe();

    const json results = json::parse(test::read_file(dir / "bench.json"));
    ASSERT_TRUE(results.contains("configs")) << results.dump(2);
    const json& configs = results["configs"];
    // The reference (ultra, rgba32f), low and ultra in rgba16f, low in rgba32f, and "off".
    ASSERT_EQ(configs.size(), 5u) << results.dump(2);
    int references = 0;
    for (const json& c : configs) {
        SCOPED_TRACE(c.dump());
        EXPECT_EQ(c["plugin"], "acetate.lighting");
        EXPECT_EQ(c["frames"], 2);
        EXPECT_GT(c["pixels_shaded"].get<uint64_t>(), 0u);
        EXPECT_GT(c["median_ms"].get<double>(), 0.0);
        EXPECT_LE(c["min_ms"].get<double>(), c["median_ms"].get<double>());
        EXPECT_LE(c["median_ms"].get<double>(), c["max_ms"].get<double>());
        EXPECT_TRUE(c["error"]["finite"].get<bool>());
        EXPECT_EQ(c["error"]["pixels"], 19 * 13);
        if (c["reference"].get<bool>()) {
            ++references;
            EXPECT_EQ(c["preset"], "ultra");
            EXPECT_EQ(c["format"], "rgba32f");
            // The known answer: the reference against itself.
            EXPECT_EQ(c["error"]["max_abs"].get<double>(), 0.0);
            EXPECT_EQ(c["error"]["max_roundings"].get<double>(), 0.0);
            EXPECT_EQ(c["error"]["mean_abs"].get<double>(), 0.0);
            EXPECT_EQ(c["error"]["psnr_db"], "inf");
            EXPECT_EQ(c["error"]["warn_share"].get<double>(), 0.0);
        } else {
            // Every other configuration differs somewhere (fewer lights, half floats, or no
            // lighting at all), so its PSNR is a finite number and its heat map exists.
            EXPECT_TRUE(c["error"]["psnr_db"].is_number());
            EXPECT_GT(c["error"]["max_abs"].get<double>(), 0.0);
            EXPECT_TRUE(fs::exists(dir / "report" / c["heat_map"].get<std::string>()));
        }
    }
    EXPECT_EQ(references, 1);
    const std::string html = test::read_file(dir / "report" / "index.html");
    EXPECT_NE(html.find("<svg"), std::string::npos);
    EXPECT_NE(html.find("acetate.lighting"), std::string::npos);
    // The limits: one tile covering the canvas, lit: every pass shades exactly the tile, so
    // what the frame shades is the minimum (tile, lighting, composite, output: 4 canvases).
    ASSERT_EQ(results["limits"].size(), 1u) << results.dump(2);
    EXPECT_EQ(results["limits"][0]["necessary_pixels"], 4 * 19 * 13) << results["limits"][0];
    EXPECT_EQ(results["limits"][0]["pixels_shaded"], 4 * 19 * 13) << results["limits"][0];
    EXPECT_EQ(results["limits"][0]["switch_floor"], -1) << results["limits"][0];
    // The peer: oiiotool flattened the same tile, and the two images agree to half precision
    // (acetate's output image is rgba16f; the tile is exact in both).
    ASSERT_EQ(results["peers"].size(), 1u) << results.dump(2);
    EXPECT_LE(results["peers"][0]["difference"]["max_abs"].get<double>(), 1.0 / 1024)
        << results["peers"][0].dump(2);
}

// A plugin whose presets are "draft" and "final": without --presets the bench runs every preset
// it declares, and the reference is its last one, as there is no "ultra".
TEST(BenchCli, APluginsOwnPresetsAreRunAndTheLastIsTheReference) {
    const fs::path dir = test::scratch_dir();
    std::string text = test::read_file(tiny_scene(dir));
    const std::string lighting = "\"plugin\": \"acetate.lighting\"";
    text.replace(text.find(lighting), lighting.size(), "\"plugin\": \"test.named_presets\"");
    const fs::path scene = test::write_text(dir / "named.json", text);
    const auto run =
        run_bench(dir, "--plugin-path '" + std::string(ACETATE_TEST_PLUGIN_DIR) + "' '" +
                           scene.string() + "' --formats rgba16f --frames 1 --no-peers --json '" +
                           (dir / "bench.json").string() + "'");
    ASSERT_EQ(run.code, 0) << run.describe();
    const json results = json::parse(test::read_file(dir / "bench.json"));
    std::set<std::string> presets;
    for (const json& c : results["configs"]) {
        if (c["preset"] == "off") continue;
        presets.insert(c["preset"].get<std::string>());
        if (c["reference"].get<bool>()) {
            EXPECT_EQ(c["preset"], "final") << c.dump();
            EXPECT_EQ(c["error"]["max_abs"].get<double>(), 0.0) << c.dump();
        } else {
            // draft keeps 0.5 of the colour where final keeps 0.9: it differs.
            EXPECT_GT(c["error"]["max_abs"].get<double>(), 0.0) << c.dump();
        }
    }
    EXPECT_EQ(presets, (std::set<std::string>{"draft", "final"})) << results.dump(2);
}

TEST(BenchCli, BadInputGetsOneLineNamingIt) {
    const fs::path dir = test::scratch_dir();
    const fs::path scene = tiny_scene(dir);
    struct Case {
        std::string args, expected;
    };
    const std::vector<Case> cases = {
        {"'" + scene.string() + "' --presets low,shiny --no-peers",
         "--presets: plugin acetate.lighting has no preset \"shiny\""},
        {"'" + scene.string() + "' --formats rgba8 --no-peers",
         "--formats: expected rgba16f or rgba32f, got \"rgba8\""},
        {"'" + scene.string() + "' --plugins acetate.water --no-peers",
         "--plugins: no scene names the plugin acetate.water"},
        {"'" + scene.string() + "' --floor 3 --no-peers", "--floor: floor 3 does not exist"},
        {"'" + (dir / "missing.json").string() + "'", "missing.json"},
    };
    for (const Case& c : cases) {
        const auto run = run_bench(dir, c.args);
        EXPECT_NE(run.code, 0) << run.describe();
        const auto lines = test::nonempty_lines(run.err);
        ASSERT_FALSE(lines.empty()) << run.describe();
        EXPECT_NE(lines.back().find(c.expected), std::string::npos) << run.describe();
        EXPECT_EQ(lines.back().rfind("acetate-bench: ", 0), 0u) << run.describe();
    }
}

}  // namespace
}  // namespace acetate
