// The harness knows ABI 1.1: its describe output shows what 1.1 plugins declare (the ABI they
// were built for, vector parameters, hidden parameters), hidden parameters are never varied, and
// its synthetic scenes give plugins lights with height and a sun, and masks with content.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "case_spec.hpp"
#include "synthetic_inputs.hpp"
#include "test_files.hpp"
#include "validate.hpp"

namespace acetate::harness {
namespace {

const std::filesystem::path kProbe =
    std::filesystem::path(ACETATE_TEST_PLUGIN_DIR) / "sdk11_probe.so";

TEST(HarnessAbi11, DescribeShowsTheAbiVectorsAndHiddenParameters) {
    auto info = describe_plugin(kProbe);
    ASSERT_TRUE(info) << info.error().message;
    const nlohmann::json j = to_json(info.value());
    EXPECT_EQ(j["abi"], "1.2");  // built with this tree's header
    EXPECT_EQ(j["hidden_params"], nlohmann::json::array({"taps"}));
    ASSERT_EQ(j["params"].size(), 2u) << j.dump();
    EXPECT_EQ(j["params"][0]["name"], "tint");
    EXPECT_EQ(j["params"][0]["type"], "color");
    EXPECT_EQ(j["params"][0]["components"], 3);
    EXPECT_EQ(j["params"][1]["type"], "vec2");
    EXPECT_EQ(j["params"][1]["components"], 2);
    // What the describe child writes, the parent reads back unchanged.
    auto back = plugin_info_from_json(j, "plugin.json");
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(to_json(back.value()), j);

    auto lighting = describe_plugin(std::filesystem::path(ACETATE_PLUGIN_DIR) / "lighting.so");
    ASSERT_TRUE(lighting) << lighting.error().message;
    EXPECT_EQ(lighting->abi, "1.2");
    EXPECT_EQ(lighting->hidden_params, std::vector<std::string>{"max_lights"});
}

TEST(HarnessAbi11, HiddenParametersAreNotVariedAndSunsAreTried) {
    auto info = describe_plugin(kProbe);
    ASSERT_TRUE(info) << info.error().message;
    const std::vector<CaseSpec> cases = plan_cases(info.value(), 3, 1, true, false, {});
    auto has = [&](const std::string& id) {
        return std::any_of(cases.begin(), cases.end(),
                           [&](const CaseSpec& c) { return c.id == id; });
    };
    EXPECT_TRUE(has("lights/sun"));
    EXPECT_TRUE(has("lights/grazing-sun"));
    EXPECT_TRUE(has("params/sweep-tint"));
    EXPECT_FALSE(has("params/sweep-taps"));
    for (const CaseSpec& c : cases)
        EXPECT_FALSE(c.params.contains("taps")) << c.id << " sets a hidden parameter";
}

TEST(HarnessAbi11, SyntheticFloorsHaveLightsWithHeightASunAndMaskContent) {
    InputChoice choice;
    choice.lights = LightSet::Sun;
    const FloorInput in = make_floor_input(choice, 64, 48, 0, 1, 7, {"water"});
    ASSERT_TRUE(in.sun.has_value());
    EXPECT_EQ(in.sun->elevation, 40.0f);
    ASSERT_EQ(in.lights.size(), 3u);
    EXPECT_TRUE(std::any_of(in.lights.begin(), in.lights.end(),
                            [](const LightDesc& l) { return l.height > 0; }));
    const ImageRGBA& water = in.masks.at("water");
    float lowest = 1, highest = 0;
    for (size_t i = 3; i < water.pixels.size(); i += 4)
        lowest = std::min(lowest, water.pixels[i]), highest = std::max(highest, water.pixels[i]);
    EXPECT_LT(lowest, 0.1f);
    EXPECT_GT(highest, 0.9f);

    // Written and parsed back as `acetate render` reads it.
    SceneLayout layout;
    layout.width = 64;
    layout.height = 48;
    layout.floors.push_back(in);
    layout.floor_effects.resize(1);
    auto scene = write_scene(layout, acetate::test::scratch_dir(), "sun");
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_TRUE(scene->floors[0].sun.has_value());
    EXPECT_EQ(scene->floors[0].sun->azimuth, in.sun->azimuth);
    for (size_t i = 0; i < in.lights.size(); ++i)
        EXPECT_EQ(scene->floors[0].lights[i].height, in.lights[i].height);
}

}  // namespace
}  // namespace acetate::harness
