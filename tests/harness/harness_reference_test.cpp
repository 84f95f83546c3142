// The integration `reference` check (harness/composite_reference.hpp, docs/harness.md): its
// model of an RGBA16F composite, on hand-built floors, accepts both results Vulkan allows
// when a blend overflows (65504 or infinity, and what later blends make of each) and still
// rejects a value a few roundings off; and end to end, drop_shadow, a correct
// coverage-expanding plugin that scales a saturated composite with its shadow's alpha, passes
// `integration/stack-hdr`.

#include <Imath/half.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "composite_reference.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

using ::acetate::test::contains;

namespace fs = std::filesystem;
using harness::blend_over;
using harness::half_rounding;
using harness::PixelReference;
using harness::roundings_off;
using nlohmann::json;
using test::shell_quote;
using Rgba = std::array<float, 4>;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// What a correct saturating GPU holds: the exact "over" of `floors`, each blend rounded to
// half and clamped to the half maximum.
Rgba saturating_gpu(const std::vector<Rgba>& floors) {
    Rgba held{0, 0, 0, 0};
    for (const Rgba& out : floors)
        for (int ch = 0; ch < 4; ++ch) {
            const double v = out[ch] + (1.0 - double(out[3])) * held[ch];
            held[ch] = float(Imath::half(float(std::clamp(v, -65504.0, 65504.0))));
        }
    return held;
}

void put(ImageRGBA& image, uint32_t x, const Rgba& rgba) {
    std::copy(rgba.begin(), rgba.end(), image.at(x, 0));
}

PixelReference model_of(const std::vector<Rgba>& floors) {
    PixelReference pixel;
    for (const Rgba& out : floors) blend_over(pixel, out);
    return pixel;
}

// ---- the model, on one pixel ---------------------------------------------------------------

// Floors 0 and 1 take red past 65504 (65504 + 0.5 * 65504); floor 2 is a drop shadow's black
// at alpha 0.6, which scales what the target holds by 0.4; floor 3 is opaque.
const std::vector<Rgba> kHdrFloors = {
    {65504, 32752, 16376, 1},
    {65504, 32752, 16376, 0.5f},
    {0, 0, 0, 0.6f},
    {0.5f, 0.25f, 0.125f, 1},
};

TEST(CompositeReference, SaturationAtAnIntermediateFloorIsAcceptedAsMaximumOrInfinity) {
    const std::vector<Rgba> three(kHdrFloors.begin(), kHdrFloors.begin() + 3);
    const PixelReference model = model_of(three);
    ASSERT_EQ(model.blends, 3u);
    const double fail = 3;  // one rounding per blend

    // The target saturated at floor 1 and the shadow scaled 65504: red is about 26202.
    const Rgba saturated = saturating_gpu(three);
    EXPECT_NEAR(saturated[0], 0.4 * 65504, 16);
    EXPECT_LE(roundings_off(model, saturated), fail);
    // The target overflowed at floor 1 and the shadow kept the infinity.
    Rgba infinite = saturated;
    infinite[0] = kInf;
    EXPECT_LE(roundings_off(model, infinite), fail);

    // The old reference: no saturation, 0.4 * 98256. No correct half-float target holds it.
    Rgba unsaturated = saturated;
    unsaturated[0] = float(0.4 * (65504 + 0.5 * 65504));
    EXPECT_GT(roundings_off(model, unsaturated), fail);
    // Saturated, but 4 roundings off (a rounding of red is 2^-10 of its peak, 65504).
    Rgba off = saturated;
    off[0] += float(4 * half_rounding(65504));
    EXPECT_GT(roundings_off(model, off), fail);
    // Non-finite values only where the overflow model has them: not in green, nor -inf in red.
    Rgba green = saturated;
    green[1] = kInf;
    EXPECT_EQ(roundings_off(model, green), std::numeric_limits<double>::infinity());
    Rgba negative = saturated;
    negative[0] = -kInf;
    EXPECT_EQ(roundings_off(model, negative), std::numeric_limits<double>::infinity());
}

