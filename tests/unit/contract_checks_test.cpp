// The image contract checked on pairs of images (harness/contract_checks.hpp), directly: each
// check catches a pair that breaks its rule, at the edge the rule draws, and passes the correct
// pair beside it (the control). The battery (tests/harness/) proves the same checks through
// whole plugins; these run in microseconds and name the edge. No device.

#include "contract_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace acetate::harness {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// A 4x3 image with every pixel `rgba`.
ImageRGBA flat(float r, float g, float b, float a) {
    ImageRGBA image(4, 3);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            float* p = image.at(x, y);
            p[0] = r, p[1] = g, p[2] = b, p[3] = a;
        }
    return image;
}

void set(ImageRGBA& image, uint32_t x, uint32_t y, float r, float g, float b, float a) {
    float* p = image.at(x, y);
    p[0] = r, p[1] = g, p[2] = b, p[3] = a;
}

// One check of the five on `input` -> `output` of floor 0.
CheckResult run(void (*check)(const FloorImages&, CheckAccumulator&), const ImageRGBA& input,
                const ImageRGBA& output) {
    CheckAccumulator out("check", "passed");
    check(FloorImages{0, &input, &output}, out);
    return out.finish();
}

CheckResult coverage(const ImageRGBA& input, const ImageRGBA& output, bool expanding) {
    CheckAccumulator out("coverage", "passed");
    check_coverage(FloorImages{0, &input, &output}, expanding, out);
    return out.finish();
}

TEST(ContractChecks, ColourWhereAlphaIsZeroFailsAndItsControlPasses) {
    const ImageRGBA input = flat(0.25f, 0.25f, 0.25f, 0.5f);
    ImageRGBA output = flat(0.25f, 0.25f, 0.25f, 0.5f);
    set(output, 1, 1, 0, 0, 0, 0);  // transparent and black: correct
    EXPECT_EQ(run(check_premultiplied, input, output).verdict, Verdict::Pass);
    set(output, 2, 1, 0.01f, 0, 0, 0);  // colour at alpha 0
    const CheckResult broken = run(check_premultiplied, input, output);
    EXPECT_EQ(broken.verdict, Verdict::Fail);
    EXPECT_EQ(broken.violations, 1u);
    ASSERT_FALSE(broken.examples.empty());
    EXPECT_EQ(broken.examples[0].x, 2);
    EXPECT_EQ(broken.examples[0].y, 1);
}

TEST(ContractChecks, ColourAtZeroAlphaIsJudgedAtTheInputsLargestRatio) {
    // The edge: an effect that halves an alpha of 2^-24 gets 0 in a half target, while the
    // colour it premultiplies, up to rgb/a of the input times larger, survives.
    const ImageRGBA input = flat(1000 * kZeroAlpha, 0, 0, kZeroAlpha);  // rgb/a = 1000
    EXPECT_FLOAT_EQ(colour_at_zero_alpha_tolerance(input), 1000 * kZeroAlpha);
    ImageRGBA output = input;
    set(output, 0, 0, 900 * kZeroAlpha, 0, 0, 0);  // within the ratio
    EXPECT_EQ(run(check_premultiplied, input, output).verdict, Verdict::Pass);
    set(output, 0, 0, 1100 * kZeroAlpha, 0, 0, 0);  // beyond it
    EXPECT_EQ(run(check_premultiplied, input, output).verdict, Verdict::Fail);
}

TEST(ContractChecks, PreservingCoverageIsAlphaBitForBit) {
    const ImageRGBA input = flat(0.2f, 0.2f, 0.2f, 0.5f);
    ImageRGBA output = flat(0.4f, 0.1f, 0.0f, 0.5f);  // colour may change
    EXPECT_EQ(coverage(input, output, false).verdict, Verdict::Pass);
    set(output, 3, 2, 0.4f, 0.1f, 0.0f, std::nextafter(0.5f, 1.0f));  // one ulp more alpha
    const CheckResult broken = coverage(input, output, false);
    EXPECT_EQ(broken.verdict, Verdict::Fail);
    EXPECT_EQ(broken.violations, 1u);
}

