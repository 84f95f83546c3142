// acetate.water against an independent CPU model (tests/support/water_model.hpp): the still-water
// tint in double, the foam band against a brute-force distance transform, and the contract on hard
// cases (odd and large canvases, one-pixel ponds, water at the canvas edge, alpha ramps, water
// over transparent pixels, HDR input at the half-float limit, times up to 10^5 s, four floors).

#include <Imath/half.h>
#include <fmt/format.h>

#include <cmath>
#include <cstring>

#include "render_fixture.hpp"
#include "test_files.hpp"
#include "water_model.hpp"

namespace acetate::test {
namespace {

namespace model = water_model;

float half_of(float v) {
    return float(Imath::half(v));
}

// Everything that moves or adds light switched off: what is left is the depth tint and murk.
nlohmann::json still_params() {
    return {{"waves", 0.0},
            {"caustics", 0.0},
            {"foam", 0.0},
            {"glints", 0.0},
            {"shallow_color", {0.9, 0.8, 0.7}},
            {"deep_color", {0.2, 0.45, 0.6}},
            {"murk_color", {0.1, 0.3, 0.35}},
            {"depth_range", 12.0},
            {"murk", 0.5},
            {"ambient", 0.75}};
}
const model::Tint kStillTint{{0.9, 0.8, 0.7}, {0.2, 0.45, 0.6}, {0.1, 0.3, 0.35}, 12.0, 0.5, 0.75};

class WaterTest : public RenderTest {
  protected:
    // A water mask image: cover in r, g and b, alpha 1 (as a one-channel file reads).
    static ImageRGBA mask_image(const std::vector<double>& cover, uint32_t width, uint32_t height) {
        ImageRGBA mask(width, height);
        for (size_t i = 0; i < cover.size(); ++i) {
            float* p = &mask.pixels[i * 4];
            p[0] = p[1] = p[2] = float(cover[i]);
            p[3] = 1.0f;
        }
        return mask;
    }

    // Adds a floor with `tile` stretched over the whole canvas, carrying `cover` (one value per
    // tile pixel) as its water mask when given, and acetate.water with `params` (no effect when
    // params is null).
    uint32_t water_floor(SceneDesc& scene, const ImageRGBA& tile, const std::vector<double>* cover,
                         const nlohmann::json& params, const std::string& preset = "") {
        const uint32_t floor = add_floor(scene, fmt::format("f{}", scene.floors.size()));
        add_tile(scene, floor, tile, {0, 0, double(scene.width), double(scene.height)});
        if (cover)
            scene.floors[floor].tiles[0].masks["water"] =
                write_exr(dir() / fmt::format("water{}.exr", masks_++),
                          mask_image(*cover, tile.width, tile.height));
        if (!params.is_null()) {
            EffectRef ref;
            ref.plugin = "acetate.water";
            ref.params = params;
            ref.preset = preset;
            ref.where = fmt::format("floors[{}].effects[0]", floor);
            scene.floors[floor].effects.push_back(ref);
        }
        return floor;
    }

    int masks_ = 0;  // every mask gets its own file, whatever scene and floor it is for

    // The floor's own pixels after its effects (read back exactly as the GPU holds them).
    ImageRGBA floor_after_effects(Compositor& compositor, uint32_t floor, double time = 0.0) {
        compositor.set_view(OutputView::FloorRgb);  // the floor's whole target is kept
        auto frame = compositor.render(floor, time);
        EXPECT_TRUE(frame.ok()) << (frame.ok() ? "" : frame.error().message);
        EXPECT_EQ(frame.ok() ? frame->violations : 1u, 0u);
        auto image = compositor.read_active_floor();
        EXPECT_TRUE(image.ok());
        return image.ok() ? std::move(image.value()) : ImageRGBA{};
    }

