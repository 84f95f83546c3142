// acetate.specular against an independent CPU model in double precision (specular_model.hpp:
// written from the textbook formulas, not from the shader: the classic GGX form, Smith's G2 from
// the Lambda functions, Schlick's Fresnel), at the limits the effect promises to handle: roughness
// 0, a light straight above a flat normal, grazing light, normals facing away, 64 lights on HDR
// input, an alpha ramp, a normal mask on one tile of two, no lights; with acetate.lighting
// before it; and across floors.
//
// Every input is made of half floats (the floor target and the masks are RGBA16F), so the
// model and the shader start from the same values. The floor target is read directly
// (the floor-rgb view), so one conversion to half lies between the shader and the test.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <vector>

#include "render_fixture.hpp"
#include "specular_model.hpp"
#include "test_files.hpp"

namespace acetate::test {
namespace {

using namespace specular;

class SpecularTest : public RenderTest {
  protected:
    // Adds a tile whose colour and masks are the `in` composites over `rect`, and copies them
    // there (the host resamples a 1:1 rect at pixel centres exactly).
    void add_region(SceneDesc& scene, uint32_t floor, Inputs& canvas, const ImageRGBA& colour,
                    std::map<std::string, ImageRGBA> masks, uint32_t x0, uint32_t y0) {
        add_tile(scene, floor, colour,
                 {double(x0), double(y0), double(colour.width), double(colour.height)});
        TileDesc& tile = scene.floors[floor].tiles.back();
        for (auto& [kind, mask] : masks)
            tile.masks[kind] =
                write_exr(dir() / fmt::format("mask{}.{}.exr", masks_++, kind), mask);
        auto copy = [&](const ImageRGBA& from, ImageRGBA& to) {
            for (uint32_t y = 0; y < from.height; ++y)
                for (uint32_t x = 0; x < from.width; ++x)
                    std::memcpy(to.at(x0 + x, y0 + y), from.at(x, y), 4 * sizeof(float));
        };
        copy(colour, canvas.colour);
        if (masks.count("specular")) copy(masks["specular"], canvas.specular);
        if (masks.count("roughness")) copy(masks["roughness"], canvas.roughness);
        if (masks.count("normal")) copy(masks["normal"], canvas.normal);
        canvas.has_roughness |= masks.count("roughness") != 0;
        canvas.has_normal |= masks.count("normal") != 0;
    }

    static EffectRef effect(const std::string& where, nlohmann::json params,
                            std::string preset = "") {
        EffectRef ref;
        ref.plugin = "acetate.specular";
        ref.params = std::move(params);
        ref.preset = std::move(preset);
        ref.where = where;
        return ref;
    }

    // Renders `floor` and returns its own target after its effects.
    ImageRGBA floor_target(const SceneDesc& scene, uint32_t floor, FrameStats* stats = nullptr) {
        CompositorOptions options;
        options.view = OutputView::FloorRgb;
        auto compositor = load(scene, options);
        if (!compositor) return {};
        render(*compositor, floor, stats);
        auto target = compositor->read_active_floor();
        EXPECT_TRUE(target.ok());
        return target.ok() ? target.value() : ImageRGBA();
    }

    // Compares every `step`-th pixel of `out` with the model; returns the largest added term.
    double expect_model(const ImageRGBA& out, const Inputs& in, const FloorDesc& floor,
                        const Params& p, uint32_t step = 1) {
        EXPECT_EQ(out.width, in.colour.width);
        if (out.width != in.colour.width || out.height != in.colour.height) return 0;
        double largest = 0;
        int failures = 0;
        for (uint32_t y = 0; y < out.height; y += step)
            for (uint32_t x = 0; x < out.width; x += step) {
                const Expected e = expected_at(in, x, y, floor, p);
                const float* o = out.at(x, y);
                for (int c = 0; c < 3; ++c) {
                    // Also false for NaN and Inf.
                    if (!(std::fabs(o[c] - e.rgb[c]) <= tolerance(e.rgb[c], e.added[c])) &&
                        failures++ < 5)
                        ADD_FAILURE()
                            << "pixel " << x << "," << y << " channel " << c << ": " << o[c]
                            << ", model " << e.rgb[c] << " (added " << e.added[c] << ")";
                    largest = std::max(largest, e.added[c]);
                }
                if (o[3] != in.colour.at(x, y)[3] && failures++ < 5)
                    ADD_FAILURE() << "alpha at " << x << "," << y << ": " << o[3] << ", input "
                                  << in.colour.at(x, y)[3];
            }
        EXPECT_EQ(failures, 0) << "pixels differing from the model";
        return largest;
    }

