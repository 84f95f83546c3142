// acetate.lighting against an independent CPU computation, and its contract: alpha preserved
// exactly, transparent pixels stay zero, one floor's lights never light another floor.

#include <Imath/half.h>

#include <cmath>
#include <cstring>

#include "render_fixture.hpp"

namespace acetate::test {
namespace {

class LightingTest : public RenderTest {
  protected:
    EffectRef lighting(nlohmann::json params = nlohmann::json::object(), std::string preset = "") {
        EffectRef ref;
        ref.plugin = "acetate.lighting";
        ref.params = std::move(params);
        ref.preset = std::move(preset);
        ref.where = "floors[0].effects[0]";
        return ref;
    }

    // The lighting model, written independently of the shader: illumination = ambient +
    // sum of point lights with falloff (1 - (d/r)^2)^2 inside the radius, times (1 - darkness).
    static double illumination(double x, double y, const std::vector<LightDesc>& lights, double day,
                               double day_ambient, double night_ambient, double darkness) {
        double level = (night_ambient + (day_ambient - night_ambient) * day) * (1 - darkness);
        double sum[3] = {level, level, level};
        for (const LightDesc& l : lights) {
            const double d = std::hypot(x - l.pos[0], y - l.pos[1]) / l.radius;
            if (d >= 1) continue;
            const double f = (1 - d * d) * (1 - d * d) * l.intensity * (1 - darkness);
            for (int c = 0; c < 3; ++c) sum[c] += l.color[c] * f;
        }
        return sum[0];  // tests use white or single-channel lights; red channel suffices
    }
};

TEST_F(LightingTest, MatchesTheCpuModelAtSampledPixels) {
    SceneDesc scene = make_scene(128, 96, {0, 0, 0, 1});
    const uint32_t floor = add_floor(scene, "ground");
    // Albedo 0.5 grey, alpha varying across the tile (premultiplied).
    ImageRGBA tile(128, 96);
    for (uint32_t y = 0; y < 96; ++y)
        for (uint32_t x = 0; x < 128; ++x) {
            const float a = (x % 16 == 0) ? 0.0f : 0.25f + 0.75f * float(y) / 95.0f;
            float* p = tile.at(x, y);
            p[0] = p[1] = p[2] = 0.5f * a;
            p[3] = a;
        }
    add_tile(scene, floor, tile, {0, 0, 128, 96});
    scene.floors[floor].lights = {{{40, 30}, 50, {1, 1, 1}, 2.0f},
                                  {{100, 70}, 30, {1, 0.5f, 0.25f}, 1.0f}};
    const double day = 0.3, day_ambient = 1.0, night_ambient = 0.2, darkness = 0.25;
    scene.floors[floor].effects = {lighting({{"day", day},
                                             {"day_ambient", day_ambient},
                                             {"night_ambient", night_ambient},
                                             {"darkness", darkness}})};
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    FrameStats stats;
    const ImageRGBA out = render(*compositor, floor, &stats);
    ASSERT_EQ(out.width, 128u);
    EXPECT_EQ(stats.violations, 0u);
    int checked = 0;
    for (uint32_t y = 1; y < 96; y += 7) {
        for (uint32_t x = 1; x < 128; x += 5) {
            const float* in = tile.at(x, y);
            const double light = illumination(x + 0.5, y + 0.5, scene.floors[floor].lights, day,
                                              day_ambient, night_ambient, darkness);
            // Output = lit floor over the opaque black background: rgb = lit rgb, alpha = 1.
            const double expected = in[0] * light;
            // Tolerance: the lit value is rounded to half twice (floor target, composite) and
            // once more by the output: 3 ulps at 2^-10 relative.
            EXPECT_NEAR(out.at(x, y)[0], expected, 3 * expected / 1024 + 1e-6)
                << "pixel " << x << "," << y;
            ++checked;
        }
    }
    EXPECT_GT(checked, 200);
}

TEST_F(LightingTest, PreservesAlphaExactlyAndKeepsTransparentPixelsZero) {
    SceneDesc scene = make_scene(64, 64, {0, 0, 0, 0});  // transparent background: see alpha
    const uint32_t floor = add_floor(scene, "ground");
    ImageRGBA tile(64, 64);
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            const float a = (x + y) % 3 == 0 ? 0.0f : float(x) / 63.0f;
            float* p = tile.at(x, y);
            p[0] = 0.8f * a;
            p[1] = 0.4f * a;
            p[2] = 0.2f * a;
            p[3] = a;
        }
    add_tile(scene, floor, tile, {0, 0, 64, 64});
    scene.floors[floor].lights = {{{32, 32}, 40, {1, 0.9f, 0.8f}, 5.0f}};
    scene.floors[floor].effects = {lighting({{"day", 0.0}})};
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    FrameStats stats;
    render(*compositor, floor, &stats);
    auto accumulation = compositor->read_accumulation();
    ASSERT_TRUE(accumulation.ok());
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            const float* p = accumulation->at(x, y);
            // The tile's alpha in half precision, unchanged by the effect.
            ASSERT_EQ(p[3], float(Imath::half(tile.at(x, y)[3]))) << x << "," << y;
            if (tile.at(x, y)[3] == 0.0f) {
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(p[c], 0.0f) << "colour at alpha 0, " << x << "," << y;
            }
        }
    EXPECT_EQ(stats.violations, 0u);
}