    // The contract on one floor's output: alpha exactly the tile's (as a half), rgb finite,
    // non-negative, at most the half-float limit, and 0 wherever alpha is 0.
    static void expect_contract(const ImageRGBA& out, const ImageRGBA& tile,
                                const std::string& what) {
        ASSERT_EQ(out.width, tile.width) << what;
        ASSERT_EQ(out.height, tile.height) << what;
        for (uint32_t y = 0; y < out.height; ++y)
            for (uint32_t x = 0; x < out.width; ++x) {
                const float* p = out.at(x, y);
                ASSERT_EQ(p[3], half_of(tile.at(x, y)[3])) << what << " alpha at " << x << "," << y;
                for (int c = 0; c < 3; ++c) {
                    ASSERT_TRUE(std::isfinite(p[c]) && p[c] >= 0.0f && p[c] <= 65504.0f)
                        << what << " channel " << c << " at " << x << "," << y << " is " << p[c];
                    if (p[3] == 0.0f) {
                        ASSERT_EQ(p[c], 0.0f) << what << " colour at alpha 0";
                    }
                }
            }
    }
};

// An ellipse of water running off the right and bottom edges, and a one-pixel pond.
std::vector<double> pond_cover(int width, int height) {
    std::vector<double> cover(size_t(width) * height, 0.0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double u = (x + 0.5 - 60) / 35, v = (y + 0.5 - 40) / 22;
            cover[size_t(y) * width + x] = u * u + v * v <= 1.0 ? 1.0 : 0.0;
        }
    cover[size_t(10) * width + 10] = 1.0;
    return cover;
}

TEST_F(WaterTest, StillWaterMatchesTheCpuTintInDouble) {
    constexpr int kW = 96, kH = 64;
    SceneDesc scene = make_scene(kW, kH, {0, 0, 0, 1});
    ImageRGBA tile(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float* p = tile.at(x, y);
            p[0] = 0.2f + 0.6f * float(x) / kW;
            p[1] = 0.5f;
            p[2] = 0.8f - 0.6f * float(y) / kH;
            p[3] = 1.0f;
        }
    // A pond with a soft edge: coverage 0.75 and 0.25 in the two rings around it.
    std::vector<double> cover(size_t(kW) * kH, 0.0);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const double r = std::hypot(x + 0.5 - 40, (y + 0.5 - 30) * 1.3);
            cover[size_t(y) * kW + x] = r < 24 ? 1.0 : r < 25 ? 0.75 : r < 26 ? 0.25 : 0.0;
        }
    const uint32_t floor = water_floor(scene, tile, &cover, still_params());
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = floor_after_effects(*compositor, floor);
    ASSERT_EQ(out.width, uint32_t(kW));
    const std::vector<double> distance = model::exact_shore_distance(cover, kW, kH);
    int water = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const float* in = tile.at(x, y);
            const std::array<double, 4> bed{half_of(in[0]), half_of(in[1]), half_of(in[2]), 1.0};
            const size_t i = size_t(y) * kW + x;
            // The shore field is stored as half floats: the model reads the same rounding.
            const auto expected =
                model::still_water(bed, cover[i], half_of(float(distance[i])), kStillTint);
            water += cover[i] > 0;
            for (int c = 0; c < 3; ++c) {
                // The effect's float result is rounded once to the half-float floor target:
                // half an ulp, 2^-11 relative; twice that covers float's own rounding on the way.
                const double tolerance = std::ldexp(std::abs(expected[c]), -10) + 1e-6;
                ASSERT_NEAR(out.at(x, y)[c], expected[c], tolerance)
                    << "channel " << c << " at " << x << "," << y << " (cover " << cover[i]
                    << ", distance " << distance[i] << ")";
                if (cover[i] == 0) {
                    ASSERT_EQ(out.at(x, y)[c], bed[c]) << "land is copied exactly";
                }
            }
            ASSERT_EQ(out.at(x, y)[3], 1.0f);
        }
    EXPECT_GT(water, 1000);
}