    int masks_ = 0;
};

TEST_F(SpecularTest, FlatTiltedSmoothAndRoughTilesMatchTheCpuModel) {
    SceneDesc scene = make_scene(128, 96);
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(128, 96);
    // The specular mask varies in rgb and alpha, so the luminance-times-alpha reading shows.
    auto specular = image(64, 48, [](uint32_t x, uint32_t y) {
        return std::array<double, 4>{0.5 + x / 128.0, 0.9, 0.6 + y / 96.0, 0.5 + y / 96.0};
    });
    auto colour = image(64, 48, [](uint32_t x, uint32_t y) {
        const double a = (x + y) % 5 == 0 ? 0.5 : 1.0;
        return std::array<double, 4>{0.03 * a, 0.025 * a, 0.02 * a, a};  // dark: highlights show
    });
    add_region(scene, f, in, colour, {{"specular", specular}}, 0, 0);  // flat
    add_region(scene, f, in, colour,
               {{"specular", specular}, {"normal", normal_mask(64, 48, {0.35, -0.25, 1})}}, 64, 0);
    add_region(scene, f, in, colour, {{"specular", specular}, {"roughness", mask(64, 48, 0.2)}}, 0,
               48);  // smooth
    add_region(scene, f, in, colour, {{"specular", specular}, {"roughness", mask(64, 48, 0.9)}}, 64,
               48);  // rough
    FloorDesc& floor = scene.floors[f];
    floor.lights = {{{30, 20}, 90, {1, 0.9f, 0.7f}, 3.0f, 25},
                    {{100, 30}, 80, {0.6f, 0.8f, 1}, 4.0f, 40},
                    {{40, 75}, 70, {1, 1, 1}, 2.0f, 15},
                    {{120, 90}, 150, {1, 1, 1}, 6.0f, 3}};  // low: grazing light, Fresnel shows
    floor.sun = SunDesc{30, 50, {1, 0.95f, 0.8f}, 1.5f};
    Params p;
    p.intensity = 1.5, p.f0 = 0.06, p.roughness = 0.5;
    floor.effects = {effect("floors[0].effects[0]", p.json())};
    FrameStats stats;
    const ImageRGBA out = floor_target(scene, f, &stats);
    EXPECT_GT(expect_model(out, in, floor, p), 0.2) << "the highlights must be visible";
    EXPECT_EQ(stats.violations, 0u);
}

TEST_F(SpecularTest, LightStraightAboveAFlatNormalPeaksAtTheBoundOfRoughnessZero) {
    SceneDesc scene = make_scene(64, 48);
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(64, 48);
    add_region(scene, f, in, grey(64, 48, 0.2), {{"specular", mask(64, 48, 1)}}, 0, 0);
    FloorDesc& floor = scene.floors[f];
    floor.lights = {{{32.5f, 24.5f}, 1000, {1, 1, 1}, 1.0f, 20}};  // above pixel (32, 24)
    Params p;
    p.roughness = 0, p.f0 = 1;
    floor.effects = {effect("floors[0].effects[0]", p.json())};
    const ImageRGBA out = floor_target(scene, f);
    expect_model(out, in, floor, p);
    // NoH = NoL = NoV = VoH = 1: D = 1 / (pi alpha^2) with alpha = 0.089^2, V = 1/4, F = f0 = 1,
    // times the falloff (1 - (20 / 1000)^2)^2.
    const double alpha = 0.089 * 0.089, falloff = std::pow(1 - 0.02 * 0.02, 2);
    const double peak = falloff / (kPi * alpha * alpha) / 4;
    EXPECT_NEAR(out.at(32, 24)[0], 0.2 + peak, tolerance(0.2 + peak, peak));
}

TEST_F(SpecularTest, RoughnessZeroStaysFiniteAfterBloom) {
    SceneDesc scene = make_scene(64, 48, {0, 0, 0, 1});
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(64, 48);
    add_region(scene, f, in, grey(64, 48, 0.5), {{"specular", mask(64, 48, 1)}}, 0, 0);
    scene.floors[f].lights = {{{32.5f, 24.5f}, 1000, {1, 1, 1}, 1.0e6f, 20},
                              {{10, 10}, 100, {1, 1, 1}, 1.0e6f, 0}};
    scene.floors[f].effects = {effect("floors[0].effects[0]", {{"roughness", 0.0}, {"f0", 1.0}})};
    EffectRef bloom;
    bloom.plugin = "acetate.bloom";
    bloom.params = {{"intensity", 4.0}, {"threshold", 0.0}};
    bloom.where = "global_effects[0]";
    scene.global_effects = {bloom};
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    FrameStats stats;
    const ImageRGBA out = render(*compositor, f, &stats);
    ASSERT_EQ(out.width, 64u);
    for (size_t i = 0; i < out.pixels.size(); ++i)
        ASSERT_TRUE(std::isfinite(out.pixels[i]) && out.pixels[i] <= kHalfMax) << i;
    EXPECT_EQ(stats.violations, 0u);
    EXPECT_GT(out.at(32, 24)[0], 60000.0f) << "the peak reaches the cap";
}

TEST_F(SpecularTest, GrazingLightOnePixelHighFiveHundredAwayMatchesTheModel) {
    SceneDesc scene = make_scene(32, 32);
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(32, 32);
    add_region(scene, f, in, grey(32, 32, 0.3), {{"specular", mask(32, 32, 1)}}, 0, 0);
    scene.floors[f].lights = {{{532, 16}, 1000, {1, 1, 1}, 200.0f, 1}};
    Params p;
    p.roughness = 1;
    scene.floors[f].effects = {effect("floors[0].effects[0]", p.json())};
    const ImageRGBA out = floor_target(scene, f);
    EXPECT_GT(expect_model(out, in, scene.floors[f], p), 1e-3) << "a faint, finite highlight";
}

TEST_F(SpecularTest, NormalFacingAwayFromEveryLightAddsNothing) {
    SceneDesc scene = make_scene(48, 32);
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(48, 32);
    auto colour = image(48, 32, [](uint32_t x, uint32_t) {
        const double a = x / 47.0;
        return std::array<double, 4>{0.6 * a, 0.5 * a, 0.4 * a, a};
    });
    // Facing left (-x), nearly horizontal; every light is to the right and low.
    add_region(scene, f, in, colour,
               {{"specular", mask(48, 32, 1)}, {"normal", normal_mask(48, 32, {-1, 0, 0.1})}}, 0,
               0);
    FloorDesc& floor = scene.floors[f];
    floor.lights = {{{100, 16}, 500, {1, 1, 1}, 50.0f, 5}, {{300, 0}, 500, {1, 1, 1}, 50.0f, 2}};
    floor.sun = SunDesc{0, 5, {1, 1, 1}, 10.0f};
    Params p;
    p.roughness = 0.3;
    floor.effects = {effect("floors[0].effects[0]", p.json())};
    const ImageRGBA out = floor_target(scene, f);
    ASSERT_EQ(out.width, 48u);
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 48; ++x) {
            const Vec3 s = specular_term(in, x, y, floor, p);
            ASSERT_EQ(s[0] + s[1] + s[2], 0.0) << "the model agrees: NoL <= 0 for every light";
            ASSERT_EQ(std::memcmp(out.at(x, y), in.colour.at(x, y), 4 * sizeof(float)), 0)
                << "pixel " << x << "," << y << " changed";
        }
}

TEST_F(SpecularTest, SixtyFourLightsOnHdrInputStayFiniteAndCapped) {
    SceneDesc scene = make_scene(64, 32);
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(64, 32);
    // 8x8 blocks: rgb 65504 at alpha 1 and 0.5, 60000, 1000, 1, and transparent.
    auto colour = image(64, 32, [](uint32_t x, uint32_t y) {
        const double values[8] = {65504, 65504, 60000, 1000, 1, 0, 65504, 0.25};
        const double alphas[8] = {1, 0.5, 1, 1, 1, 0, 1, 0.25};
        const int b = int((x / 8 + 4 * (y / 16)) % 8);
        return std::array<double, 4>{values[b], values[b], values[b], alphas[b]};
    });
    add_region(scene, f, in, colour, {{"specular", mask(64, 32, 1)}}, 0, 0);
    FloorDesc& floor = scene.floors[f];
    for (int i = 0; i < 64; ++i)
        floor.lights.push_back({{float(4 + i % 8 * 8), float(4 + i / 8 * 4)},
                                1.0e4f,
                                {1, 1, 1},
                                3.0e38f,
                                float(i % 3)});
    floor.sun = SunDesc{45, 90, {1, 1, 1}, 3.0e38f};
    Params p;
    p.roughness = 0, p.f0 = 1, p.intensity = 8, p.max_points = 64;
    floor.effects = {effect("floors[0].effects[0]", p.json(), "ultra")};
    FrameStats stats;
    const ImageRGBA out = floor_target(scene, f, &stats);
    ASSERT_EQ(out.width, 64u);
    for (size_t i = 0; i < out.pixels.size(); ++i)
        ASSERT_TRUE(std::isfinite(out.pixels[i]) && out.pixels[i] <= kHalfMax) << i;
    expect_model(out, in, floor, p);
    EXPECT_EQ(out.at(20, 4)[0], kHalfMax) << "60000 plus a capped highlight is 65504";
    EXPECT_EQ(stats.violations, 0u);
}

TEST_F(SpecularTest, AlphaRampScalesTheHighlightAndKeepsAlphaBitExact) {
    SceneDesc scene = make_scene(64, 8);
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(64, 8);
    auto colour = image(64, 8, [](uint32_t x, uint32_t) {
        const double a = x / 63.0;
        return std::array<double, 4>{0.25 * a, 0.25 * a, 0.25 * a, a};
    });
    add_region(scene, f, in, colour, {{"specular", mask(64, 8, 1)}}, 0, 0);
    FloorDesc& floor = scene.floors[f];
    floor.sun = SunDesc{0, 75, {1, 1, 1}, 4.0f};  // the same light at every pixel
    Params p;
    p.roughness = 0.5;
    floor.effects = {effect("floors[0].effects[0]", p.json())};
    const ImageRGBA out = floor_target(scene, f);
    expect_model(out, in, floor, p);
    const double full = specular_term(in, 0, 0, floor, p)[0];
    ASSERT_GT(full, 0.05);
    for (uint32_t x = 0; x < 64; ++x) {
        const float* o = out.at(x, 3);
        const float* c = in.colour.at(x, 3);
        ASSERT_EQ(o[3], c[3]) << "alpha at x = " << x;
        if (c[3] == 0) {
            for (int k = 0; k < 3; ++k) ASSERT_EQ(o[k], 0.0f) << "colour at alpha 0";
            continue;
        }
        // The highlight is the same light times alpha: (out - in) / alpha = full.
        EXPECT_NEAR(o[0] - c[0], c[3] * full, tolerance(o[0], c[3] * full)) << "x = " << x;
    }
}

TEST_F(SpecularTest, NormalMaskOnOneOfTwoTilesLeavesTheOtherFlatWithoutASeam) {
    SceneDesc scene = make_scene(64, 32);
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(64, 32);
    auto bumps = image(32, 32, [](uint32_t x, uint32_t y) {
        const Vec3 n = normalized({0.4 * std::sin(x * 0.5), 0.4 * std::cos(y * 0.4), 1});
        return std::array<double, 4>{0.5 + 0.5 * n[0], 0.5 - 0.5 * n[1], 0.5 + 0.5 * n[2], 1};
    });
    add_region(scene, f, in, grey(32, 32, 0.4), {{"specular", mask(32, 32, 1)}, {"normal", bumps}},
               0, 0);
    add_region(scene, f, in, grey(32, 32, 0.4), {{"specular", mask(32, 32, 1)}}, 32, 0);
    FloorDesc& floor = scene.floors[f];
    floor.lights = {{{32, 16}, 200, {1, 1, 1}, 3.0f, 30}};  // above the seam
    Params p;
    p.roughness = 0.3;
    floor.effects = {effect("floors[0].effects[0]", p.json())};
    const ImageRGBA out = floor_target(scene, f);
    EXPECT_GT(expect_model(out, in, floor, p), 0.1);
    // The right tile against a model that has no normal mask at all.
    Inputs flat = in;
    flat.has_normal = false;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 32; x < 64; ++x) {
            const Expected e = expected_at(flat, x, y, floor, p);
            ASSERT_NEAR(out.at(x, y)[0], e.rgb[0], tolerance(e.rgb[0], e.added[0]))
                << "pixel " << x << "," << y << " of the tile without a normal mask";
        }
}