// Light multiplies colour, so a bright light on an HDR pixel could leave the half-float range:
// rgba16f would then store Inf (or, rounding toward zero as lavapipe does, hide it). The lit
// colour is capped at 65504 and never lowers a channel already above it, so it is checked in
// rgba32f targets, where nothing else would cap it.
TEST_F(LightingTest, NeverPushesAChannelPastTheHalfFloatMaximum) {
    SceneDesc scene = make_scene(48, 16, {0, 0, 0, 1});
    const uint32_t floor = add_floor(scene, "ground");
    ImageRGBA tile(48, 16);
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 48; ++x) {
            // Left third 40000 (lit past the cap), middle 65504 (at it), right 90000 (above
            // it already: a light may not lower it), alpha 1 and 0.5 in alternate rows.
            const float level = x < 16 ? 40000.0f : x < 32 ? 65504.0f : 90000.0f;
            const float a = y % 2 ? 0.5f : 1.0f;
            float* p = tile.at(x, y);
            p[0] = p[1] = p[2] = level * a;
            p[3] = a;
        }
    add_tile(scene, floor, tile, {0, 0, 48, 16});
    scene.floors[floor].lights = {{{24, 8}, 60, {1, 1, 1}, 1000.0f}};
    scene.floors[floor].effects = {lighting({{"day", 1.0}, {"day_ambient", 1.0}})};
    CompositorOptions options;
    options.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    auto compositor = load(scene, options);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, floor);
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 48; ++x) {
            const float in = tile.at(x, y)[0];
            // Lit by at least the ambient 1, so every pixel reaches max(in, 65504) or more
            // before the cap: the output is exactly that (over opaque black, alpha 1 or 0.5).
            const float expected = std::max(in, 65504.0f);
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(out.at(x, y)[c], expected) << "pixel " << x << "," << y;
        }
}

TEST_F(LightingTest, OneFloorsLightsNeverLightAnotherFloor) {
    SceneDesc scene = make_scene(64, 32, {0, 0, 0, 1});
    const uint32_t ground = add_floor(scene, "ground");
    add_tile(scene, ground, solid(32, 32, {0.5f, 0.5f, 0.5f, 1}), {0, 0, 32, 32});
    scene.floors[ground].lights = {{{48, 16}, 60, {1, 1, 1}, 3.0f}};  // centred on the UPPER tile
    scene.floors[ground].effects = {lighting({{"day", 1.0}, {"day_ambient", 1.0}})};
    const uint32_t upper = add_floor(scene, "upper");
    add_tile(scene, upper, solid(32, 32, {0.5f, 0.5f, 0.5f, 1}), {32, 0, 32, 32});
    scene.floors[upper].effects = {lighting({{"day", 1.0}, {"day_ambient", 1.0}})};
    scene.floors[upper].effects[0].where = "floors[1].effects[0]";
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, upper);
    // The upper floor has no lights: ambient 1 leaves it exactly as drawn.
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 32; x < 64; ++x) ASSERT_EQ(out.at(x, y)[0], 0.5f) << x << "," << y;
    // The ground floor is lit by its own light (brighter than ambient alone near it).
    EXPECT_GT(out.at(31, 16)[0], 0.6f);
}

TEST_F(LightingTest, PresetsSetParametersAndUnknownOnesAreRefused) {
    SceneDesc scene = make_scene(16, 16);
    const uint32_t floor = add_floor(scene, "ground");
    add_tile(scene, floor, solid(16, 16, {0.5f, 0.5f, 0.5f, 1}), {0, 0, 16, 16});
    scene.floors[floor].effects = {lighting({}, "ultra")};
    EXPECT_TRUE(load(scene));
    scene.floors[floor].effects = {lighting({}, "extreme")};
    auto refused = Compositor::load(renderer(), scene, {});
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("floors[0].effects[0].preset"), std::string::npos)
        << refused.error().message;
    scene.floors[floor].effects = {lighting({{"brightness", 2}})};
    refused = Compositor::load(renderer(), scene, {});
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("params.brightness"), std::string::npos)
        << refused.error().message;
}

}  // namespace
}  // namespace acetate::test

namespace acetate::test {
namespace {

TEST_F(LightingTest, AnimatesWithTimeAndIsDeterministic) {
    SceneDesc scene = make_scene(32, 32, {0, 0, 0, 1});
    const uint32_t floor = add_floor(scene, "ground");
    add_tile(scene, floor, solid(32, 32, {0.5f, 0.5f, 0.5f, 1}), {0, 0, 32, 32});
    scene.floors[floor].lights = {{{16, 16}, 20, {1, 1, 1}, 2.0f}};
    EffectRef ref;
    ref.plugin = "acetate.lighting";
    ref.params = {{"flicker", 1.0}};
    ref.where = "floors[0].effects[0]";
    scene.floors[floor].effects = {ref};
    EffectRef bloom;
    bloom.plugin = "acetate.bloom";
    bloom.where = "global_effects[0]";
    scene.global_effects = {bloom};
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    auto frame = [&](float time) {
        auto stats = compositor->render(floor, time);
        EXPECT_TRUE(stats.ok());
        auto out = compositor->read_output();
        EXPECT_TRUE(out.ok());
        return out.ok() ? out.value() : ImageRGBA();
    };
    const ImageRGBA a = frame(0.0f), b = frame(0.3f), c = frame(0.0f);
    EXPECT_GT(max_abs_difference(a, b), 0.01) << "the flicker follows time";
    ASSERT_EQ(a.pixels.size(), c.pixels.size());
    EXPECT_EQ(std::memcmp(a.pixels.data(), c.pixels.data(), a.pixels.size() * sizeof(float)), 0)
        << "same inputs and time, bit-identical output";
}

}  // namespace
}  // namespace acetate::test