// Waves on, over a bed of one straight colour under an alpha ramp: every refraction tap reads
// the same colour once brought to the pixel's alpha, so the renormalised result must be the
// still-water model of the pixel itself.
TEST_F(WaterTest, RefractionRenormalisesToThePixelsAlpha) {
    constexpr int kW = 96, kH = 64;
    SceneDesc scene = make_scene(kW, kH, {0, 0, 0, 0});
    ImageRGBA tile(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const float a = 0.6f + 0.4f * float(x) / kW;
            float* p = tile.at(x, y);
            p[0] = 0.3f * a, p[1] = 0.6f * a, p[2] = 0.9f * a, p[3] = a;
        }
    const std::vector<double> cover = pond_cover(kW, kH);
    nlohmann::json params = still_params();
    params.update({{"waves", 2.0}, {"refraction", 8.0}});
    const uint32_t floor = water_floor(scene, tile, &cover, params, "ultra");
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = floor_after_effects(*compositor, floor, 0.37);
    ASSERT_EQ(out.width, uint32_t(kW));
    const std::vector<double> distance = model::exact_shore_distance(cover, kW, kH);
    int moved = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const size_t i = size_t(y) * kW + x;
            const float* in = tile.at(x, y);
            const std::array<double, 4> bed{half_of(in[0]), half_of(in[1]), half_of(in[2]),
                                            half_of(in[3])};
            const auto expected =
                model::still_water(bed, cover[i], half_of(float(distance[i])), kStillTint);
            for (int c = 0; c < 3; ++c) {
                // Each tap's colour and alpha are half floats (2^-11 relative each), the ratio
                // brings both, and the output is rounded once more: 2^-9 relative in all.
                ASSERT_NEAR(out.at(x, y)[c], expected[c], std::ldexp(expected[c], -9) + 1e-6)
                    << "channel " << c << " at " << x << "," << y;
            }
            ASSERT_EQ(out.at(x, y)[3], half_of(in[3]));
            moved += cover[i] > 0 && distance[i] > 4;
        }
    EXPECT_GT(moved, 500) << "enough water far enough from the shore for taps to move";
}

TEST_F(WaterTest, FoamBandFollowsTheExactDistanceTransform) {
    constexpr int kW = 80, kH = 56;
    constexpr double kWidth = 6.0;
    SceneDesc scene = make_scene(kW, kH, {0, 0, 0, 1});
    const std::vector<double> cover = pond_cover(kW, kH);
    // No tint and no murk; the bed has no red and the foam is pure red lit by ambient 1, so the
    // output's red is the foam's opacity.
    nlohmann::json params = still_params();
    params.update({{"shallow_color", {1, 1, 1}},
                   {"deep_color", {1, 1, 1}},
                   {"murk", 0.0},
                   {"foam", 1.0},
                   {"foam_width", kWidth},
                   {"foam_breakup", 0.0},
                   {"foam_color", {1, 0, 0}},
                   {"ambient", 1.0}});
    const uint32_t floor = water_floor(scene, solid(kW, kH, {0, 0.5f, 0.2f, 1}), &cover, params);
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = floor_after_effects(*compositor, floor);
    ASSERT_EQ(out.width, uint32_t(kW));
    const std::vector<double> distance = model::exact_shore_distance(cover, kW, kH);
    int inside = 0, outside = 0, inverted = 0, far_on_border = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const size_t i = size_t(y) * kW + x;
            const double foam = out.at(x, y)[0], d = distance[i];
            if (cover[i] == 0) {
                ASSERT_EQ(foam, 0.0) << "foam on land at " << x << "," << y;
                continue;
            }
            // The allowance: the band's edge within 1.5 px of the exact distance.
            if (d < kWidth - 1.5) {
                ASSERT_GT(foam, 0.0) << x << "," << y << " d " << d;
                ++inside;
            }
            if (d > kWidth + 1.5) {
                ASSERT_EQ(foam, 0.0) << x << "," << y << " d " << d;
                ++outside;
                far_on_border += x == kW - 1 || y == kH - 1;
            }
            // Where the profile 1 - smoothstep(0, width, d) can be inverted, the GPU's distance
            // is the exact one, within 0.01 px: the R16F field rounds distances under 8 px by
            // at most 2^-8 px (0.004), and the foam's own half rounding (2^-12 absolute) moves
            // the inverted distance by at most 0.002 px where the profile is this steep.
            if (foam > 0.05 && foam < 0.95) {
                const double gpu_distance = kWidth * model::inverse_smoothstep(1.0 - foam);
                ASSERT_NEAR(gpu_distance, d, 0.01) << "distance at " << x << "," << y;
                ++inverted;
            }
        }
    EXPECT_GT(inside, 100);
    EXPECT_GT(outside, 300);
    EXPECT_GT(inverted, 50);
    EXPECT_GT(far_on_border, 20) << "the pond runs off the canvas with no foam along the border";
    EXPECT_GT(out.at(10, 10)[0], 0.9f) << "a one-pixel pond is all shore";
}