TEST(CompositeReference, AnOpaqueFloorOverAnInfinityMayGiveNaN) {
    const PixelReference model = model_of(kHdrFloors);
    const double fail = 4;
    // Saturating: the opaque floor replaces 26202 exactly.
    const Rgba saturated = saturating_gpu(kHdrFloors);
    EXPECT_EQ(saturated[0], 0.5f);
    EXPECT_LE(roundings_off(model, saturated), fail);
    // Overflowing: 0.5 + (1 - 1) * inf is NaN in IEEE arithmetic, as in blending hardware.
    Rgba nan = saturated;
    nan[0] = kNaN;
    EXPECT_LE(roundings_off(model, nan), fail);
    // A NaN where nothing overflowed is still wrong.
    Rgba blue = saturated;
    blue[2] = kNaN;
    EXPECT_EQ(roundings_off(model, blue), std::numeric_limits<double>::infinity());
}

TEST(CompositeReference, ThreeRoundingsOffIsRejected) {
    const std::vector<Rgba> floors = {{0.3f, 0.2f, 0.1f, 0.5f}, {0.25f, 0.5f, 0.125f, 0.5f}};
    const PixelReference model = model_of(floors);
    const double fail = 2;  // two blends
    const Rgba exact = saturating_gpu(floors);
    EXPECT_LE(roundings_off(model, exact), 1.0);
    // Red peaked at 0.25 + 0.5 * 0.3 = 0.4.
    const double rounding = half_rounding(0.25 + 0.5 * double(0.3f));
    Rgba one = exact, three = exact;
    one[0] += float(rounding);
    three[0] += float(3 * rounding);
    EXPECT_LE(roundings_off(model, one), fail);
    EXPECT_GT(roundings_off(model, three), fail);
    EXPECT_NEAR(roundings_off(model, three), 3.0, 0.6);  // 3, give or take exact's rounding
}

// ---- whole images: the host's gate ---------------------------------------------------------

TEST(CompositeReference, FloorsAreBlendedOnlyWhereTheHostBlendsThem) {
    // Two pixels. Floor 0 is opaque grey. Floor 1 (preserving) has tiles only at x = 0, and
    // its effect wrote junk at x = 1, which the stencil drops. Floor 2 (expanding) adds a
    // shadow at x = 1 where its input was transparent.
    ImageRGBA in0(2, 1), in1(2, 1), out1(2, 1), in2(2, 1), out2(2, 1);
    for (uint32_t x = 0; x < 2; ++x) put(in0, x, {0.5f, 0.5f, 0.5f, 1});
    put(in1, 0, {0.25f, 0, 0, 0.5f});
    put(out1, 0, {0.25f, 0, 0, 0.5f});
    put(out1, 1, {1, 1, 1, 1});
    put(out2, 1, {0, 0, 0, 0.5f});
    const std::vector<harness::ReferenceFloor> floors = {
        {&in0, &in0, false}, {&in1, &out1, false}, {&in2, &out2, true}};
    const auto model = harness::composite_reference(floors, floors.size());
    ASSERT_EQ(model.size(), 2u);
    EXPECT_EQ(model[0].blends, 2u);  // floors 0 and 1; floor 2 is (0, 0, 0, 0) there
    EXPECT_EQ(model[1].blends, 2u);  // floors 0 and 2
    ImageRGBA composite(2, 1);
    put(composite, 0, {0.5f, 0.25f, 0.25f, 1});
    put(composite, 1, {0.25f, 0.25f, 0.25f, 1});
    auto cmp = harness::compare_to_reference(model, composite, 1.5, 3);
    EXPECT_LE(cmp.worst, 1.5);
    EXPECT_EQ(cmp.fail_pixels, 0u);
    // The junk composited as if the stencil let it through: caught, at x = 1.
    put(composite, 1, {1, 1, 1, 1});
    cmp = harness::compare_to_reference(model, composite, 1.5, 3);
    EXPECT_EQ(cmp.fail_pixels, 1u);
    EXPECT_EQ(cmp.x, 1u);
    EXPECT_EQ(cmp.y, 0u);
}

