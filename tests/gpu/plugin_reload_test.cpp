// A plugin rebuilt on disk (Host::reload_plugins): two builds of one id (tests/plugins/
// reload.cpp: reload_v1 halves colour, reload_v2 quarters it) swapped under the Host. An unchanged
// file reloads nothing; a changed one is taken, and every scene using it renders the new code
// with its time kept, as a fresh load does; a changed file that is not a plugin, or declares
// another id, is refused and the scene keeps rendering the old code. Validation layers on.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "acetate/host/host.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

constexpr float kTile[4] = {0.8f, 0.4f, 0.2f, 1.0f};  // opaque
// The tile and the targets are half floats: 0.8 and its scaled values each round by at most
// 2^-11 relative; 1e-3 is above both together and far below the 0.2 between the two versions.
constexpr float kHalf = 1e-3f;

class PluginReload : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::scratch_dir();
        plugins_ = dir_ / "plugins";
        fs::create_directories(plugins_);
        ImageRGBA tile(8, 8);
        for (uint32_t y = 0; y < 8; ++y)
            for (uint32_t x = 0; x < 8; ++x) std::copy_n(kTile, 4, tile.at(x, y));
        test::write_exr(dir_ / "tile.exr", tile);
        test::write_text(dir_ / "scene.json", R"({"format": "acetate-scene/1",
  "canvas": {"width": 8, "height": 8},
  "floors": [{"name": "ground", "tiles": [{"image": "tile.exr", "rect": [0, 0, 8, 8]}],
              "effects": [{"plugin": "test.reload"}]}]})");
        install("reload_v1.so");
        host::HostOptions options;
        options.pipeline_cache = false;
        options.allow_unvalidated = true;
        options.plugin_directories = {plugins_};
        options.on_warning = [this](const std::string& line) { warnings_.push_back(line); };
        auto created = host::Host::create(options);
        ASSERT_TRUE(created) << created.error().message;
        host_ = std::move(created.value());
    }

    // Puts `file` (of the test plugins, or any path) in place of test.reload.so, as a rebuild
    // does: written beside it and renamed over it.
    void install(const fs::path& file) {
        const fs::path source =
            file.is_absolute() ? file : fs::path(ACETATE_TEST_PLUGIN_DIR) / file;
        fs::copy_file(source, plugins_ / "next.so", fs::copy_options::overwrite_existing);
        fs::rename(plugins_ / "next.so", plugins_ / "test.reload.so");
    }

    // The red channel of the frame's first pixel: 0.8 scaled by the plugin in use.
    static float red_of(host::Scene& scene) {
        auto stats = scene.render();
        EXPECT_TRUE(stats) << stats.error().message;
        auto frame = scene.read_frame();
        EXPECT_TRUE(frame) << frame.error().message;
        return frame ? frame->rgba[0] : -1.0f;
    }

    std::unique_ptr<host::Scene> load() {
        auto scene = host_->load_scene_file(dir_ / "scene.json");
        EXPECT_TRUE(scene) << scene.error().message;
        return scene ? std::move(scene.value()) : nullptr;
    }

    fs::path dir_, plugins_;
    std::vector<std::string> warnings_;
    std::unique_ptr<host::Host> host_;
};

TEST_F(PluginReload, ARebuiltPluginReplacesTheOldCodeInEveryScene) {
    auto first = load();
    auto second = load();
    ASSERT_TRUE(first && second);
    ASSERT_TRUE(first->set_time(1.5));
    EXPECT_NEAR(red_of(*first), 0.4f, kHalf);

    // Nothing changed: nothing reloaded.
    std::vector<host::PluginReload> reloads = host_->reload_plugins();
    ASSERT_EQ(reloads.size(), 1u);
    EXPECT_EQ(reloads[0].plugin, "test.reload");
    EXPECT_FALSE(reloads[0].changed);
    EXPECT_EQ(reloads[0].scenes_rebuilt, 0u);
    EXPECT_EQ(reloads[0].refused, "");

    install("reload_v2.so");
    reloads = host_->reload_plugins();
    ASSERT_EQ(reloads.size(), 1u);
    EXPECT_TRUE(reloads[0].changed);
    EXPECT_EQ(reloads[0].scenes_rebuilt, 2u);
    EXPECT_EQ(reloads[0].refused, "");
    EXPECT_EQ(first->time(), 1.5) << "the reloaded scene keeps its time";
    EXPECT_NEAR(red_of(*first), 0.2f, kHalf);
    EXPECT_NEAR(red_of(*second), 0.2f, kHalf);
    // A scene loaded afterwards gets the new code too, and renders what the reloaded ones do.
    auto fresh = load();
    ASSERT_TRUE(fresh);
    EXPECT_NEAR(red_of(*fresh), 0.2f, kHalf);
    EXPECT_EQ(host_->validation_messages(), 0u);
}

TEST_F(PluginReload, ARefusedRebuildLeavesTheOldCodeRendering) {
    auto scene = load();
    ASSERT_TRUE(scene);
    EXPECT_NEAR(red_of(*scene), 0.4f, kHalf);

    // Not a library at all.
    test::write_text(dir_ / "junk.so", "not a shared library\n");
    install(dir_ / "junk.so");
    std::vector<host::PluginReload> reloads = host_->reload_plugins();
    ASSERT_EQ(reloads.size(), 1u);
    EXPECT_TRUE(reloads[0].changed);
    EXPECT_EQ(reloads[0].scenes_rebuilt, 0u);
    EXPECT_TRUE(test::contains(reloads[0].refused, (plugins_ / "test.reload.so").string()))
        << reloads[0].refused;
    EXPECT_NEAR(red_of(*scene), 0.4f, kHalf) << "the old code still renders";
    ASSERT_FALSE(warnings_.empty());
    EXPECT_TRUE(test::contains(warnings_.back(), "test.reload")) << warnings_.back();

    // A plugin, but of another id.
    install("bad_shader.so");
    reloads = host_->reload_plugins();
    ASSERT_EQ(reloads.size(), 1u);
    EXPECT_TRUE(test::contains(reloads[0].refused, "declares id \"test.bad_shader\""))
        << reloads[0].refused;
    EXPECT_NEAR(red_of(*scene), 0.4f, kHalf);

    // Fixed: taken at the next reload.
    install("reload_v2.so");
    reloads = host_->reload_plugins();
    EXPECT_EQ(reloads[0].refused, "");
    EXPECT_EQ(reloads[0].scenes_rebuilt, 1u);
    EXPECT_NEAR(red_of(*scene), 0.2f, kHalf);
}

}  // namespace
}  // namespace acetate