TEST_F(WaterTest, HardCasesKeepTheContract) {
    struct Case {
        uint32_t width, height;
        double time;
        const char* preset;
    };
    // Odd strips, a one-pixel canvas; every feature on, with a light and a sun.
    const Case cases[] = {{1, 517, 0.37, "ultra"},
                          {333, 1, 1e5, "low"},
                          {1, 1, 0.0, "medium"},
                          {61, 47, 1e5, "ultra"}};
    for (const Case& k : cases) {
        const std::string what =
            fmt::format("{}x{} at t = {} ({})", k.width, k.height, k.time, k.preset);
        SceneDesc scene = make_scene(k.width, k.height);
        // Alpha ramps along both axes (so along a strip too) across the shore, with transparent
        // pixels sprinkled in; colour premultiplied.
        ImageRGBA tile(k.width, k.height);
        std::vector<double> cover(size_t(k.width) * k.height);
        for (uint32_t y = 0; y < k.height; ++y)
            for (uint32_t x = 0; x < k.width; ++x) {
                const float a =
                    (x + y) % 7 == 3 ? 0.0f : std::clamp(0.05f + float(x + y) / 20.0f, 0.0f, 1.0f);
                float* p = tile.at(x, y);
                p[0] = 0.6f * a, p[1] = 0.5f * a, p[2] = 0.3f * a, p[3] = a;
                cover[size_t(y) * k.width + x] = (x + y) % 97 < 80 ? 1.0 : 0.0;
            }
        const uint32_t floor = water_floor(scene, tile, &cover, {{"glints", 4.0}}, k.preset);
        LightDesc light{{float(k.width) / 2, float(k.height) / 2}, 300, {1, 0.9f, 0.8f}, 50};
        light.height = 20;
        scene.floors[floor].lights = {light};
        scene.floors[floor].sun = SunDesc{30, 60, {1, 1, 1}, 3};
        auto compositor = load(scene);
        ASSERT_TRUE(compositor) << what;
        expect_contract(floor_after_effects(*compositor, floor, k.time), tile, what);
    }
}

TEST_F(WaterTest, ALargeCanvasStaysFinite) {
    constexpr uint32_t kW = 4096, kH = 2304;
    SceneDesc scene = make_scene(kW, kH);
    // A 64x36 tile and mask stretched over the canvas: a lake of 2300 px with a ragged shore.
    std::vector<double> cover(64 * 36);
    for (int y = 0; y < 36; ++y)
        for (int x = 0; x < 64; ++x)
            cover[size_t(y) * 64 + x] =
                std::hypot(x - 32.0, (y - 18.0) * 1.5) < 27 - (x % 3) ? 1 : 0;
    const uint32_t floor =
        water_floor(scene, solid(64, 36, {0.3f, 0.4f, 0.2f, 1}), &cover, {{"glints", 4.0}}, "high");
    LightDesc light{{2048, 1152}, 900, {1, 1, 1}, 20};
    light.height = 100;
    scene.floors[floor].lights = {light};
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    expect_contract(floor_after_effects(*compositor, floor, 1e5), solid(kW, kH, {0, 0, 0, 1}),
                    "4096x2304");
}

TEST_F(WaterTest, HdrInputAtTheHalfLimitNeverOverflows) {
    constexpr int kW = 48, kH = 32;
    SceneDesc scene = make_scene(kW, kH);
    const ImageRGBA tile = solid(kW, kH, {65504.0f, 60000.0f, 1.0f, 1.0f});
    const std::vector<double> cover(size_t(kW) * kH, 1.0);
    const uint32_t floor = water_floor(
        scene, tile, &cover,
        {{"glints", 4.0}, {"roughness", 0.0}, {"caustics", 1.0}, {"waves", 4.0}, {"foam", 1.0}},
        "ultra");
    std::vector<LightDesc> lights;
    for (int i = 0; i < 64; ++i) {
        LightDesc l{{float(i % 8) * 6, float(i / 8) * 4}, 200, {1, 1, 1}, 1000};
        l.height = float(i % 5);
        lights.push_back(l);
    }
    scene.floors[floor].lights = lights;
    scene.floors[floor].sun = SunDesc{0, 90, {1, 1, 1}, 1000};
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    expect_contract(floor_after_effects(*compositor, floor, 2.0), tile, "HDR");
}

