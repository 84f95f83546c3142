// The sRGB tables (scene/srgb.hpp) against the curve written out here on its own (IEC
// 61966-2-1 in double precision): the 8-bit encoder must give exactly the curve's rounded code
// for every float, and the decoder exactly the curve's value, table or not. Exact equality is
// the claim, so there is no tolerance.
#include "scene/srgb.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

namespace acetate {
namespace {

float reference_encode(float linear) {
    if (linear <= 0.0031308f) return linear * 12.92f;
    return float(1.055 * std::pow(double(linear), 1.0 / 2.4) - 0.055);
}

long reference_code(float linear) {
    return std::lround(reference_encode(linear) * 255.0f);
}

float reference_decode(float encoded) {
    if (encoded <= 0.04045f) return encoded / 12.92f;
    return float(std::pow((double(encoded) + 0.055) / 1.055, 2.4));
}

TEST(Srgb, TheEightBitEncoderGivesTheCurvesCodeForEveryFloatItWasAskedAbout) {
    // Every 61st float between 0 and 1 (17 million floats), both ends, and each float on either
    // side of every place the code changes.
    const uint32_t one = std::bit_cast<uint32_t>(1.0f);
    uint64_t checked = 0;
    for (uint32_t bits = 0; bits <= one; bits += 61) {
        const float x = std::bit_cast<float>(bits);
        ASSERT_EQ(linear_to_srgb8(x), reference_code(x)) << "linear " << x;
        ++checked;
    }
    EXPECT_EQ(linear_to_srgb8(0.0f), 0);
    EXPECT_EQ(linear_to_srgb8(1.0f), 255);
    for (uint32_t bits = 1; bits <= one; ++bits) {
        // Only where the code changes: found by walking the codes, not every float.
        const float x = std::bit_cast<float>(bits);
        const float before = std::bit_cast<float>(bits - 1);
        if (reference_code(x) == reference_code(before)) {
            // Skip ahead: halve the distance to the next change instead of stepping one ulp.
            uint32_t step = 1u << 16;
            while (step > 1 && (bits + step > one || reference_code(std::bit_cast<float>(
                                                         bits + step)) != reference_code(x)))
                step /= 2;
            bits += step - 1;
            continue;
        }
        ASSERT_EQ(linear_to_srgb8(before), reference_code(before)) << "linear " << before;
        ASSERT_EQ(linear_to_srgb8(x), reference_code(x)) << "linear " << x;
        ++checked;
    }
    EXPECT_GT(checked, 17'000'000u);
}

TEST(Srgb, TheDecoderGivesTheCurvesValueForEightBitValuesAndOthers) {
    for (int k = 0; k < 256; ++k) {
        // Both ways of writing k/255 in float: OpenImageIO's (k * (1/255)) and the quotient.
        const float encoded = float(k) * (1.0f / 255.0f);
        EXPECT_EQ(srgb_to_linear(encoded), reference_decode(encoded)) << "k " << k;
        EXPECT_EQ(srgb_to_linear(float(k) / 255.0f), reference_decode(float(k) / 255.0f));
        // A neighbour that is not an 8-bit value is computed, not looked up.
        const float near = std::nextafter(encoded, 2.0f);
        EXPECT_EQ(srgb_to_linear(near), reference_decode(near)) << "k " << k;
    }
    EXPECT_EQ(srgb_to_linear(0.5f), reference_decode(0.5f));
    EXPECT_EQ(srgb_to_linear(1.5f), reference_decode(1.5f));  // out of range: the curve
    EXPECT_EQ(srgb_to_linear(-0.25f), reference_decode(-0.25f));
}

}  // namespace
}  // namespace acetate
