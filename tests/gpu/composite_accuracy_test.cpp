// Composite accuracy against an independent CPU reference: premultiplied "over" in double
// precision, floor by floor and tile by tile, then over the background.
//
// Tolerance, from the target format: every blend writes its result to the target, rounding it
// once. For RGBA16F one rounding is within one ulp of the value, 2^-10 relative (Vulkan allows
// round-toward-zero as well as to-nearest), or 2^-24 absolute for subnormals; errors carried
// from earlier blends are only scaled by (1 - a) <= 1. So after n roundings the error is at
// most n * (2^-10 * M + 2^-24), M the largest magnitude the pixel's running value reached.
// RGBA32F: the blend's own arithmetic now dominates: 1 - a, the product and the sum each round
// within 2^-24 of the value, so a blend is within 2^-22 relative of the peak. Inputs are quantised
// to the texture format first, exactly as the upload does, so the reference starts from the same
// numbers.

#include <Imath/half.h>

#include <cmath>

#include "render_fixture.hpp"

namespace acetate::test {
namespace {

struct Precision {
    double relative, absolute;
};
constexpr Precision kHalf{1.0 / 1024.0, 1.0 / 16777216.0};
constexpr Precision kFloat{1.0 / 4194304.0, 1e-38};

float quantise(float v, VkFormat format) {
    return format == VK_FORMAT_R16G16B16A16_SFLOAT ? float(Imath::half(v)) : v;
}

// Deterministic pseudo-random numbers (no std::rand: results must not depend on the library).
struct Lcg {
    uint64_t state;
    double next() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) / double(1ull << 53);
    }
};

// A premultiplied image with varied alpha: transparent, opaque and everything between.
ImageRGBA random_premultiplied(uint32_t w, uint32_t h, uint64_t seed, double scale) {
    Lcg rng{seed};
    ImageRGBA image(w, h);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            const double pick = rng.next();
            const double a = pick < 0.15 ? 0.0 : pick > 0.85 ? 1.0 : rng.next();
            float* p = image.at(x, y);
            for (int c = 0; c < 3; ++c) p[c] = float(rng.next() * scale * a);
            p[3] = float(a);
        }
    }
    return image;
}

class CompositeAccuracy : public RenderTest {
  protected:
    // Reference: tiles (integer rects, image size == rect size, so sampling is exact) drawn
    // over a transparent accumulation in order, then over the background. Returns the output
    // and, per pixel, the largest magnitude any intermediate value reached.
    void reference(const SceneDesc& scene, const std::vector<std::vector<ImageRGBA>>& floor_tiles,
                   uint32_t active, VkFormat format, ImageRGBA& out, std::vector<double>& peak) {
        std::vector<double> acc(size_t(scene.width) * scene.height * 4, 0.0);
        peak.assign(size_t(scene.width) * scene.height, 0.0);
        for (uint32_t f = 0; f <= active; ++f) {
            for (size_t t = 0; t < floor_tiles[f].size(); ++t) {
                const ImageRGBA& img = floor_tiles[f][t];
                const SceneRect& r = scene.floors[f].tiles[t].rect;
                for (uint32_t y = 0; y < img.height; ++y) {
                    for (uint32_t x = 0; x < img.width; ++x) {
                        const int64_t cx = int64_t(r.x) + x, cy = int64_t(r.y) + y;
                        if (cx < 0 || cy < 0 || cx >= scene.width || cy >= scene.height) continue;
                        const size_t i = size_t(cy) * scene.width + size_t(cx);
                        double src[4];
                        for (int c = 0; c < 4; ++c) src[c] = quantise(img.at(x, y)[c], format);
                        for (int c = 0; c < 4; ++c) {
                            acc[i * 4 + c] = src[c] + acc[i * 4 + c] * (1.0 - src[3]);
                            peak[i] =
                                std::max({peak[i], std::fabs(acc[i * 4 + c]), std::fabs(src[c])});
                        }
                    }
                }
            }
        }
        out = ImageRGBA(scene.width, scene.height);
        const auto& bg = scene.background;
        for (size_t i = 0; i < peak.size(); ++i) {
            const double a = acc[i * 4 + 3];
            for (int c = 0; c < 3; ++c)
                out.pixels[i * 4 + c] = float(acc[i * 4 + c] + bg[c] * bg[3] * (1 - a));
            out.pixels[i * 4 + 3] = float(a + bg[3] * (1 - a));
            for (int c = 0; c < 4; ++c)
                peak[i] = std::max(peak[i], std::fabs(double(out.pixels[i * 4 + c])));
        }
    }

