// ABI 1.1 end to end on the device: what tests/plugins/sdk11/sdk11_probe.cpp reports back in
// its output's first row is compared with values this test works out on its own (masks summed
// at build, lights with height and a sun, floor facts, vector and hidden parameters, a phase and
// the clock reduced in double, a 32-bit target read through a renamed input); and a declared
// reach (tests/plugins/sdk11/reach_glow.cpp) shades fewer pixels for the same image.
#include <Imath/half.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "render_fixture.hpp"
#include "test_files.hpp"

namespace acetate::test {
namespace {

class Sdk11Test : public RenderTest {
  protected:
    static constexpr uint32_t kWidth = 40, kHeight = 24;

    // Floor 0: grey over the canvas. Floor 1: an opaque 30x20 tile at the origin with a water
    // mask, two lights and a sun, and the probe.
    SceneDesc probe_scene(nlohmann::json params, const std::string& preset) {
        SceneDesc scene = make_scene(kWidth, kHeight, {0, 0, 0, 1});
        add_tile(scene, add_floor(scene, "under"), solid(kWidth, kHeight, {0.5f, 0.5f, 0.5f, 1}),
                 {0, 0, kWidth, kHeight});
        const uint32_t probe = add_floor(scene, "probe");
        add_tile(scene, probe, solid(30, 20, {0.1f, 0.2f, 0.3f, 1}), {0, 0, 30, 20});
        scene.floors[probe].tiles[0].masks["water"] = write_exr(dir() / "water.exr", water_);
        LightDesc high{{5, 6}, 10, {1, 1, 1}, 1};
        high.height = 7.5f;
        const LightDesc flat{{20, 3}, 4, {1, 0.5f, 0.25f}, 2};
        scene.floors[probe].lights = {high, flat};
        scene.floors[probe].sun = SunDesc{90, 30, {1, 1, 1}, 1};
        EffectRef ref;
        ref.plugin = "test.sdk11_probe";
        ref.where = "floors[1].effects[0]";
        ref.params = std::move(params);
        ref.preset = preset;
        scene.floors[probe].effects.push_back(ref);
        return scene;
    }

    void SetUp() override {
        RenderTest::SetUp();
        // Water in the left third, its alpha rising down the tile: values a float holds exactly.
        water_ = ImageRGBA(30, 20);
        for (uint32_t y = 0; y < 20; ++y)
            for (uint32_t x = 0; x < 10; ++x) water_.at(x, y)[3] = float(y) / 16.0f;
    }