TEST_F(WaterTest, WaterOverTransparentPixelsAddsNothing) {
    constexpr int kW = 40, kH = 24;
    SceneDesc scene = make_scene(kW, kH);
    // Transparent on the left half, opaque on the right; water everywhere.
    ImageRGBA tile(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = kW / 2; x < kW; ++x) {
            float* p = tile.at(x, y);
            p[0] = p[1] = p[2] = 0.4f, p[3] = 1.0f;
        }
    const std::vector<double> cover(size_t(kW) * kH, 1.0);
    const uint32_t floor = water_floor(scene, tile, &cover, {{"glints", 4.0}, {"foam", 1.0}});
    scene.floors[floor].sun = SunDesc{0, 80, {1, 1, 1}, 10};
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA out = floor_after_effects(*compositor, floor, 0.37);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW / 2; ++x)
            for (int c = 0; c < 4; ++c)
                ASSERT_EQ(out.at(x, y)[c], 0.0f) << "transparent pixel " << x << "," << y;
    expect_contract(out, tile, "half transparent");
}

TEST_F(WaterTest, WaterShowsThroughAGapAboveAndNeverOnTheUpperFloor) {
    constexpr int kW = 64, kH = 40;
    SceneDesc scene = make_scene(kW, kH, {0, 0, 0, 1});
    const std::vector<double> cover(size_t(kW) * kH, 1.0);
    const ImageRGBA grey = solid(kW, kH, {0.5f, 0.5f, 0.5f, 1});
    water_floor(scene, grey, &cover, nlohmann::json::object());  // floor 0: water
    // Floor 1: opaque red except a gap in columns 24..39.
    const uint32_t upper = add_floor(scene, "upper");
    add_tile(scene, upper, solid(24, kH, {0.8f, 0.1f, 0.1f, 1}), {0, 0, 24, kH});
    add_tile(scene, upper, solid(24, kH, {0.8f, 0.1f, 0.1f, 1}), {40, 0, 24, kH});
    water_floor(scene, grey, &cover, nlohmann::json::object());  // floor 2: water
    const uint32_t top = add_floor(scene, "top");
    add_tile(scene, top, solid(8, 8, {0, 0, 1, 1}), {0, 0, 8, 8});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    const ImageRGBA from_ground = render(*compositor, 0);
    const ImageRGBA from_upper = render(*compositor, upper);
    ASSERT_EQ(from_upper.width, uint32_t(kW));
    int changed = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const bool gap = x >= 24 && x < 40;
            for (int c = 0; c < 4; ++c) {
                if (gap)
                    ASSERT_EQ(from_upper.at(x, y)[c], from_ground.at(x, y)[c])
                        << "the water of floor 0 through the gap at " << x << "," << y;
                else
                    ASSERT_EQ(from_upper.at(x, y)[c], half_of(c == 0   ? 0.8f
                                                              : c == 3 ? 1.0f
                                                                       : 0.1f))
                        << "floor 1's own pixels, untouched, at " << x << "," << y;
            }
            changed += gap && from_upper.at(x, y)[2] != half_of(0.5f);
        }
    EXPECT_GT(changed, 16 * kH / 2) << "the gap shows water, not the bare grey bed";
}