TEST_F(SpecularTest, NoLightsNoSunOrNoSpecularMaskPassTheFloorThroughBitExact) {
    for (int variant = 0; variant < 2; ++variant) {
        SCOPED_TRACE(variant == 0 ? "masks, no lights and no sun" : "lights, no specular mask");
        SceneDesc scene = make_scene(32, 32);
        const uint32_t f = add_floor(scene, "ground");
        Inputs in(32, 32);
        auto colour = image(32, 32, [](uint32_t x, uint32_t y) {
            const double a = (x * 7 + y) % 4 / 3.0;
            return std::array<double, 4>{0.7 * a, 300 * a, 0.1 * a, a};
        });
        std::map<std::string, ImageRGBA> masks = {{"roughness", mask(32, 32, 0.1)},
                                                  {"normal", normal_mask(32, 32, {0.2, 0, 1})}};
        if (variant == 0) masks["specular"] = mask(32, 32, 1);
        add_region(scene, f, in, colour, masks, 0, 0);
        if (variant == 1) {
            scene.floors[f].lights = {{{16, 16}, 100, {1, 1, 1}, 5.0f, 10}};
            scene.floors[f].sun = SunDesc{0, 45, {1, 1, 1}, 2.0f};
        }
        scene.floors[f].effects = {effect("floors[0].effects[0]", {{"roughness", 0.0}})};
        const ImageRGBA out = floor_target(scene, f);
        ASSERT_EQ(out.pixels.size(), in.colour.pixels.size());
        EXPECT_EQ(std::memcmp(out.pixels.data(), in.colour.pixels.data(),
                              out.pixels.size() * sizeof(float)),
                  0);
    }
}

