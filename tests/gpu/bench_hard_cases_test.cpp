// acetate-bench's hard-case table (bench/hard_cases.hpp): every case rendered for
// acetate.lighting on the device (lavapipe in CI, validation on), and the markdown's cells.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "hard_cases.hpp"
#include "render/renderer.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::bench {
namespace {

class HardCasesTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        ContextOptions options = ContextOptions::from_environment();
        options.validation = true;
        auto context = VulkanContext::create(options);
        ASSERT_TRUE(context) << context.error().message;
        context_ = std::move(context.value());
        RendererOptions renderer_options;
        renderer_options.plugin_directories.push_back(ACETATE_PLUGIN_DIR);
        auto renderer = Renderer::create(*context_, renderer_options);
        ASSERT_TRUE(renderer) << renderer.error().message;
        renderer_ = std::move(renderer.value());
    }
    static void TearDownTestSuite() {
        renderer_.reset();
        context_.reset();
    }
    void TearDown() override {
        if (!context_) return;
        const auto& messages = context_->validation_messages();
        EXPECT_TRUE(messages.empty()) << "Vulkan validation: " << messages.front();
    }

    static std::unique_ptr<VulkanContext> context_;
    static std::unique_ptr<Renderer> renderer_;
};

std::unique_ptr<VulkanContext> HardCasesTest::context_;
std::unique_ptr<Renderer> HardCasesTest::renderer_;

TEST_F(HardCasesTest, LightingEveryCaseFiniteWithAStatedTolerance) {
    ASSERT_TRUE(renderer_);
    std::vector<std::string> lines;
    auto results = run_hard_cases(*renderer_, {"acetate.lighting"},
                                  [&](const std::string& line) { lines.push_back(line); });
    ASSERT_TRUE(results) << results.error().message;
    ASSERT_EQ(results->size(), hard_case_names().size());
    EXPECT_EQ(lines.size(), hard_case_names().size());
    for (size_t i = 0; i < results->size(); ++i) {
        const HardCaseResult& r = (*results)[i];
        SCOPED_TRACE(r.hard_case);
        EXPECT_EQ(r.plugin, "acetate.lighting");
        EXPECT_EQ(r.hard_case, hard_case_names()[i]);
        EXPECT_TRUE(r.finite);
        EXPECT_TRUE(std::isfinite(r.max_roundings));
        EXPECT_FALSE(r.why.empty());
        EXPECT_GT(r.tolerance, 0.0);
    }
    const std::string markdown = hard_cases_markdown(results.value());
    std::printf("%s", markdown.c_str());
    EXPECT_NE(markdown.find("| acetate.lighting |"), std::string::npos) << markdown;
    for (const std::string& c : hard_case_names())
        EXPECT_NE(markdown.find(c), std::string::npos) << c;
}

TEST_F(HardCasesTest, UnknownPluginIsAnError) {
    ASSERT_TRUE(renderer_);
    auto results = run_hard_cases(*renderer_, {"com.example.nothing"}, nullptr);
    ASSERT_FALSE(results);
    EXPECT_NE(results.error().message.find("com.example.nothing"), std::string::npos);
}

// CPU only from here on.

TEST(HardCasesMarkdown, MarksFailingCells) {
    HardCaseResult good;
    good.plugin = "acetate.lighting";
    good.hard_case = "1x1";
    good.max_roundings = 0.5;
    good.tolerance = 0.5;
    good.why = "one rounding";
    good.pass = true;
    HardCaseResult over = good;
    over.hard_case = "odd 37x23";
    over.max_roundings = 3.25;
    over.pass = false;
    HardCaseResult nan = good;
    nan.hard_case = "colour 65504";
    nan.finite = false;
    nan.max_roundings = std::numeric_limits<double>::infinity();
    nan.pass = false;
    nan.note = "overflows";
    HardCaseResult contract = good;
    contract.hard_case = "alpha 2^-24";
    contract.contract = false;
    contract.pass = false;
    const std::string md = hard_cases_markdown({good, over, nan, contract});
    EXPECT_NE(md.find("✓ 0.50"), std::string::npos) << md;
    EXPECT_NE(md.find("✗ 3.25"), std::string::npos) << md;
    EXPECT_NE(md.find("✗ NaN/inf [1]"), std::string::npos) << md;
    EXPECT_NE(md.find("✗ contract"), std::string::npos) << md;
    EXPECT_NE(md.find("[1] acetate.lighting colour 65504: overflows"), std::string::npos) << md;
    EXPECT_NE(md.find("tolerance 0.50 roundings"), std::string::npos) << md;
    EXPECT_NE(md.find("| acetate.lighting |"), std::string::npos) << md;
}

TEST(HardCasesMetric, RoundingsAtTheLargerOfReferenceAndLevel) {
    ImageRGBA reference(1, 1), test(1, 1);
    reference.pixels = {1.0f, 0.0f, 0.0f, 1.0f};
    test.pixels = {1.0f + 1.0f / 1024.0f, 0.0f, 0.0f, 1.0f};
    EXPECT_DOUBLE_EQ(hard_case_roundings(test, reference, 0.0), 1.0);
    test.pixels = {1.0f, 1.0f / 1024.0f, 0.0f, 1.0f};  // 2^-10 beside a reference of 0
    EXPECT_DOUBLE_EQ(hard_case_roundings(test, reference, 0.0), 0x1p-10 / 0x1p-24);
    EXPECT_DOUBLE_EQ(hard_case_roundings(test, reference, 1.0), 1.0);  // at level 1
    test.pixels[2] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(std::isinf(hard_case_roundings(test, reference, 1.0)));
}

TEST(HardCasesMetric, ContractAndHalfRounding) {
    ImageRGBA image(2, 1);
    image.pixels = {0, 0, 0, 0, 0.5f, 0.25f, 0, 1};
    EXPECT_TRUE(keeps_contract(image));
    image.pixels[1] = 0x1p-24f;
    std::string where;
    EXPECT_FALSE(keeps_contract(image, &where));
    EXPECT_NE(where.find("(0, 0)"), std::string::npos) << where;
    EXPECT_EQ(round_to_half(65504.0f), 65504.0f);
    EXPECT_TRUE(std::isinf(round_to_half(65520.0f)));
    EXPECT_EQ(round_to_half(0x1p-24f), 0x1p-24f);
    EXPECT_EQ(round_to_half(0x1p-25f), 0.0f);  // a tie: to even (0)
    EXPECT_EQ(round_to_half(0x1.8p-25f), 0x1p-24f);
    EXPECT_EQ(round_to_half(1.0f + 0x1p-11f), 1.0f);  // a tie: to even
    EXPECT_EQ(round_to_half(0.9f), 0.89990234375f);
}

}  // namespace
}  // namespace acetate::bench