TEST(ContractChecks, ExpandingCoverageMayGrowButNeverShrinkOrPassOne) {
    const ImageRGBA input = flat(0.2f, 0.2f, 0.2f, 0.5f);
    ImageRGBA output = flat(0.2f, 0.2f, 0.2f, 0.75f);  // grew: allowed
    EXPECT_EQ(coverage(input, output, true).verdict, Verdict::Pass);
    EXPECT_EQ(coverage(input, output, false).verdict, Verdict::Fail) << "grew, yet preserving";
    ImageRGBA shrunk = output;
    set(shrunk, 0, 0, 0.2f, 0.2f, 0.2f, 0.25f);
    EXPECT_EQ(coverage(input, shrunk, true).verdict, Verdict::Fail);
    ImageRGBA past_one = output;
    set(past_one, 0, 0, 0.2f, 0.2f, 0.2f, std::nextafter(1.0f, 2.0f));
    EXPECT_EQ(coverage(input, past_one, true).verdict, Verdict::Fail);
}

TEST(ContractChecks, OpaqueCoverageStaysOpaque) {
    const ImageRGBA input = flat(0.5f, 0.5f, 0.5f, 1.0f);
    ImageRGBA output = flat(0.9f, 0.5f, 0.1f, 1.0f);
    EXPECT_EQ(run(check_alpha_leak, input, output).verdict, Verdict::Pass);
    set(output, 1, 0, 0.9f, 0.5f, 0.1f, 0.999f);
    EXPECT_EQ(run(check_alpha_leak, input, output).verdict, Verdict::Fail);
}

TEST(ContractChecks, NonFiniteValuesAreReportedOnceByFinite) {
    const ImageRGBA input = flat(0.5f, 0.5f, 0.5f, 1.0f);
    ImageRGBA output = input;
    EXPECT_EQ(run(check_finite, input, output).verdict, Verdict::Pass);
    set(output, 0, 0, kNaN, 0.5f, 0.5f, 1.0f);
    set(output, 1, 0, 0.5f, kInf, 0.5f, 1.0f);
    set(output, 2, 0, 0.5f, 0.5f, 0.5f, -kInf);
    const CheckResult finite = run(check_finite, input, output);
    EXPECT_EQ(finite.verdict, Verdict::Fail);
    EXPECT_EQ(finite.violations, 3u);
    // The others skip non-finite pixels, so one NaN is one failure, not four.
    EXPECT_EQ(run(check_premultiplied, input, output).verdict, Verdict::Pass);
    EXPECT_EQ(run(check_non_negative, input, output).verdict, Verdict::Pass);
    EXPECT_EQ(run(check_alpha_leak, input, output).verdict, Verdict::Pass);
}

TEST(ContractChecks, NegativeChannelsFailAndMinusZeroIsZero) {
    const ImageRGBA input = flat(0.5f, 0.5f, 0.5f, 1.0f);
    ImageRGBA output = flat(0.0f, 0.5f, 0.5f, 1.0f);
    set(output, 0, 0, -0.0f, 0.5f, 0.5f, 1.0f);
    EXPECT_EQ(run(check_non_negative, input, output).verdict, Verdict::Pass);
    set(output, 1, 0, 0.5f, -std::numeric_limits<float>::denorm_min(), 0.5f, 1.0f);
    EXPECT_EQ(run(check_non_negative, input, output).verdict, Verdict::Fail);
}

TEST(ContractChecks, EveryViolationIsCountedButOnlyTheFirstFewKept) {
    const ImageRGBA input = flat(0.5f, 0.5f, 0.5f, 1.0f);
    ImageRGBA output = flat(-0.5f, 0.5f, 0.5f, 1.0f);  // all 12 pixels negative
    const CheckResult result = run(check_non_negative, input, output);
    EXPECT_EQ(result.violations, 12u);
    EXPECT_EQ(result.examples.size(), kMaxExamples);
}

TEST(ContractChecks, ExactComparisonCountsEveryBitThatDiffers) {
    const ImageRGBA a = flat(0.5f, 0.5f, 0.5f, 1.0f);
    ImageRGBA b = a;
    EXPECT_EQ(compare_exact(a, b, 0).pixels, 0u);
    set(b, 3, 2, std::nextafter(0.5f, 1.0f), 0.5f, 0.5f, 1.0f);
    set(b, 0, 0, 0.5f, 0.5f, 0.5f, 1.0f);  // the same
    EXPECT_EQ(compare_exact(a, b, 0).pixels, 1u);
    ImageRGBA nan_a = a, nan_b = a;  // the same NaN bits are the same pixel
    set(nan_a, 1, 1, kNaN, 0, 0, 1);
    set(nan_b, 1, 1, kNaN, 0, 0, 1);
    EXPECT_EQ(compare_exact(nan_a, nan_b, 0).pixels, 0u);
}

}  // namespace
}  // namespace acetate::harness