TEST_F(SpecularTest, LowPresetUsesFourLightsAndTheFastVisibility) {
    SceneDesc scene = make_scene(48, 32);
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(48, 32);
    add_region(scene, f, in, grey(48, 32, 0.3),
               {{"specular", mask(48, 32, 0.8)}, {"roughness", mask(48, 32, 0.35)}}, 0, 0);
    FloorDesc& floor = scene.floors[f];
    for (int i = 0; i < 6; ++i)
        floor.lights.push_back({{float(4 + 8 * i), float(6 + 4 * i)}, 40, {1, 1, 1}, 2.0f, 12});
    Params p;
    p.exact = false, p.max_points = 4;
    floor.effects = {effect("floors[0].effects[0]", p.json(), "low")};
    const ImageRGBA out = floor_target(scene, f);
    expect_model(out, in, floor, p);
    // The fifth and sixth lights are not considered: under them, only the first four count.
    Params all = p;
    all.max_points = 6;
    EXPECT_GT(specular_term(in, 44, 26, floor, all)[0],
              specular_term(in, 44, 26, floor, p)[0] + 0.05);
}

TEST_F(SpecularTest, LightingThenSpecularAddsTheSpecularTermToTheLitFloor) {
    SceneDesc scene = make_scene(64, 48);
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(64, 48);
    auto colour = image(64, 48, [](uint32_t x, uint32_t y) {
        const double a = 0.25 + 0.75 * y / 47.0;
        return std::array<double, 4>{0.5 * a, 0.4 * a, 0.3 * (x % 7 ? a : 0), a};
    });
    add_region(scene, f, in, colour,
               {{"specular", mask(64, 48, 0.9)}, {"normal", normal_mask(64, 48, {0.1, 0.2, 1})}}, 0,
               0);
    FloorDesc& floor = scene.floors[f];
    floor.lights = {{{20, 20}, 50, {1, 1, 1}, 2.0f, 10},
                    {{50, 30}, 40, {1, 0.5f, 0.25f}, 3.0f, 20}};
    EffectRef lighting;
    lighting.plugin = "acetate.lighting";
    lighting.params = {{"day", 0.3}, {"day_ambient", 1.0}, {"night_ambient", 0.2}};
    lighting.where = "floors[0].effects[0]";
    Params p;
    p.roughness = 0.3;
    floor.effects = {lighting, effect("floors[0].effects[1]", p.json())};
    const ImageRGBA out = floor_target(scene, f);
    ASSERT_EQ(out.width, 64u);
    const double ambient = 0.2 + (1.0 - 0.2) * 0.3;
    for (uint32_t y = 0; y < 48; y += 2)
        for (uint32_t x = 0; x < 64; x += 2) {
            // acetate.lighting's model: ambient plus (1 - (d/r)^2)^2 in the plane, per colour.
            Vec3 light{ambient, ambient, ambient};
            for (const LightDesc& l : floor.lights) {
                const double d = std::hypot(x + 0.5 - l.pos[0], y + 0.5 - l.pos[1]) / l.radius;
                if (d < 1)
                    for (int c = 0; c < 3; ++c)
                        light[c] += l.color[c] * l.intensity * (1 - d * d) * (1 - d * d);
            }
            const Vec3 s = specular_term(in, x, y, floor, p);
            const float* c = in.colour.at(x, y);
            for (int k = 0; k < 3; ++k) {
                const double lit = c[k] * light[k], added = c[3] * s[k];
                // Two conversions to half: lighting's output, then specular's.
                const double tol = kHalfConversion * lit + tolerance(lit + added, added);
                ASSERT_NEAR(out.at(x, y)[k], lit + added, tol) << x << "," << y << " channel " << k;
            }
        }
}