// ---- end to end: drop_shadow through acetate-harness ---------------------------------------

// Seconds a case may take: one needs 1 to 5 s here, more when the machine is busy.
constexpr int kTimeoutSeconds = 60;

fs::path drop_shadow() {
    return fs::path(ACETATE_HARNESS_PLUGIN_DIR) / "drop_shadow.so";
}

// `acetate-harness validate drop_shadow` in a private folder with its own registry.
test::CommandResult validate(const fs::path& dir, const std::string& args) {
    return test::run_command("cd " + shell_quote(dir.string()) + " && " +
                                 test::harness_environment() + " " +
                                 shell_quote(ACETATE_HARNESS_PATH) + " --registry " +
                                 shell_quote((dir / "registry.json").string()) + " validate " +
                                 shell_quote(drop_shadow().string()) + " --no-signoffs --report " +
                                 shell_quote((dir / "report").string()) + " --jobs 2 --timeout " +
                                 std::to_string(kTimeoutSeconds) + " " + args,
                             dir);
}

json read_report(const fs::path& dir) {
    try {
        return json::parse(test::read_file(dir / "report" / "report.json"));
    } catch (const json::exception& e) {
        ADD_FAILURE() << dir << ": " << e.what();
        return json::object();
    }
}

// The control passes every alpha check, so what the integration cases judge is a correct
// plugin.
TEST(HarnessReference, DropShadowPassesTheAlphaStage) {
    const fs::path dir = test::scratch_dir();
    ASSERT_TRUE(fs::is_regular_file(drop_shadow())) << drop_shadow();
    const test::CommandResult run = validate(dir, "--strictness 1 --stage alpha-tested");
    EXPECT_EQ(run.code, 0) << run.describe();
    EXPECT_TRUE(contains(run.out, "all checks passed")) << run.describe();
}

// Only integration cases are named, so no alpha case runs first (validate.cpp) and the stack
// runs without companions: drop_shadow on floors 1 and 3 over the HDR tiles, whose composite
// passes 65504 before floor 3's shadow scales it.
TEST(HarnessReference, DropShadowPassesTheHdrStack) {
    const fs::path dir = test::scratch_dir();
    ASSERT_TRUE(fs::is_regular_file(drop_shadow())) << drop_shadow();
    const test::CommandResult run =
        validate(dir,
                 "--strictness 5 --stage integrated --case integration/stack-hdr --case "
                 "integration/stack");
    SCOPED_TRACE(run.describe());
    const json report = read_report(dir);
    ASSERT_TRUE(report.contains("cases")) << report.dump(2);
    for (const std::string id : {"integration/stack-hdr", "integration/stack"}) {
        const json* found = nullptr;
        for (const json& c : report["cases"])
            if (c["id"] == id) found = &c;
        ASSERT_NE(found, nullptr) << "no case " << id;
        const json* reference = nullptr;
        for (const json& check : (*found)["checks"])
            if (check["check"] == "reference") reference = &check;
        ASSERT_NE(reference, nullptr) << id << " has no reference check: " << found->dump(2);
        const std::string verdict = (*reference)["verdict"].get<std::string>();
        EXPECT_TRUE(verdict == "PASS" || verdict == "WARN")
            << id << ": " << verdict << ": " << (*reference)["message"];
        EXPECT_TRUE(contains((*reference)["message"].get<std::string>(), "roundings"))
            << (*reference)["message"];
    }
    EXPECT_EQ(run.code, 0);
    EXPECT_TRUE(contains(run.out, "all checks passed"));
}

}  // namespace
}  // namespace acetate
