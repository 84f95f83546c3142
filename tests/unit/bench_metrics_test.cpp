// acetate-bench's error metrics (host/scene/image_compare.hpp) by known answers worked out by hand:
// the half-float spacing, the statistics of compare_images (identical images, one rounding at
// 1.0, the subnormals, the top of the half range, NaN, shares at their strict thresholds), the
// heat map's colours and the Pareto front. No GPU needed.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "image_compare.hpp"

namespace acetate::bench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

ImageRGBA filled(uint32_t w, uint32_t h, float value) {
    ImageRGBA image(w, h);
    std::fill(image.pixels.begin(), image.pixels.end(), value);
    return image;
}

ErrorStats compare_ok(const ImageRGBA& test, const ImageRGBA& reference,
                      const ErrorThresholds& thresholds = {}, ImageRGBA* heat = nullptr) {
    Result<ErrorStats> stats = compare_images(test, reference, thresholds, heat);
    EXPECT_TRUE(stats.ok()) << (stats.ok() ? "" : stats.error().message);
    return stats.ok() ? stats.value() : ErrorStats{};
}

TEST(HalfSpacing, FollowsTheBinadeOfTheReference) {
    EXPECT_EQ(half_spacing(1.0), 0x1p-10);
    EXPECT_EQ(half_spacing(1.999), 0x1p-10);
    EXPECT_EQ(half_spacing(2.0), 0x1p-9);
    EXPECT_EQ(half_spacing(0.75), 0x1p-11);
    EXPECT_EQ(half_spacing(-1.5), 0x1p-10);     // the sign does not matter
    EXPECT_EQ(half_spacing(0x1p-14), 0x1p-24);  // the smallest normal half
}

TEST(HalfSpacing, SubnormalsAndTheTopOfTheRange) {
    EXPECT_EQ(half_spacing(0.0), 0x1p-24);
    EXPECT_EQ(half_spacing(0x1p-15), 0x1p-24);
    EXPECT_EQ(half_spacing(0x1p-20), 0x1p-24);
    EXPECT_EQ(half_spacing(32768.0), 32.0);
    EXPECT_EQ(half_spacing(65503.0), 32.0);
    EXPECT_EQ(half_spacing(65504.0), 32.0);
    EXPECT_EQ(half_spacing(1e9), 32.0);
    EXPECT_TRUE(std::isnan(half_spacing(std::nan(""))));
}

TEST(CompareImages, IdenticalImagesHaveNoError) {
    ImageRGBA image(3, 2);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i) * 0.37f - 1.0f;
    const ErrorStats s = compare_ok(image, image);
    EXPECT_EQ(s.pixels, 6u);
    EXPECT_EQ(s.max_roundings, 0);
    EXPECT_EQ(s.max_abs, 0);
    EXPECT_EQ(s.mean_abs, 0);
    EXPECT_EQ(s.psnr_db, kInf);
    EXPECT_EQ(s.warn_share, 0);
    EXPECT_EQ(s.fail_share, 0);
    EXPECT_TRUE(s.finite);
}

TEST(CompareImages, OneRoundingAtOne) {
    // 2x2 of 1.0; one green channel is 1 + 2^-10, one half-float step above 1.0.
    const ImageRGBA reference = filled(2, 2, 1.0f);
    ImageRGBA test = reference;
    test.at(1, 0)[1] = 1.0f + 0x1p-10f;
    const ErrorStats s = compare_ok(test, reference);
    EXPECT_EQ(s.pixels, 4u);
    EXPECT_EQ(s.max_roundings, 1.0);
    EXPECT_EQ(s.max_abs, 0x1p-10);
    // 16 channels, one of them 2^-10 off: mean 2^-14, MSE 2^-20 / 16 = 2^-24,
    // PSNR = 10 log10(2^24) = 240 log10(2) = 72.2471989594... dB.
    EXPECT_EQ(s.mean_abs, 0x1p-14);
    EXPECT_NEAR(s.psnr_db, 72.24719895935549, 1e-9);
    // The difference equals the warn threshold (2^-10) and shares count "strictly greater".
    EXPECT_EQ(s.warn_share, 0);
    EXPECT_EQ(s.fail_share, 0);
    EXPECT_TRUE(s.finite);
}

