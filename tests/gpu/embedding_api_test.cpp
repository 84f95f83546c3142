// The embedding API (acetate/host/host.hpp) as a program other than `acetate` uses it: a scene
// inspected without a device, loaded with a debug view and 32-bit targets, its per-floor frame
// statistics and what it holds, and a host that loads no plugins. Expected pixels come from
// the tiles' own values (premultiplied "over", the debug views' definitions), not from a
// render. Validation layers on (ACETATE_VALIDATION=1 from ctest).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "acetate/host/host.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

class EmbeddingApi : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::scratch_dir();
        // Floor 0: opaque (0.2, 0.4, 0.6) over the left 8 columns. Floor 1: (0.8, 0.1, 0.3) at
        // alpha 0.5, premultiplied, over columns 4..11: over floor 0 at columns 4..7.
        ImageRGBA low(8, 8), high(8, 8);
        for (uint32_t y = 0; y < 8; ++y)
            for (uint32_t x = 0; x < 8; ++x) {
                std::copy_n(kLow, 4, low.at(x, y));
                std::copy_n(kHighPremultiplied, 4, high.at(x, y));
            }
        test::write_exr(dir_ / "low.exr", low);
        test::write_exr(dir_ / "high.exr", high);
        test::write_exr(dir_ / "mask.exr", high);
        test::write_text(dir_ / "scene.json", scene_text(""));
    }

    // Two floors on a 16x8 canvas; `effects` goes into floor 1.
    static std::string scene_text(const std::string& effects) {
        return R"({"format": "acetate-scene/1", "canvas": {"width": 16, "height": 8},
  "floors": [{"name": "ground", "tiles": [{"image": "low.exr", "rect": [0, 0, 8, 8]}]},
             {"name": "roof", "tiles": [{"image": "high.exr", "rect": [4, 0, 8, 8],
                                         "masks": {"water": "mask.exr"}}],
              "effects": [)" +
               effects + "]}]}\n";
    }

    static host::HostOptions options() {
        host::HostOptions o;
        o.pipeline_cache = false;
        o.load_plugins = false;
        return o;
    }

    static constexpr float kLow[4] = {0.2f, 0.4f, 0.6f, 1.0f};
    static constexpr float kHighPremultiplied[4] = {0.4f, 0.05f, 0.15f, 0.5f};
    fs::path dir_;
};

TEST_F(EmbeddingApi, InspectsASceneWithoutADevice) {
    auto info = host::Host::inspect_scene_file(dir_ / "scene.json");
    ASSERT_TRUE(info) << info.error().message;
    EXPECT_EQ(info->width, 16u);
    EXPECT_EQ(info->height, 8u);
    EXPECT_EQ(info->floor_names, (std::vector<std::string>{"ground", "roof"}));
    EXPECT_FALSE(info->names_plugins);
    ASSERT_EQ(info->inputs.size(), 4u);  // the scene, two tile images, one mask
    EXPECT_EQ(info->inputs[0].field, "scene");
    const std::string scene = (dir_ / "scene.json").string();
    EXPECT_EQ(info->inputs[1].field, scene + ": floors[0].tiles[0].image");
    EXPECT_EQ(info->inputs[3].field, scene + ": floors[1].tiles[0].masks.water");
    EXPECT_EQ(info->inputs[3].file.filename(), "mask.exr");

    test::write_text(dir_ / "bad.json", R"({"format": "acetate-scene/1", "canvas": {}})");
    auto bad = host::Host::inspect_scene_file(dir_ / "bad.json");
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().message,
              (dir_ / "bad.json").string() + ": canvas: missing required field \"width\"");
    EXPECT_EQ(bad.error().file, (dir_ / "bad.json").string());
    EXPECT_EQ(bad.error().field, "canvas");
    EXPECT_EQ(bad.error().plugin, "");
    EXPECT_EQ(bad.error().floor, std::nullopt);
}