    ImageRGBA water_;
};

TEST_F(Sdk11Test, ProbeReadsWhatTheHostGaveIt) {
    CompositorOptions options;
    options.format = VK_FORMAT_R32G32B32A32_SFLOAT;  // the probe's values come back exactly
    auto compositor =
        load(probe_scene({{"tint", {0.1, 0.2, 0.3}}, {"offset", {9.0, -1.0}}}, "ultra"), options);
    ASSERT_TRUE(compositor);
    const double time = 100000.3;
    auto frame = compositor->render(1, time);
    ASSERT_TRUE(frame) << frame.error().message;
    auto out = compositor->read_output();
    ASSERT_TRUE(out) << out.error().message;
    auto at = [&](uint32_t x) {
        const float* p = out->at(x, 0);
        return std::array<float, 3>{p[0], p[1], p[2]};
    };
    using V = std::array<float, 3>;

    // Parameters: a colour and a vec2 (clamped per component to [-8, 8]); the hidden taps from
    // the "ultra" preset, also reaching GLSL through the pass's defines.
    EXPECT_EQ(at(0), (V{0.1f, 0.2f, 0.3f}));
    EXPECT_EQ(at(1), (V{8.0f, -1.0f, 8.0f}));
    // The clock and a 0.7 s phase, reduced in double: at 10^5 s a float time is 7.8 ms coarse.
    const double turns = time / 0.7;
    EXPECT_EQ(at(2), (V{float(turns - std::floor(turns)), float(time - 100000.0), 100000.0f}));
    EXPECT_NE(float(float(time) - 100000.0f), float(time - 100000.0))
        << "the case must be one a float time gets wrong";
    // Lights: two points then the sun; heights as the scene gave them (default 0).
    const double pi = 3.14159265358979323846, az = 90 * pi / 180, el = 30 * pi / 180;
    EXPECT_EQ(at(3)[0], 3.0f);
    EXPECT_EQ(at(3)[1], 7.5f);
    EXPECT_NEAR(at(3)[2], std::sin(el), 1e-7);
    EXPECT_NEAR(at(10)[0], std::cos(el) * std::cos(az), 1e-7);
    EXPECT_NEAR(at(10)[1], std::cos(el) * std::sin(az), 1e-7);
    EXPECT_NEAR(at(10)[2], std::sin(el), 1e-7);
    EXPECT_EQ(at(11), (V{float(ACETATE_LIGHT_SUN), 20.0f, 3.0f}));

    // The water mask as build() read it: its alpha summed, and the weighted centroid (the tile
    // is drawn one to one, so the composite holds the file's values).
    double sum = 0, cx = 0, cy = 0;
    for (uint32_t y = 0; y < 20; ++y)
        for (uint32_t x = 0; x < 30; ++x) {
            const double a = water_.at(x, y)[3];
            sum += a, cx += a * (x + 0.5), cy += a * (y + 0.5);
        }
    EXPECT_EQ(at(4), (V{float(sum), float(cx / sum), float(cy / sum)}));
    // A declared kind the floor lacks reads zeros; then the coverage bounds, floor count and
    // index, and the mask's size (the canvas).
    EXPECT_EQ(at(5), (V{0.0f, 0.0f, 0.0f}));
    EXPECT_EQ(at(6), (V{30.0f, 20.0f, 2.0f}));
    EXPECT_EQ(at(7), (V{1.0f, 8.0f, float(kWidth * 10000 + kHeight)}));
    // The RG32F half-size target through the input renamed "src": its size, and a value a half
    // float cannot hold.
    EXPECT_EQ(at(8), (V{kWidth / 2.0f, kHeight / 2.0f, 1.0f / (kWidth / 2.0f)}));
    const float field_x = 3.5f * 1000.123f, field_y = 2.5f * 1000.123f;
    ASSERT_NE(float(Imath::half(field_x)), field_x);
    EXPECT_EQ(at(9), (V{field_x, field_y, 0.0f}));
    // Away from row 0 the floor is unchanged.
    EXPECT_EQ(std::vector<float>(out->at(5, 5), out->at(5, 5) + 4),
              (std::vector<float>{0.1f, 0.2f, 0.3f, 1.0f}));

    // A time just under a whole second, where the fraction in double rounds to 1.0f: the host
    // keeps it below 1, as it keeps the phases, for effects that take it as [0, 1).
    ASSERT_TRUE(compositor->render(1, 2.99999999));
    auto edge = compositor->read_output();
    ASSERT_TRUE(edge) << edge.error().message;
    EXPECT_EQ(edge->at(2, 0)[1], 0x1.fffffep-1f);
    EXPECT_EQ(edge->at(2, 0)[2], 2.0f);
    EXPECT_LT(edge->at(2, 0)[0], 1.0f);
    EXPECT_EQ(float(2.99999999 - 2.0), 1.0f) << "the case must be one a plain cast gets wrong";
}

TEST_F(Sdk11Test, SceneErrorsNameTheField) {
    auto refused = [&](nlohmann::json params, const std::string& preset) {
        auto loaded = Compositor::load(renderer(), probe_scene(std::move(params), preset), {});
        return loaded ? std::string("(loaded)") : loaded.error().message;
    };
    EXPECT_NE(refused({{"taps", 3}}, "")
                  .find("floors[1].effects[0].params.taps: plugin "
                        "\"test.sdk11_probe\" sets this parameter from its "
                        "presets only"),
              std::string::npos);
    EXPECT_NE(refused({{"offset", 1.0}}, "")
                  .find("floors[1].effects[0].params.offset: expected "
                        "an array of 2 numbers, got 1.0"),
              std::string::npos);
    EXPECT_NE(refused({{"tint", {0.1, "x", 0.3}}}, "")
                  .find("floors[1].effects[0].params.tint[1]: expected a number"),
              std::string::npos);

    const std::string light = R"({"format": "acetate-scene/1", "canvas": {"width": 8, "height": 8},
        "floors": [{"name": "a", "tiles": [], "lights": [{"pos": [1, 1], "radius": 2,
        "height": -3}]}]})";
    auto parsed = parse_scene_text(light, dir() / "light.json");
    ASSERT_FALSE(parsed);
    EXPECT_NE(parsed.error().message.find("light.json: floors[0].lights[0].height: must be >= 0"),
              std::string::npos)
        << parsed.error().message;
    const std::string sun = R"({"format": "acetate-scene/1", "canvas": {"width": 8, "height": 8},
        "floors": [{"name": "a", "tiles": [], "sun": {"azimuth": 10, "elevation": 95}}]})";
    parsed = parse_scene_text(sun, dir() / "sun.json");
    ASSERT_FALSE(parsed);
    EXPECT_EQ(parsed.error().message,
              (dir() / "sun.json").string() +
                  ": floors[0].sun.elevation: must be in [0, 90] degrees, got 95");
}

// A 720p canvas with two small floors, each grown by one pixel. Without a declared reach the
// host must shade the whole canvas for each; with it, only the tiles grown by one pixel.
TEST_F(Sdk11Test, DeclaredReachShadesLessForTheSameImage) {
    auto render_with = [&](bool declare_reach, uint64_t& pixels) {
        SceneDesc scene = make_scene(1280, 720, {0, 0, 0, 1});
        for (int f = 0; f < 2; ++f) {
            const uint32_t floor = add_floor(scene, fmt::format("f{}", f));
            add_tile(scene, floor, solid(100, 80, {0.4f, 0.2f * f, 0.1f, 1}),
                     {200.0 + 500 * f, 100.0 + 300 * f, 100, 80});
            EffectRef ref;
            ref.plugin = "test.reach_glow";
            ref.where = fmt::format("floors[{}].effects[0]", f);
            ref.params = {{"declare_reach", declare_reach}};
            scene.floors[floor].effects.push_back(ref);
        }
        auto compositor = load(scene);
        FrameStats stats;
        ImageRGBA image = compositor ? render(*compositor, 1, &stats) : ImageRGBA{};
        pixels = 0;  // the floors' own passes (the output pass covers the canvas either way)
        for (const FloorFrameReport& floor : stats.floors) pixels += floor.pixels_shaded;
        return image;
    };
    uint64_t whole = 0, reached = 0;
    const ImageRGBA without = render_with(false, whole);
    const ImageRGBA with = render_with(true, reached);
    ASSERT_EQ(with.pixels.size(), without.pixels.size());
    EXPECT_EQ(with.pixels, without.pixels) << "a declared reach must not change the image";
    std::printf("pixels shaded: %llu without a reach, %llu with reach 1\n",
                static_cast<unsigned long long>(whole), static_cast<unsigned long long>(reached));
    // Each floor: its tiles (100x80), then the glow and the composite over 102x82; without the
    // reach, the glow and the composite cover the canvas.
    EXPECT_EQ(reached, 2u * (100 * 80 + 2 * 102 * 82));
    EXPECT_EQ(whole, 2u * (100 * 80 + 2 * 1280 * 720));
}

}  // namespace
}  // namespace acetate::test