TEST(CompareImages, RoundingsAreInTheReferencesSpacing) {
    // Just below 1.0 the half spacing is 2^-11, but the unit is the reference's (1.0: 2^-10).
    const ImageRGBA reference = filled(1, 1, 1.0f);
    ImageRGBA test = reference;
    test.pixels[0] = 1.0f - 0x1p-11f;
    EXPECT_EQ(compare_ok(test, reference).max_roundings, 0.5);
}

TEST(CompareImages, SubnormalRange) {
    const ImageRGBA reference = filled(1, 1, 0.0f);
    ImageRGBA test = reference;
    test.pixels[2] = 0x1p-24f;
    ErrorStats s = compare_ok(test, reference);
    EXPECT_EQ(s.max_roundings, 1.0);
    EXPECT_EQ(s.max_abs, 0x1p-24);

    // Three smallest subnormals above 2^-15: still spacing 2^-24.
    const ImageRGBA reference2 = filled(1, 1, 0x1p-15f);
    ImageRGBA test2 = reference2;
    test2.pixels[0] = 0x1p-15f + 3 * 0x1p-24f;
    EXPECT_EQ(compare_ok(test2, reference2).max_roundings, 3.0);
}

TEST(CompareImages, TheLargestHalf) {
    const ImageRGBA reference = filled(1, 1, 65504.0f);
    ImageRGBA test = reference;
    test.pixels[3] = 65504.0f + 64.0f;
    const ErrorStats s = compare_ok(test, reference);
    EXPECT_EQ(s.max_roundings, 2.0);  // 64 / 32
    EXPECT_EQ(s.max_abs, 64.0);
    EXPECT_EQ(s.mean_abs, 16.0);
    EXPECT_NEAR(s.psnr_db, -10.0 * std::log10(64.0 * 64.0 / 4.0), 1e-9);
    EXPECT_EQ(s.warn_share, 1.0);
    EXPECT_EQ(s.fail_share, 1.0);
}

TEST(CompareImages, NaNAndInfinityAreNotFinite) {
    for (float bad : {kNaN, std::numeric_limits<float>::infinity()}) {
        const ImageRGBA reference = filled(2, 2, 0.5f);
        ImageRGBA test = reference;
        test.at(0, 1)[0] = bad;
        const ErrorStats s = compare_ok(test, reference);
        EXPECT_FALSE(s.finite);
        EXPECT_EQ(s.max_abs, kInf);
        EXPECT_EQ(s.max_roundings, kInf);
        EXPECT_EQ(s.mean_abs, kInf);
        EXPECT_EQ(s.psnr_db, -kInf);
        EXPECT_EQ(s.warn_share, 0.25);  // the one pixel of four
        EXPECT_EQ(s.fail_share, 0.25);
    }
}

TEST(CompareImages, ANonFiniteReferenceIsAnError) {
    const ImageRGBA test = filled(2, 2, 0.5f);
    ImageRGBA reference = test;
    reference.at(1, 1)[2] = kNaN;
    const Result<ErrorStats> s = compare_images(test, reference, {});
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("(1, 1)"), std::string::npos) << s.error().message;
}