TEST_F(EmbeddingApi, ViewsPrecisionAndPerFloorStatistics) {
    auto created = host::Host::create(options());
    ASSERT_TRUE(created) << created.error().message;
    host::Host& h = *created.value();

    host::SceneOptions scene_options;
    scene_options.precision = host::Precision::Float32;
    auto scene = h.load_scene_file(dir_ / "scene.json", scene_options);
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_TRUE((*scene)->set_active_floor(1));
    auto stats = (*scene)->render();
    ASSERT_TRUE(stats) << stats.error().message;
    ASSERT_EQ(stats->floors.size(), 2u);
    EXPECT_EQ(stats->floors[0].floor, 0u);
    EXPECT_EQ(stats->floors[1].floor, 1u);
    EXPECT_EQ(stats->floors[1].width, 8);  // the roof's tile, columns 4..11
    EXPECT_FALSE(stats->global_effects);
    auto frame = (*scene)->read_frame();
    ASSERT_TRUE(frame) << frame.error().message;
    // Column 5: the roof over the ground, premultiplied over; 32-bit float targets keep it to
    // float rounding (1e-6), which half floats (about 1e-3 here) would not.
    const float* p = &frame->rgba[(3 * 16 + 5) * 4];
    for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(p[c], kHighPremultiplied[c] + kLow[c] * (1 - kHighPremultiplied[3]), 1e-6f)
            << "channel " << c;
    const std::vector<host::ImageInfo> targets = (*scene)->render_targets();
    const auto accumulation = std::find_if(targets.begin(), targets.end(),
                                           [](const auto& t) { return t.name == "accumulation"; });
    ASSERT_NE(accumulation, targets.end());
    EXPECT_EQ(accumulation->format, "rgba32f");
    EXPECT_EQ(accumulation->bytes, uint64_t(16) * 8 * 16) << "16x8 texels of 4 32-bit floats";
    EXPECT_GT((*scene)->images_held().size(), (*scene)->render_targets().size())
        << "the tile textures and the mask are held too";

    // The floor-alpha view of the roof: its own alpha in grey, opaque; 0 where it has no tile.
    scene_options.view = host::View::FloorAlpha;
    auto alpha_view = h.load_scene_file(dir_ / "scene.json", scene_options);
    ASSERT_TRUE(alpha_view) << alpha_view.error().message;
    ASSERT_TRUE((*alpha_view)->set_active_floor(1));
    ASSERT_TRUE((*alpha_view)->render());
    auto alpha = (*alpha_view)->read_frame();
    ASSERT_TRUE(alpha);
    EXPECT_EQ(alpha->rgba[(3 * 16 + 5) * 4], 0.5f);
    EXPECT_EQ(alpha->rgba[(3 * 16 + 1) * 4], 0.0f);
    EXPECT_EQ(alpha->rgba[(3 * 16 + 1) * 4 + 3], 1.0f);

    EXPECT_EQ(h.plugins_loaded(), 0u);
    EXPECT_GT(h.pipelines_in_pool(), 0u);
    EXPECT_EQ(h.validation_messages(), 0u);
    EXPECT_EQ(std::string(host::view_name(host::View::FloorAlpha)), "floor-alpha");
    auto unknown = host::parse_view("floor_alpha");
    ASSERT_FALSE(unknown);
    EXPECT_NE(unknown.error().message.find("expected normal, floor-alpha"), std::string::npos)
        << unknown.error().message;
}

TEST_F(EmbeddingApi, AHostWithoutPluginsReadsNoRegistryAndRefusesAScenesPlugin) {
    host::HostOptions o = options();
    o.registry = test::write_text(dir_ / "registry.json", "{ not json");
    auto created = host::Host::create(o);
    ASSERT_TRUE(created) << "the registry is not read: " << created.error().message;
    EXPECT_EQ(host::Host::registry_file(o), dir_ / "registry.json");

    // A plugin no folder holds: the host refuses it before looking for its file.
    test::write_text(dir_ / "lit.json", scene_text(R"({"plugin": "test.installed_nowhere"})"));
    auto info = host::Host::inspect_scene_file(dir_ / "lit.json");
    ASSERT_TRUE(info);
    EXPECT_TRUE(info->names_plugins);
    auto scene = (*created)->load_scene_file(dir_ / "lit.json");
    ASSERT_FALSE(scene);
    const std::string& line = scene.error().message;
    EXPECT_NE(line.find("lit.json: floors[1].effects[0].plugin: "), std::string::npos) << line;
    EXPECT_NE(line.find("this host loads no plugins"), std::string::npos) << line;
    EXPECT_EQ(line.find('\n'), std::string::npos) << line;

    o.load_plugins = true;
    auto strict = host::Host::create(o);
    ASSERT_FALSE(strict) << "with plugins on, the malformed registry is read and refused";
    EXPECT_NE(strict.error().message.find("registry.json"), std::string::npos)
        << strict.error().message;
}

}  // namespace
}  // namespace acetate