// Floor 0's water sees only floor 0: lights, a sun and water on the floors above change none
// of its pixels.
TEST_F(WaterTest, AFloorsWaterIgnoresOtherFloorsLightsAndWater) {
    constexpr int kW = 64, kH = 40;
    std::vector<double> cover(size_t(kW) * kH, 0.0);
    for (int y = 6; y < kH - 6; ++y)
        for (int x = 6; x < kW - 6; ++x) cover[size_t(y) * kW + x] = 1.0;
    const ImageRGBA bed = solid(kW, kH, {0.4f, 0.5f, 0.3f, 1});
    const nlohmann::json params = {{"glints", 4.0}, {"foam", 1.0}};
    LightDesc own{{20, 20}, 60, {1, 1, 1}, 3};
    own.height = 15;
    SceneDesc alone = make_scene(kW, kH, {0, 0, 0, 1});
    water_floor(alone, bed, &cover, params);
    alone.floors[0].lights = {own};
    SceneDesc stacked = alone;
    stacked.file = dir() / "stacked.json";
    for (int f = 1; f <= 2; ++f) {
        const uint32_t upper = water_floor(stacked, bed, &cover, params);
        LightDesc bright{{40, 20}, 80, {1, 0.5f, 0.2f}, 40};
        bright.height = 10;
        stacked.floors[upper].lights = {bright};
        stacked.floors[upper].sun = SunDesc{45, 60, {1, 1, 1}, 20};
    }
    auto a = load(alone), b = load(stacked);
    ASSERT_TRUE(a && b);
    const ImageRGBA out_alone = floor_after_effects(*a, 0, 0.37);
    const ImageRGBA out_stacked = floor_after_effects(*b, 0, 0.37);
    ASSERT_EQ(out_alone.pixels.size(), out_stacked.pixels.size());
    EXPECT_EQ(std::memcmp(out_alone.pixels.data(), out_stacked.pixels.data(),
                          out_alone.pixels.size() * sizeof(float)),
              0);
}

TEST_F(WaterTest, AFloorWithoutWaterIsABitExactPassThroughWithNoPass) {
    constexpr int kW = 50, kH = 30;
    ImageRGBA tile(kW, kH);
    for (size_t i = 0; i < tile.pixels.size(); ++i) tile.pixels[i] = float(i % 7) / 7.0f;
    for (size_t i = 3; i < tile.pixels.size(); i += 4) tile.pixels[i] = 1.0f;
    const std::vector<double> empty(size_t(kW) * kH, 0.0);
    for (const std::vector<double>* cover : {(const std::vector<double>*)nullptr, &empty}) {
        const std::string what = cover ? "an empty water mask" : "no water mask";
        SceneDesc bare = make_scene(kW, kH, {0.1f, 0.2f, 0.3f, 1});
        water_floor(bare, tile, cover, nullptr);
        SceneDesc with = make_scene(kW, kH, {0.1f, 0.2f, 0.3f, 1});
        water_floor(with, tile, cover, nlohmann::json::object(), "ultra");
        auto a = load(bare), b = load(with);
        ASSERT_TRUE(a && b);
        FrameStats sa, sb;
        const ImageRGBA out_a = render(*a, 0, &sa), out_b = render(*b, 0, &sb);
        ASSERT_EQ(out_a.pixels.size(), out_b.pixels.size());
        EXPECT_EQ(std::memcmp(out_a.pixels.data(), out_b.pixels.data(),
                              out_a.pixels.size() * sizeof(float)),
                  0)
            << what;
        EXPECT_EQ(sb.passes, sa.passes) << what << ": the instance adds no pass";
        EXPECT_EQ(sb.pixels_shaded, sa.pixels_shaded) << what;
    }
}

TEST_F(WaterTest, SameTimeSamePixelsAndTheWaterMoves) {
    constexpr int kW = 64, kH = 48;
    SceneDesc scene = make_scene(kW, kH, {0, 0, 0, 1});
    std::vector<double> cover(size_t(kW) * kH, 0.0);
    for (int y = 4; y < kH - 4; ++y)
        for (int x = 4; x < kW - 4; ++x) cover[size_t(y) * kW + x] = 1.0;
    ImageRGBA tile(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float* p = tile.at(x, y);
            p[0] = p[1] = p[2] = ((x / 3 + y / 3) % 2) ? 0.8f : 0.2f;  // refraction shows
            p[3] = 1.0f;
        }
    const uint32_t floor = water_floor(scene, tile, &cover, {{"refraction", 6.0}});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    auto at = [&](double t) { return floor_after_effects(*compositor, floor, t); };
    for (double t : {0.0, 0.37, 1e5}) {
        const ImageRGBA a = at(t), b = at(t);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0)
            << "t = " << t << ": the same time gives the same pixels";
    }
    EXPECT_GT(max_abs_difference(at(0.0), at(0.37)), 0.01) << "the water moves with time";
    EXPECT_GT(max_abs_difference(at(1e5), at(1e5 + 0.37)), 0.01) << "and still does at 10^5 s";
}

}  // namespace
}  // namespace acetate::test