TEST(CompareImages, SizeMismatchIsAnError) {
    const Result<ErrorStats> s = compare_images(filled(3, 2, 0), filled(2, 3, 0), {});
    ASSERT_FALSE(s.ok());
    const std::string& message = s.error().message;
    EXPECT_NE(message.find("3x2"), std::string::npos) << message;
    EXPECT_NE(message.find("2x3"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(CompareImages, SharesUseThePixelsLargestChannelStrictly) {
    // Thresholds exact in binary so "equal" really is equal.
    const ErrorThresholds thresholds{0.25, 0.5};
    const ImageRGBA reference = filled(6, 1, 0.5f);
    ImageRGBA test = reference;
    test.at(1, 0)[0] += 0.25f;   // = warn: not counted
    test.at(2, 0)[3] += 0.375f;  // over warn only
    test.at(3, 0)[1] -= 0.5f;    // = fail: over warn only
    test.at(4, 0)[0] += 0.125f;  // largest channel 0.75: over both
    test.at(4, 0)[2] += 0.75f;
    for (int c = 0; c < 4; ++c) test.at(5, 0)[c] += 0.2f;  // 0.8 in all, 0.2 at most: neither
    const ErrorStats s = compare_ok(test, reference, thresholds);
    EXPECT_DOUBLE_EQ(s.warn_share, 3.0 / 6.0);
    EXPECT_DOUBLE_EQ(s.fail_share, 1.0 / 6.0);
    EXPECT_EQ(s.max_abs, 0.75);
}

TEST(HeatMap, ColoursFollowTheLogScale) {
    const HeatMapScale& scale = heat_map_scale();
    auto stop = [&](size_t i) {
        return std::array<float, 3>{srgb_to_linear(scale.stops[i][0] / 255.0f),
                                    srgb_to_linear(scale.stops[i][1] / 255.0f),
                                    srgb_to_linear(scale.stops[i][2] / 255.0f)};
    };
    EXPECT_EQ(heat_map_colour(0.0), stop(0));
    EXPECT_EQ(heat_map_colour(1e-9), stop(0));  // below the floor
    EXPECT_EQ(heat_map_colour(1.0), stop(7));
    EXPECT_EQ(heat_map_colour(5.0), stop(7));  // above the ceiling
    // 1e-3 is half way along six decades: half way between stops 3 and 4 of 0..7.
    const std::array<float, 3> mid = heat_map_colour(1e-3);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(mid[c], srgb_to_linear((scale.stops[3][c] + scale.stops[4][c]) / 2.0f / 255.0f),
                    1e-6);
    // Brighter with every decade, so the order reads without colour.
    double previous = -1;
    for (double d = 1e-6; d <= 1.0; d *= 10) {
        const auto rgb = heat_map_colour(d);
        const double luminance = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
        EXPECT_GT(luminance, previous) << d;
        previous = luminance;
    }
}

TEST(HeatMap, CompareImagesFillsIt) {
    const ImageRGBA reference = filled(3, 1, 0.25f);
    ImageRGBA test = reference;
    test.at(1, 0)[0] = 1.25f;  // off by 1
    test.at(2, 0)[1] = kNaN;
    ImageRGBA heat;
    compare_ok(test, reference, {}, &heat);
    ASSERT_EQ(heat.width, 3u);
    ASSERT_EQ(heat.height, 1u);
    const auto& cyan = heat_map_scale().non_finite;
    const std::array<float, 3> expected[] = {
        heat_map_colour(0),
        heat_map_colour(1.0),
        {srgb_to_linear(cyan[0] / 255.0f), srgb_to_linear(cyan[1] / 255.0f),
         srgb_to_linear(cyan[2] / 255.0f)}};
    for (uint32_t x = 0; x < 3; ++x) {
        const float* p = heat.at(x, 0);
        EXPECT_EQ((std::array<float, 3>{p[0], p[1], p[2]}), expected[x]) << x;
        EXPECT_EQ(p[3], 1.0f);
    }
}

TEST(ParetoFront, HandCase) {
    const std::vector<std::pair<double, double>> points = {
        {1, 10},            // fastest but one: on
        {2, 5},             // on
        {2, 6},             // same cost as {2, 5}, more error: off
        {3, 5},             // same error as {2, 5}, slower: off
        {4, 1},             // on
        {4, 1},             // a tie with the one before: both on
        {0.5, 20},          // the fastest: on
        {std::nan(""), 0},  // NaN: never on, dominates nothing
        {5, 0.5},           // on
        {6, 0.5},           // dominated by {5, 0.5}
    };
    const std::vector<bool> expected = {true, true, false, false, true,
                                        true, true, false, true,  false};
    EXPECT_EQ(pareto_front(points), expected);
    EXPECT_TRUE(pareto_front({}).empty());
    EXPECT_EQ(pareto_front({{1, 1}}), std::vector<bool>{true});
}

}  // namespace
}  // namespace acetate::bench
