// acetate.water's load-time data on the CPU: the linear-time distance transform against brute
// force (tests/support/water_model.hpp) on random shores, at every divisor; and the wave texture's
// promises (it tiles, its caustic pattern has mean 1 and a bound).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "distance_field.hpp"
#include "water_model.hpp"
#include "wave_field.hpp"

namespace acetate::test {
namespace {

using water::build_shore_field;
using water::ShoreField;

// Random blobs of water, sometimes touching the canvas edges.
std::vector<float> random_cover(int width, int height, uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<float> cover(size_t(width) * height, 0.0f);
    for (int blob = 0; blob < 6; ++blob) {
        const double cx = unit(random) * width, cy = unit(random) * height;
        const double r = 1 + unit(random) * std::min(width, height) / 3.0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                if (std::hypot(x + 0.5 - cx, y + 0.5 - cy) < r) cover[size_t(y) * width + x] = 1;
    }
    return cover;
}

TEST(WaterField, ExactTransformMatchesBruteForce) {
    for (uint32_t seed = 1; seed <= 12; ++seed) {
        const int width = 7 + int(seed * 13 % 71), height = 3 + int(seed * 29 % 53);
        const std::vector<float> cover = random_cover(width, height, seed);
        const ShoreField field = build_shore_field(cover, width, height, 1);
        const std::vector<double> exact = water_model::exact_shore_distance(
            std::vector<double>(cover.begin(), cover.end()), width, height);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const double want = std::min(exact[size_t(y) * width + x], 65504.0);
                const bool in_box =
                    x >= field.box.x0 && x < field.box.x1 && y >= field.box.y0 && y < field.box.y1;
                if (!in_box) {
                    ASSERT_EQ(want, 0.0) << "water outside the field's box, seed " << seed;
                    continue;
                }
                const float got =
                    field.distance[size_t(y - field.box.y0) * field.box.width() + x - field.box.x0];
                // Float storage of a distance computed in double: 2^-24 relative.
                ASSERT_NEAR(got, want, want * 1e-6) << x << "," << y << " seed " << seed;
            }
    }
}

TEST(WaterField, CoarserCellsStayWithinACellOfTheExactDistance) {
    const int width = 200, height = 120;
    const std::vector<float> cover = random_cover(width, height, 99);
    const std::vector<double> exact = water_model::exact_shore_distance(
        std::vector<double>(cover.begin(), cover.end()), width, height);
    for (int divisor : {2, 4}) {
        const ShoreField field = build_shore_field(cover, width, height, divisor);
        ASSERT_FALSE(field.empty());
        for (int cy = field.box.y0; cy < field.box.y1; ++cy)
            for (int cx = field.box.x0; cx < field.box.x1; ++cx) {
                const float got = field.distance[size_t(cy - field.box.y0) * field.box.width() +
                                                 cx - field.box.x0];
                if (got <= 0.0f) continue;  // a land cell
                // The cell's centre pixel: its exact distance differs by at most the cell's
                // diagonal (the shore itself moves by up to a cell when cells are averaged).
                const int x = std::min(width - 1, cx * divisor + divisor / 2);
                const int y = std::min(height - 1, cy * divisor + divisor / 2);
                ASSERT_NEAR(got, exact[size_t(y) * width + x], divisor * 1.5)
                    << "divisor " << divisor << " cell " << cx << "," << cy;
            }
    }
}

TEST(WaterField, EdgeCases) {
    // No water: an empty field. All water: the far value (no land, and the border is not land).
    EXPECT_TRUE(build_shore_field(std::vector<float>(12, 0.0f), 4, 3, 1).empty());
    const ShoreField all = build_shore_field(std::vector<float>(12, 1.0f), 4, 3, 1);
    ASSERT_EQ(all.distance.size(), 12u);
    for (float d : all.distance) EXPECT_EQ(d, water::kFarFromShore);
    // One water pixel: half a pixel from the shore on every side.
    std::vector<float> one(25, 0.0f);
    one[12] = 1.0f;
    const ShoreField dot = build_shore_field(one, 5, 5, 1);
    EXPECT_EQ(dot.box.width(), 3);
    EXPECT_EQ(dot.distance[4], 0.5f);
    // Exactly half covered is land: the threshold is strict.
    EXPECT_TRUE(build_shore_field(std::vector<float>(4, 0.5f), 2, 2, 1).empty());
}

TEST(WaterField, WaveTextureTilesAndItsCausticsAreBounded) {
    const std::vector<float> waves = water::build_wave_texture();
    constexpr int n = water::kWaveTexels, side = n + 1;
    ASSERT_EQ(waves.size(), size_t(side) * side * 4);
    double mean = 0;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const float* t = &waves[(size_t(y) * side + x) * 4];
            const float* wrapped = &waves[(size_t(y % n) * side + x % n) * 4];
            for (int c = 0; c < 4; ++c) ASSERT_EQ(t[c], wrapped[c]) << "the last row/column wraps";
            ASSERT_LE(std::hypot(t[0], t[1]), 1.0f + 1e-6f);
            ASSERT_LE(std::abs(t[2]), 1.0f + 1e-6f);
            ASSERT_GE(t[3], 0.0f);
            ASSERT_LE(t[3], water::kMaxCausticDensity);
            if (x < n && y < n) mean += t[3];
        }
    // Caustics move light, they do not add it: a mean of 1 (the cap at 4, applied after the
    // mean is restored, takes under 1% back).
    EXPECT_NEAR(mean / (n * n), 1.0, 0.01);
    EXPECT_EQ(waves, water::build_wave_texture()) << "deterministic";
}

}  // namespace
}  // namespace acetate::test