TEST_F(SpecularTest, OneFloorsLightsNeverReachAnotherFloor) {
    SceneDesc scene = make_scene(64, 32, {0, 0, 0, 1});
    const uint32_t ground = add_floor(scene, "ground");
    const uint32_t upper = add_floor(scene, "upper");
    Inputs ground_in(64, 32), upper_in(64, 32);
    add_region(scene, ground, ground_in, grey(32, 32, 0.3), {{"specular", mask(32, 32, 1)}}, 0, 0);
    add_region(scene, upper, upper_in, grey(32, 32, 0.3), {{"specular", mask(32, 32, 1)}}, 32, 0);
    // Each floor's light hangs over the other floor's tile.
    scene.floors[ground].lights = {{{48, 16}, 60, {1, 1, 1}, 50.0f, 8}};
    scene.floors[upper].lights = {{{16, 16}, 60, {1, 1, 1}, 50.0f, 8}};
    Params p;
    scene.floors[ground].effects = {effect("floors[0].effects[0]", p.json())};
    scene.floors[upper].effects = {effect("floors[1].effects[0]", p.json())};
    EXPECT_GT(expect_model(floor_target(scene, ground), ground_in, scene.floors[ground], p), 0.01);
    EXPECT_GT(expect_model(floor_target(scene, upper), upper_in, scene.floors[upper], p), 0.01);
    // The composite: each half shows its own floor's highlight only.
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = render(*compositor, upper);
    ASSERT_EQ(out.width, 64u);
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            const Expected e = x < 32 ? expected_at(ground_in, x, y, scene.floors[ground], p)
                                      : expected_at(upper_in, x, y, scene.floors[upper], p);
            // Opaque floors over an opaque background: the composite and the output store the
            // floor's half value again, so one conversion remains.
            ASSERT_NEAR(out.at(x, y)[0], e.rgb[0], tolerance(e.rgb[0], e.added[0]))
                << x << "," << y;
        }
}

