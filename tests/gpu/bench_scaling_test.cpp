// acetate-bench --scaling (bench/scaling.hpp): the least-squares cost model on exact synthetic
// data (CPU), and the whole study in its quick form on tiny canvases on the device (lavapipe
// in CI, validation on): every series, pixels shaded growing with floors and canvas, the model
// applied to every point, the markdown.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "render/renderer.hpp"
#include "scaling.hpp"
#include "scene/scene.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::bench {
namespace {

namespace fs = std::filesystem;

ScalingPoint synthetic(uint64_t pixels, uint32_t passes, double fixed_ms, double ns_per_pixel,
                       double ms_per_pass) {
    ScalingPoint p;
    p.series = "synthetic";
    p.pixels_shaded = pixels;
    p.passes = passes;
    p.median_ms = fixed_ms + ns_per_pixel * 1e-6 * double(pixels) + ms_per_pass * double(passes);
    return p;
}

// Pixels and passes that vary apart from each other, as the three series make them.
std::vector<ScalingPoint> synthetic_points(double fixed_ms, double ns_per_pixel,
                                           double ms_per_pass) {
    std::vector<ScalingPoint> points;
    const std::vector<std::pair<uint64_t, uint32_t>> xs = {
        {1'000'000, 6},   {2'500'000, 9},  {5'000'000, 15},  {12'000'000, 27},
        {30'000'000, 51}, {3'000'000, 30}, {8'000'000, 12},  {20'000'000, 40},
        {900'000, 60},    {45'000'000, 8}, {16'000'000, 100}};
    for (auto [pixels, passes] : xs)
        points.push_back(synthetic(pixels, passes, fixed_ms, ns_per_pixel, ms_per_pass));
    return points;
}

TEST(ScalingModel, RecoversExactThreeParameterData) {
    std::vector<ScalingPoint> points = synthetic_points(2.0, 5.0, 0.1);
    const CostModel model = fit_cost_model(points);
    EXPECT_FALSE(model.passes_dropped);
    EXPECT_NEAR(model.fixed_ms, 2.0, 1e-6);
    EXPECT_NEAR(model.ns_per_pixel, 5.0, 1e-6);
    EXPECT_NEAR(model.ms_per_pass, 0.1, 1e-6);
    EXPECT_NEAR(model.r_squared, 1.0, 1e-9);
    EXPECT_EQ(model.fitted_points, points.size());
    // It reproduces the points it was fit on.
    apply_cost_model(model, points);
    for (const ScalingPoint& p : points) {
        EXPECT_NEAR(p.model_ms, p.median_ms, 1e-6 * p.median_ms);
        EXPECT_NEAR(p.residual, 0.0, 1e-6);
    }
    EXPECT_NE(model.formula.find("ns/pixel"), std::string::npos) << model.formula;
    EXPECT_NE(model.formula.find("ms/pass"), std::string::npos) << model.formula;
}

TEST(ScalingModel, DropsPassesWhenTheyCostNothing) {
    // Exact in pixels, passes only noise around zero cost: t is small, the term goes.
    std::vector<ScalingPoint> points = synthetic_points(3.0, 4.0, 0.0);
    const double noise[] = {0.3, -0.2, 0.25, -0.3, 0.1, -0.15, 0.2, -0.1, 0.05, -0.25, 0.3};
    for (size_t i = 0; i < points.size(); ++i) points[i].median_ms += noise[i % 11];
    const CostModel model = fit_cost_model(points);
    EXPECT_TRUE(model.passes_dropped) << "t = " << model.passes_t;
    EXPECT_EQ(model.ms_per_pass, 0.0);
    EXPECT_NEAR(model.ns_per_pixel, 4.0, 0.05);
    EXPECT_EQ(model.formula.find("ms/pass"), std::string::npos) << model.formula;
}

TEST(ScalingModel, PassesCollinearWithPixelsAreDropped) {
    // Every point has passes proportional to pixels: the 3x3 system is singular.
    std::vector<ScalingPoint> points;
    for (uint32_t k = 1; k <= 5; ++k)
        points.push_back(synthetic(k * 1'000'000, k * 3, 1.0, 2.0, 0.5));
    const CostModel model = fit_cost_model(points);
    EXPECT_TRUE(model.passes_dropped);
    EXPECT_EQ(model.passes_t, 0.0);
    apply_cost_model(model, points);
    for (const ScalingPoint& p : points) EXPECT_NEAR(p.residual, 0.0, 1e-9);
}

TEST(ScalingScenes, ParseWithEveryEffect) {
    const fs::path dir =
        fs::temp_directory_path() / ("acetate-scaling-scene-test-" + std::to_string(::getpid()));
    ASSERT_TRUE(write_scaling_assets(dir, 32));
    auto file = write_scaling_scene(dir, "s.json", 160, 90, 3, 5);
    ASSERT_TRUE(file) << file.error().message;
    auto scene = parse_scene_file(file.value());
    ASSERT_TRUE(scene) << scene.error().message;
    EXPECT_EQ(scene->width, 160u);
    EXPECT_EQ(scene->floors.size(), 3u);
    EXPECT_EQ(scene->active_floor, 2u);
    for (const FloorDesc& floor : scene->floors) {
        EXPECT_EQ(floor.tiles.size(), 3u);
        EXPECT_EQ(floor.lights.size(), 4u);
        ASSERT_EQ(floor.effects.size(), 5u);
        for (size_t e = 0; e < 5; ++e)
            EXPECT_EQ(floor.effects[e].plugin, scaling_effect_plugins()[e]);
    }
    EXPECT_FALSE(write_scaling_scene(dir, "t.json", 160, 90, 1, 6));
    const double coverage = scaling_floor_coverage(1920, 1080, 0);
    EXPECT_GT(coverage, 0.5);
    EXPECT_LT(coverage, 0.7);
    std::error_code ec;
    fs::remove_all(dir, ec);
}

class ScalingDeviceTest : public ::testing::Test {
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

std::unique_ptr<VulkanContext> ScalingDeviceTest::context_;
std::unique_ptr<Renderer> ScalingDeviceTest::renderer_;

std::vector<ScalingPoint> series_of(const ScalingResults& r, const std::string& name) {
    std::vector<ScalingPoint> out;
    for (const ScalingPoint& p : r.points)
        if (p.series == name) out.push_back(p);
    return out;
}

TEST_F(ScalingDeviceTest, QuickStudyOnTinyCanvases) {
    ASSERT_TRUE(renderer_);
    ScalingOptions options;
    options.quick = true;
    options.frames = 1;
    std::vector<std::string> lines;
    auto study =
        run_scaling(*renderer_, options, [&](const std::string& line) { lines.push_back(line); });
    ASSERT_TRUE(study) << study.error().message;
    const ScalingResults& r = study.value();

    const auto floors = series_of(r, "floors"), effects = series_of(r, "effects"),
               canvas = series_of(r, "canvas");
    ASSERT_GE(floors.size(), 3u);
    ASSERT_EQ(effects.size(), 6u);
    ASSERT_GE(canvas.size(), 2u);
    EXPECT_EQ(floors.size() + effects.size() + canvas.size(), r.points.size());
    // One progress line per distinct configuration, fewer than the points (shared ones).
    EXPECT_FALSE(lines.empty());
    EXPECT_LT(lines.size(), r.points.size());

    for (const ScalingPoint& p : r.points) {
        SCOPED_TRACE(p.series + " " + std::to_string(p.width) + "x" + std::to_string(p.height) +
                     " floors " + std::to_string(p.floors) + " effects " +
                     std::to_string(p.effects_per_floor));
        EXPECT_GT(p.median_ms, 0.0);
        EXPECT_LE(p.min_ms, p.median_ms);
        EXPECT_GE(p.max_ms, p.median_ms);
        EXPECT_GT(p.pixels_shaded, 0u);
        EXPECT_GT(p.passes, 0u);
        EXPECT_EQ(p.frames, 1u);
        EXPECT_TRUE(std::isfinite(p.model_ms));
        if (p.model_ms > 0) {
            EXPECT_NEAR(p.residual, (p.median_ms - p.model_ms) / p.model_ms, 1e-12);
        }
    }
    for (size_t i = 1; i < floors.size(); ++i) {
        EXPECT_GT(floors[i].floors, floors[i - 1].floors);
        EXPECT_GT(floors[i].pixels_shaded, floors[i - 1].pixels_shaded);
        EXPECT_GT(floors[i].passes, floors[i - 1].passes);
    }
    for (size_t i = 1; i < canvas.size(); ++i) {
        EXPECT_GT(uint64_t(canvas[i].width) * canvas[i].height,
                  uint64_t(canvas[i - 1].width) * canvas[i - 1].height);
        EXPECT_GT(canvas[i].pixels_shaded, canvas[i - 1].pixels_shaded);
    }
    // Each effect adds work: never fewer pixels or passes than one fewer effect.
    for (size_t i = 1; i < effects.size(); ++i) {
        EXPECT_EQ(effects[i].effects_per_floor, uint32_t(i));
        EXPECT_GE(effects[i].pixels_shaded, effects[i - 1].pixels_shaded);
        EXPECT_GT(effects[i].passes, effects[i - 1].passes);
    }
    EXPECT_GT(r.model.fitted_points, 0u);
    EXPECT_FALSE(r.model.formula.empty());
    EXPECT_LE(r.model.r_squared, 1.0 + 1e-12);

    const std::string md = scaling_markdown(r);
    EXPECT_NE(md.find("### Floors"), std::string::npos) << md;
    EXPECT_NE(md.find("### Effects per floor"), std::string::npos) << md;
    EXPECT_NE(md.find("### Canvas"), std::string::npos) << md;
    EXPECT_NE(md.find("R² ="), std::string::npos) << md;
    EXPECT_NE(md.find("worst point"), std::string::npos) << md;
    EXPECT_NE(md.find("64×48"), std::string::npos) << md;
}

}  // namespace
}  // namespace acetate::bench
