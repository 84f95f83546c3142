// Live parameters through the embedding API (Scene::set_param, Scene::set_preset): the next
// frame is, bit for bit, what a fresh load of the scene file with those values in it renders;
// a value that keeps the effect's passes rebuilds nothing (no load, allocation or compile in
// the change or in the frame); a value that changes them rebuilds that effect alone (no image
// decoded, and the next frame compiles nothing), its reach planned again on a floor; a refusal
// names the field and leaves the frame as it was. Validation layers on.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "acetate/host/host.hpp"
#include "api_host.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class LiveParams : public ::testing::Test {
  protected:
    void SetUp() override {
        auto created = test::build_tree_host();
        ASSERT_TRUE(created) << created.error().message;
        host_ = std::move(created.value());
        dir_ = test::scratch_dir();
    }

    // The scene file with `edit` applied, written where its images still resolve (image paths
    // made absolute), loaded fresh, rendered at `time`: what set_param must equal.
    std::vector<float> fresh_frame(const fs::path& file, const std::function<void(json&)>& edit,
                                   double time) {
        const fs::path edited = test::write_edited_scene(
            file, edit, dir_ / ("edited" + std::to_string(edits_++) + ".json"));
        return frame_of(edited, time, nullptr);
    }

    // Loads `file`, renders at `time`, returns the frame; the scene stays in `keep` if given.
    std::vector<float> frame_of(const fs::path& file, double time,
                                std::unique_ptr<host::Scene>* keep) {
        auto scene = host_->load_scene_file(file);
        EXPECT_TRUE(scene) << scene.error().message;
        if (!scene) return {};
        std::vector<float> out = render(**scene, time);
        if (keep) *keep = std::move(scene.value());
        return out;
    }

    static std::vector<float> render(host::Scene& scene, double time) {
        EXPECT_TRUE(scene.set_time(time));
        auto stats = scene.render();
        EXPECT_TRUE(stats) << stats.error().message;
        auto frame = scene.read_frame();
        EXPECT_TRUE(frame) << frame.error().message;
        return frame ? frame->rgba : std::vector<float>{};
    }

    // A frame that must load, allocate and compile nothing.
    static std::vector<float> render_warm(host::Scene& scene, double time) {
        EXPECT_TRUE(scene.set_time(time));
        auto stats = scene.render();
        EXPECT_TRUE(stats) << stats.error().message;
        if (stats) {
            EXPECT_EQ(stats->images_loaded + stats->targets_allocated + stats->shaders_compiled +
                          stats->pipelines_created,
                      0u);
        }
        auto frame = scene.read_frame();
        EXPECT_TRUE(frame) << frame.error().message;
        return frame ? frame->rgba : std::vector<float>{};
    }

    std::unique_ptr<host::Host> host_;
    fs::path dir_;
    int edits_ = 0;
};

TEST_F(LiveParams, AValueThatKeepsTheFloorEffectsPassesRebuildsNothing) {
    const fs::path file = test::quay_scene("acetate.lighting");
    std::unique_ptr<host::Scene> scene;
    const std::vector<float> before = frame_of(file, 0.5, &scene);
    ASSERT_TRUE(scene);
    const uint32_t pipelines = host_->pipelines_in_pool();

    auto change = scene->set_param({0u, 0}, "day", {0.9f});
    ASSERT_TRUE(change) << change.error().message;
    EXPECT_FALSE(change->reloaded) << "\"day\" only changes a uniform";
    EXPECT_EQ(host_->pipelines_in_pool(), pipelines);
    const std::vector<float> after = render_warm(*scene, 0.5);
    EXPECT_NE(after, before) << "the change reached the frame";
    EXPECT_EQ(after,
              fresh_frame(
                  file, [](json& s) { s["floors"][0]["effects"][0]["params"]["day"] = 0.9; }, 0.5));
    EXPECT_EQ(host_->validation_messages(), 0u);
}

TEST_F(LiveParams, AGlobalEffectsValueAndAValueThatChangesItsPasses) {
    const fs::path file = test::quay_scene("acetate.bloom");
    std::unique_ptr<host::Scene> scene;
    frame_of(file, 0, &scene);
    ASSERT_TRUE(scene);
    const host::EffectSlot bloom{std::nullopt, 0};

    auto threshold = scene->set_param(bloom, "threshold", {0.4f});
    ASSERT_TRUE(threshold) << threshold.error().message;
    EXPECT_FALSE(threshold->reloaded);
    EXPECT_EQ(render_warm(*scene, 0),
              fresh_frame(
                  file, [](json& s) { s["global_effects"][0]["params"]["threshold"] = 0.4; }, 0));

    // "levels" is the depth of bloom's mip chain: another number of passes, so bloom is built
    // again, alone, keeping the threshold set before; the scene's images are not decoded again.
    auto levels = scene->set_param(bloom, "levels", {3.0f});
    ASSERT_TRUE(levels) << levels.error().message;
    EXPECT_TRUE(levels->rebuilt);
    EXPECT_FALSE(levels->reloaded);
    EXPECT_EQ(levels->images_loaded, 0u);
    EXPECT_EQ(render_warm(*scene, 0), fresh_frame(
                                          file,
                                          [](json& s) {
                                              json& p = s["global_effects"][0]["params"];
                                              p["threshold"] = 0.4;
                                              p["levels"] = 3;
                                          },
                                          0));

    auto preset = scene->set_preset(bloom, "low");
    ASSERT_TRUE(preset) << preset.error().message;
    EXPECT_EQ(render(*scene, 0), fresh_frame(
                                     file,
                                     [](json& s) {
                                         json& e = s["global_effects"][0];
                                         e["preset"] = "low";
                                         e["params"]["threshold"] = 0.4;
                                         e["params"]["levels"] = 3;
                                     },
                                     0));
    EXPECT_EQ(host_->validation_messages(), 0u);
}