    // Renders and compares every pixel; `roundings` per pixel bounds the error (see top).
    void expect_matches_reference(const SceneDesc& scene,
                                  const std::vector<std::vector<ImageRGBA>>& tiles,
                                  CompositorOptions options, uint32_t roundings,
                                  const std::string& name) {
        auto compositor = load(scene, options);
        ASSERT_TRUE(compositor);
        FrameStats stats;
        const ImageRGBA actual = render(*compositor, scene.active_floor, &stats);
        ASSERT_EQ(actual.width, scene.width);
        ImageRGBA expected;
        std::vector<double> peak;
        reference(scene, tiles, scene.active_floor, options.format, expected, peak);
        const Precision p = options.format == VK_FORMAT_R16G16B16A16_SFLOAT ? kHalf : kFloat;
        size_t failures = 0;
        double worst_ratio = 0;
        for (size_t i = 0; i < peak.size(); ++i) {
            const double tolerance = roundings * (p.relative * peak[i] + p.absolute);
            for (int c = 0; c < 4; ++c) {
                const double a = actual.pixels[i * 4 + c], e = expected.pixels[i * 4 + c];
                ASSERT_TRUE(std::isfinite(a)) << "non-finite output at pixel " << i;
                const double error = std::fabs(a - e);
                worst_ratio = std::max(worst_ratio, error / tolerance);
                if (error > tolerance && failures++ < 5)
                    ADD_FAILURE() << name << ": pixel " << i % scene.width << "," << i / scene.width
                                  << " channel " << c << ": got " << a << ", reference " << e
                                  << ", tolerance " << tolerance;
            }
        }
        if (failures)
            ADD_FAILURE() << failures << " channel values out of tolerance; images in "
                          << save_failure_images(name, actual, expected);
        RecordProperty("worst_error_over_tolerance", std::to_string(worst_ratio));
        EXPECT_EQ(stats.violations, 0u);
    }
};

TEST_F(CompositeAccuracy, TenFloorsOfPartialAlphaMatchTheReference) {
    SceneDesc scene = make_scene(96, 64, {0.05f, 0.05f, 0.06f, 1.0f});
    std::vector<std::vector<ImageRGBA>> tiles;
    for (uint32_t f = 0; f < 10; ++f) {
        const uint32_t floor = add_floor(scene, "floor" + std::to_string(f));
        // Offset tiles of different sizes so floors overlap partially.
        const uint32_t w = 40 + 5 * f, h = 30 + 3 * f;
        ImageRGBA image = random_premultiplied(w, h, 1000 + f, 4.0);
        add_tile(scene, floor, image, {double(f * 5), double(f * 3), double(w), double(h)});
        tiles.push_back({image});
    }
    // Direct path: one rounding per floor that covers a pixel, plus the output.
    for (VkFormat format : {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT}) {
        CompositorOptions options;
        options.format = format;
        expect_matches_reference(scene, tiles, options, 11, "ten-floors-direct");
        // Through floor targets: tile into the target, then the composite: two per floor.
        options.plan.draw_direct = false;
        expect_matches_reference(scene, tiles, options, 21, "ten-floors-through-target");
    }
}

TEST_F(CompositeAccuracy, AlphaRampsDownTo1Over255And1Over65535) {
    SceneDesc scene = make_scene(256, 4, {0.0f, 0.0f, 0.0f, 0.0f});
    const uint32_t ground = add_floor(scene, "ground");
    ImageRGBA below = solid(256, 4, {0.3f, 0.6f, 0.9f, 1.0f});
    add_tile(scene, ground, below, {0, 0, 256, 4});
    const uint32_t upper = add_floor(scene, "upper");
    ImageRGBA ramp(256, 4);
    for (uint32_t x = 0; x < 256; ++x) {
        const float a255 = x / 255.0f, a65535 = x / 65535.0f;
        const float rows[4] = {a255, a65535, 1.0f / 65535.0f, 1.0f / 255.0f};
        for (uint32_t y = 0; y < 4; ++y) {
            float* p = ramp.at(x, y);
            p[0] = 0.9f * rows[y];
            p[1] = 0.5f * rows[y];
            p[2] = 0.1f * rows[y];
            p[3] = rows[y];
        }
    }
    add_tile(scene, upper, ramp, {0, 0, 256, 4});
    for (VkFormat format : {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT}) {
        CompositorOptions options;
        options.format = format;
        expect_matches_reference(scene, {{below}, {ramp}}, options, 3, "alpha-ramps");
        // And the ramp alone over nothing, where tiny alpha is all there is.
        SceneDesc alone = scene;
        alone.floors.erase(alone.floors.begin());
        alone.active_floor = 0;
        expect_matches_reference(alone, {{ramp}}, options, 2, "alpha-ramps-alone");
    }
}

TEST_F(CompositeAccuracy, ValuesNearTheHalfFloatMaximumStayFinite) {
    SceneDesc scene = make_scene(8, 8, {1.0f, 1.0f, 1.0f, 1.0f});
    const uint32_t ground = add_floor(scene, "ground");
    ImageRGBA hot = solid(8, 8, {65504.0f, 40000.0f, 0.5f, 1.0f});
    add_tile(scene, ground, hot, {0, 0, 8, 8});
    const uint32_t upper = add_floor(scene, "upper");
    // Half-covered: results stay within range (65504 * 0.5 + 30000 = 62752).
    ImageRGBA glow = solid(4, 8, {30000.0f, 60000.0f * 0.5f, 1000.0f, 0.5f});
    add_tile(scene, upper, glow, {2, 0, 4, 8});
    CompositorOptions options;
    expect_matches_reference(scene, {{hot}, {glow}}, options, 3, "half-max");
    options.plan.draw_direct = false;
    expect_matches_reference(scene, {{hot}, {glow}}, options, 5, "half-max-through-target");
}

}  // namespace
}  // namespace acetate::test