TEST_F(SpecularTest, SparkleIsSteppedByTimeAndStableAtLargeTimes) {
    SceneDesc scene = make_scene(64, 64);
    const uint32_t f = add_floor(scene, "ground");
    Inputs in(64, 64);
    add_region(scene, f, in, grey(64, 64, 0.2), {{"specular", mask(64, 64, 1)}}, 0, 0);
    scene.floors[f].sun = SunDesc{0, 70, {1, 1, 1}, 4.0f};  // the same highlight everywhere
    Params p;
    nlohmann::json params = p.json();
    params["sparkle"] = 1.0;
    params["sparkle_rate"] = 8;
    scene.floors[f].effects = {effect("floors[0].effects[0]", params)};
    CompositorOptions options;
    options.view = OutputView::FloorRgb;
    auto compositor = load(scene, options);
    ASSERT_TRUE(compositor);
    auto frame = [&](double time) {
        EXPECT_TRUE(compositor->render(f, time).ok());
        auto target = compositor->read_active_floor();
        EXPECT_TRUE(target.ok());
        return target.ok() ? target.value() : ImageRGBA();
    };
    const ImageRGBA a = frame(1.0e5), same_tick = frame(1.0e5 + 0.06), next = frame(1.0e5 + 0.125);
    ASSERT_EQ(a.pixels.size(), same_tick.pixels.size());
    EXPECT_EQ(std::memcmp(a.pixels.data(), same_tick.pixels.data(), a.pixels.size() * 4), 0)
        << "one pattern per 1/8 s, even at 1e5 s";
    EXPECT_GT(max_abs_difference(a, next), 0.01) << "the next step is a new pattern";
    // The factor 1 + (9 u^8 - 1) has mean 1 and standard deviation sqrt(81/17 - 1) = 1.94: the
    // mean over 4096 pixels is within 5 standard errors (5 * 1.94 / 64 = 0.15) of 1.
    const double plain = specular_term(in, 0, 0, scene.floors[f], p)[0];
    double sum = 0;
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) sum += (a.at(x, y)[0] - in.colour.at(x, y)[0]) / plain;
    EXPECT_NEAR(sum / 4096, 1.0, 0.15);
}

}  // namespace
}  // namespace acetate::test