// Fire's reach is how far its particles can rise and spread: higher smoke declares a longer
// one, so the floor's shaded area (its tile, shrunk to the bottom of the canvas, grown by the
// reach) is planned again: the frame shades what a fresh load with that smoke shades, and is
// that load's frame bit for bit.
TEST_F(LiveParams, AFloorEffectsNewReachRebuildsItAndPlansItsFloorAgain) {
    const fs::path file = test::write_edited_scene(
        test::quay_scene("acetate.fire"),
        [](json& s) {
            s["floors"][0]["tiles"][0]["rect"] = {100, 120, 200, 72};
        },
        dir_ / "small-tile.json");
    const auto higher = [](json& s) {
        s["floors"][0]["effects"][0]["params"]["smoke_height"] = 1000;
    };
    // The floor's step in a frame of `scene` at 0.25 s: its scissor and the pixels it shaded.
    const auto step = [](host::Scene& scene) {
        EXPECT_TRUE(scene.set_time(0.25));
        auto stats = scene.render();
        EXPECT_TRUE(stats) << stats.error().message;
        return stats ? stats->floors.at(0) : host::StepStatistics{};
    };
    auto scene = host_->load_scene_file(file);
    ASSERT_TRUE(scene) << scene.error().message;
    const host::StepStatistics before = step(**scene);

    auto change = (*scene)->set_param({0, 0}, "smoke_height", {1000.0f});
    ASSERT_TRUE(change) << change.error().message;
    EXPECT_TRUE(change->rebuilt);
    EXPECT_FALSE(change->reloaded);
    EXPECT_EQ(change->images_loaded, 0u);
    const host::StepStatistics after = step(**scene);
    auto fresh =
        host_->load_scene_file(test::write_edited_scene(file, higher, dir_ / "higher.json"));
    ASSERT_TRUE(fresh) << fresh.error().message;
    const host::StepStatistics expected = step(**fresh);
    EXPECT_NE(expected.y, before.y) << "the test needs a reach that moves the area";
    EXPECT_EQ(
        std::tie(after.x, after.y, after.width, after.height, after.pixels_shaded),
        std::tie(expected.x, expected.y, expected.width, expected.height, expected.pixels_shaded));
    EXPECT_EQ(render_warm(**scene, 0.25), render(**fresh, 0.25));
    EXPECT_EQ(host_->validation_messages(), 0u);
}

TEST_F(LiveParams, RefusalsNameTheFieldAndLeaveTheFrameAsItWas) {
    const fs::path file = test::quay_scene("acetate.lighting");
    std::unique_ptr<host::Scene> scene;
    const std::vector<float> before = frame_of(file, 0, &scene);
    ASSERT_TRUE(scene);
    const std::string name = file.string();
    struct Refusal {
        host::EffectSlot slot;
        std::string param;
        std::vector<float> value;
        std::string expected;
        std::string field;  // Error::field; with it, the error concerns acetate.lighting on floor 0
    };
    for (const Refusal& r : std::vector<Refusal>{
             {{5u, 0}, "day", {0.5f}, name + ": floor 5 does not exist (floors 0..0)", ""},
             {{0u, 1}, "day", {0.5f}, name + ": floors[0].effects: no effect 1 (it lists 1)", ""},
             {{std::nullopt, 0},
              "day",
              {0.5f},
              name + ": global_effects: no effect 0 (it lists 0)",
              ""},
             {{0u, 0},
              "dusk",
              {0.5f},
              "floors[0].effects[0].params",
              "floors[0].effects[0].params.dusk"},
             {{0u, 0},
              "day",
              {std::nanf("")},
              "not a finite number",
              "floors[0].effects[0].params.day"},
             {{0u, 0},
              "day",
              {},
              "floors[0].effects[0].params.day",
              "floors[0].effects[0].params.day"},
         }) {
        SCOPED_TRACE(r.expected);
        auto change = scene->set_param(r.slot, r.param, r.value);
        ASSERT_FALSE(change);
        const host::Error& error = change.error();
        EXPECT_NE(error.message.find(r.expected), std::string::npos) << error.message;
        EXPECT_EQ(error.message.find('\n'), std::string::npos) << "one line";
        // What a program's interface is built from, besides the message.
        EXPECT_EQ(error.field, r.field);
        if (!r.field.empty()) {
            EXPECT_EQ(error.file, name);
            EXPECT_EQ(error.plugin, "acetate.lighting");
            EXPECT_EQ(error.floor, std::optional<uint32_t>(0u));
        }
    }
    auto preset = scene->set_preset({0u, 0}, "dawn");
    ASSERT_FALSE(preset);
    EXPECT_NE(preset.error().message.find("floors[0].effects[0].preset"), std::string::npos)
        << preset.error().message;
    EXPECT_EQ(preset.error().field, "floors[0].effects[0].preset");
    EXPECT_EQ(preset.error().plugin, "acetate.lighting");
    EXPECT_EQ(render_warm(*scene, 0), before);
}

}  // namespace
}  // namespace acetate
